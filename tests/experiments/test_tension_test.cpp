// The virtual direct-tension test on the small bonded specimen of test_cube_test.cpp (~800
// grains of the Van Buren sand, d >= 0.3 mm, 3.6 mm cube): the grips follow their platens
// rigidly, the curve is linear up to the first break, the tensile modulus relates to the
// compression chord modulus as the contact law dictates, homogeneity in the strengths, the
// parallel-bond model's σt < σc with mostly tensile breaks, and bitwise determinism across
// thread counts.
#include <catch2/catch.hpp>
#include <cmath>
#include <cstring>

#include "core/parallel.hpp"
#include "experiments/virtual_tests/affine_estimate.hpp"
#include "experiments/virtual_tests/cube_specimen.hpp"
#include "experiments/virtual_tests/cube_test.hpp"
#include "experiments/virtual_tests/tension_test.hpp"
#include "../with_threads.hpp"
#include "small_specimen.hpp"

using namespace gradem;
using namespace gradem::exp;
using gradem::test::small_material;
using gradem::test::small_packing;

namespace {

TensionTestSpec tension_spec() {
    TensionTestSpec t;
    t.test.loading.strain_rate = 3.0;  // as test_cube_test.cpp: ~1/3 of quasi_static_strain_rate
    return t;
}

const TensionTestResult& base_tension() {
    static const TensionTestResult r = run_tension_test(small_packing(), small_material(), tension_spec());
    return r;
}

// Compression of the same specimen up to a strain well past 2 σt (but before its peak).
const CubeTestResult& early_compression() {
    static const CubeTestResult r = [] {
        CubeTestSpec t = tension_spec().test;
        t.loading.max_strain = 8e-4;
        return run_cube_test(small_packing(), small_material(), t);
    }();
    return r;
}

// Least-squares slope of stress against gauge strain over the points with |gauge strain| <= limit.
double initial_slope(const PlatenTestResult& t, double limit) {
    double n = 0, sx = 0, sy = 0, sxx = 0, sxy = 0;
    for (const CurvePoint& p : t.curve) {
        if (std::fabs(p.gauge_strain) > limit) break;
        n += 1;
        sx += p.gauge_strain;
        sy += p.stress;
        sxx += p.gauge_strain * p.gauge_strain;
        sxy += p.gauge_strain * p.stress;
    }
    REQUIRE(n >= 5);
    return (n * sxy - sx * sy) / (n * sxx - sx * sx);
}

// The chord both moduli are compared with: 30 µε to 40 % of the largest stress recorded.
lab::CurveReduction chord_reduction(const PlatenTestResult& t) {
    lab::ReductionOptions o;
    o.fit_popovics = false;
    o.chord_lower_strain = 30e-6;
    o.strain_window = 15e-6;
    const lab::CurveReduction r = lab::reduce_curve(to_stress_strain_curve(t), o);
    REQUIRE(r.status == lab::ReductionStatus::ok);
    return r;
}

std::int64_t breaks_of(const CurvePoint& p) { return p.broken_tension + p.broken_shear; }

}  // namespace

TEST_CASE("tension: grips follow their platens rigidly at the prescribed speed", "[experiments][tension]") {
    const TensionTestResult& t = base_tension();
    const PlatenTestResult& test = t.cube.test;
    REQUIRE_FALSE(t.diverged());
    CHECK(t.grip_grains_bottom > 20);
    CHECK(t.grip_grains_top > 20);
    CHECK(t.grip_reach < 0.2 * small_packing().edge());  // clear of the gauge slabs
    // Each grip opened by half the platen strain x height; its grains moved by exactly that.
    const double opening = 0.5 * test.curve.back().platen_strain * test.height;
    INFO("grip opening " << opening << " m, largest slip of a grip grain " << t.grip_slip << " m");
    CHECK(opening > 0.0);
    CHECK(t.grip_slip < 1e-6 * opening);
    CHECK(t.grip_spin == 0.0);
    // The opening integrates the prescribed speed: after the half-cosine ramp (which covers half
    // its time at full speed), strain = rate x (t - ramp_time / 2).
    const PlatenTestSpec& loading = tension_spec().test.loading;
    const double ramp_time = loading.ramp_strain / loading.strain_rate;
    const double elapsed = test.curve.back().time - test.curve.front().time;  // the first point is one step in
    REQUIRE(elapsed > ramp_time);
    const CurvePoint& last = test.curve.back();
    const double expected = loading.strain_rate * (elapsed - 0.5 * ramp_time);
    CHECK(last.platen_strain == Approx(expected).epsilon(0.01));
}

TEST_CASE("tension: linear up to the first break, mostly tensile breaks, σt well below σc",
          "[experiments][tension]") {
    const TensionTestResult& t = base_tension();
    const std::vector<CurvePoint>& curve = t.cube.test.curve;
    REQUIRE_FALSE(t.diverged());
    CHECK(t.cube.test.stop_reason == "post-peak");
    REQUIRE(t.cube.macro.status == lab::ReductionStatus::ok);
    const double sigma_t = t.cube.macro.peak_stress_pa;

    // Before the first break the specimen is a linear spring network once the contacts along the
    // axis have opened (stress > 0): a straight line through stress vs gauge strain.
    std::size_t first_break = 0;
    while (first_break < curve.size() && breaks_of(curve[first_break]) == 0) ++first_break;
    REQUIRE(first_break < curve.size());
    const double last_intact = curve[first_break - 1].stress;
    double n = 0, sx = 0, sy = 0, sxx = 0, sxy = 0;
    std::vector<const CurvePoint*> window;
    for (std::size_t k = 0; k < first_break; ++k)
        if (curve[k].stress >= 0.2 * last_intact) window.push_back(&curve[k]);
    REQUIRE(window.size() >= 10);
    for (const CurvePoint* p : window) {
        n += 1;
        sx += p->gauge_strain;
        sy += p->stress;
        sxx += p->gauge_strain * p->gauge_strain;
        sxy += p->gauge_strain * p->stress;
    }
    const double slope = (n * sxy - sx * sy) / (n * sxx - sx * sx), intercept = (sy - slope * sx) / n;
    double worst = 0.0;
    for (const CurvePoint* p : window) worst = std::max(worst, std::fabs(p->stress - (intercept + slope * p->gauge_strain)));
    INFO("first break at " << last_intact * 1e-6 << " MPa (σt " << sigma_t * 1e-6 << " MPa), slope " << slope * 1e-9
                           << " GPa, largest deviation " << worst * 1e-6 << " MPa");
    CHECK(worst < 0.01 * last_intact);
    CHECK(slope == Approx(t.cube.macro.chord_modulus_pa).epsilon(0.03));

    // Parallel bonds under tension break in tension.
    std::size_t tensile = 0;
    for (const BreakEvent& e : t.cube.cracks) tensile += e.mode == BondState::broken_tension;
    INFO(tensile << " of " << t.cube.cracks.size() << " breaks in tension");
    CHECK(t.cube.cracks.size() > 50);
    CHECK(tensile >= 0.9 * static_cast<double>(t.cube.cracks.size()));

    // The compression curve passes 2 σt long before its peak (σc >= the largest stress seen).
    const CubeTestResult& c = early_compression();
    double largest = 0.0;
    for (const CurvePoint& p : c.test.curve) largest = std::max(largest, p.stress);
    INFO("compression reaches " << largest * 1e-6 << " MPa by strain " << c.test.curve.back().platen_strain);
    CHECK(largest > 2.0 * sigma_t);
}

TEST_CASE("tension vs compression modulus: equal while the contacts hold, bond-dominated after",
          "[experiments][tension][modulus]") {
    const TensionTestResult& t = base_tension();
    const CubeTestResult& c = early_compression();
    // Small strain (|ε| <= 3 µε): no contact has opened or closed yet, the network is the same
    // linear system loaded in opposite directions, so the slopes agree.
    const double slope_t = initial_slope(t.cube.test, 3e-6), slope_c = initial_slope(c.test, 3e-6);
    INFO("initial slopes: tension " << slope_t * 1e-9 << " GPa, compression " << slope_c * 1e-9 << " GPa");
    CHECK(slope_t == Approx(slope_c).epsilon(0.05));

    // Beyond, the contacts along the axis open in tension (bonds only) and stay shut in
    // compression (bond + contact): the tensile chord drops towards the bond-only affine share.
    const double e_t = chord_reduction(t.cube.test).chord_modulus_pa, e_c = chord_reduction(c.test).chord_modulus_pa;
    MaterialParams bonds_only = small_material();
    bonds_only.contact.effective_modulus *= 1e-6;
    const double share = affine_moduli(small_packing(), bonds_only).youngs / affine_moduli(small_packing(), small_material()).youngs;
    INFO("chord moduli: tension " << e_t * 1e-9 << " GPa, compression " << e_c * 1e-9 << " GPa, ratio " << e_t / e_c
                                  << ", affine bond-only share " << share);
    CHECK(e_t < 0.85 * e_c);
    CHECK(e_t / e_c == Approx(share).margin(0.15));

    // Contacts carry no tension: 100 x softer contacts hardly change the tensile modulus (the
    // affine estimate with contacts would drop by 1 - share).
    MaterialParams soft = small_material();
    soft.contact.effective_modulus *= 0.01;
    TensionTestSpec early = tension_spec();
    early.test.loading.max_strain = 1.5e-4;
    const double e_soft = chord_reduction(run_tension_test(small_packing(), soft, early).cube.test).chord_modulus_pa;
    INFO("tensile chord with 100 x softer contacts " << e_soft * 1e-9 << " GPa");
    CHECK(e_soft / e_t == Approx(1.0).margin(0.1));
}

TEST_CASE("tension homogeneity: strengths x 2 -> σt x 2, strain at peak x 2, same modulus",
          "[experiments][tension][homogeneity]") {
    const TensionTestResult& base = base_tension();
    const TensionTestResult strong = run_tension_test(small_packing(), small_material(1.0, 2.0), tension_spec());
    REQUIRE(strong.cube.macro.status == lab::ReductionStatus::ok);
    const lab::CurveReduction &a = base.cube.macro, &b = strong.cube.macro;
    CHECK(b.peak_stress_pa / a.peak_stress_pa == Approx(2.0).epsilon(0.05));
    CHECK(b.strain_at_peak / a.strain_at_peak == Approx(2.0).epsilon(0.07));
    CHECK(b.chord_modulus_pa / a.chord_modulus_pa == Approx(1.0).epsilon(0.03));
}

TEST_CASE("tension: bitwise-identical curves with 1 and 2 threads", "[experiments][tension][determinism]") {
    TensionTestSpec t = tension_spec();
    t.test.loading.max_strain = 2.5e-4;  // through the first breaks, before the peak
    auto run = [&] { return run_tension_test(small_packing(), small_material(), t); };
    const TensionTestResult one = test::with_threads(1, run);
    const TensionTestResult two = test::with_threads(2, run);
    REQUIRE(one.cube.test.curve.size() == two.cube.test.curve.size());
    REQUIRE_FALSE(one.cube.cracks.empty());
    CHECK(one.cube.cracks.size() == two.cube.cracks.size());
    for (std::size_t k = 0; k < one.cube.test.curve.size(); ++k) {
        const CurvePoint &a = one.cube.test.curve[k], &b = two.cube.test.curve[k];
        CHECK(std::memcmp(&a.stress, &b.stress, sizeof(double)) == 0);
        CHECK(std::memcmp(&a.gauge_strain, &b.gauge_strain, sizeof(double)) == 0);
        CHECK(std::memcmp(&a.platen_strain, &b.platen_strain, sizeof(double)) == 0);
    }
}
