// The stop rules of the axial loading (experiments/virtual_tests/axial_loading.hpp) on a
// prescribed curve: a frame whose measured stress is a known function of the platen strain, so
// where each rule stops, and which peak it keeps, is exact. The World is two free spheres
// that never touch: it only keeps time.
#include <catch2/catch.hpp>
#include <algorithm>
#include <cmath>
#include <functional>

#include "experiments/virtual_tests/axial_loading.hpp"

using namespace gradem;
using namespace gradem::exp;

namespace {

constexpr double kStep = 1e-6;    // [s] fixed time step
constexpr double kRate = 1.0;     // [1/s]: a strain of 1e-6 per step, 5e-5 per curve point
constexpr double kHeight = 1.0;   // [m]

using StressOfStrain = std::function<double(double)>;  // [Pa] of platen strain [-]

/// A plateau curve: linear to 20 MPa at a strain of 2e-3, then within 2 % under it up to
/// 3.4e-3, then up to a second, higher maximum of 20.2 MPa at 3.6e-3 (1.8 x the first peak's
/// strain), then down by 20.2 MPa per 1e-3 of strain.
double plateau_curve(double e) {
    constexpr double kPi = 3.14159265358979323846;
    if (e <= 2e-3) return 1e10 * e;
    if (e <= 3.4e-3) return 20e6 * (1.0 - 0.02 * std::sin(kPi * (e - 2e-3) / 1.4e-3));
    if (e <= 3.6e-3) return 20e6 + 0.2e6 * (e - 3.4e-3) / 0.2e-3;
    return 20.2e6 * (1.0 - (e - 3.6e-3) / 1e-3);
}

/// The extensometer's strain of a platen strain [-] (the gauges see the platen strain, by default).
using GaugeOfPlaten = std::function<double(double)>;

PlatenTestResult run_on(const StressOfStrain& stress, double stop_strain_ratio,
                        const GaugeOfPlaten& gauge = [](double e) { return e; }) {
    ParticleSet p;
    p.add({0, 0, 0}, 1e-3, 2650.0);
    p.add({1, 0, 0}, 1e-3, 2650.0);
    World world(std::move(p), ContactParams{}, SimParams{});
    world.set_time_step(kStep);
    double travel = 0.0;  // [m] both ends together
    AxialFrame frame;
    frame.height = kHeight;
    frame.area = 1.0;
    frame.drive = [&travel](World&, double speed) { travel += 2.0 * speed * kStep; };
    frame.measure = [&travel, &stress, &gauge](const World&, CurvePoint& pt) {
        pt.platen_strain = travel / kHeight;
        pt.gauge_strain = gauge(pt.platen_strain);
        pt.stress_top = pt.stress_bottom = stress(pt.platen_strain);
    };
    PlatenTestSpec spec;
    spec.strain_rate = kRate;
    spec.stop_strain_ratio = stop_strain_ratio;
    return run_axial_loading(world, spec, frame);
}

bool same_points(const PlatenTestResult& a, const PlatenTestResult& b, std::size_t n) {
    if (a.curve.size() < n || b.curve.size() < n) return false;
    for (std::size_t i = 0; i < n; ++i)
        if (a.curve[i].platen_strain != b.curve[i].platen_strain || a.curve[i].stress != b.curve[i].stress) return false;
    return true;
}

}  // namespace

TEST_CASE("strain stop: off, the plateau is followed to the later maximum and down to stop_fraction", "[experiments][loading]") {
    const PlatenTestResult r = run_on(plateau_curve, 0.0);
    CHECK(r.stop_reason == "post-peak");
    CHECK(r.peak_stress == Approx(20.2e6).epsilon(1e-3));
    CHECK(r.strain_at_peak == Approx(3.6e-3).epsilon(0.02));
    CHECK(r.curve.back().stress < 0.7 * r.peak_stress);
}

TEST_CASE("strain stop above what the curve needs: the same peak and the same curve as without it", "[experiments][loading]") {
    const PlatenTestResult off = run_on(plateau_curve, 0.0), loose = run_on(plateau_curve, 2.0);
    CHECK(loose.stop_reason == "post-peak");  // 2 x 3.6e-3 lies beyond the fall to 0.7 x the peak
    CHECK(loose.peak_stress == off.peak_stress);
    CHECK(loose.strain_at_peak == off.strain_at_peak);
    CHECK(loose.curve.size() == off.curve.size());
    CHECK(same_points(loose, off, off.curve.size()));
}

TEST_CASE("strain stop under what the curve needs: ends on the plateau at ratio x the first peak's strain", "[experiments][loading]") {
    const PlatenTestResult off = run_on(plateau_curve, 0.0), tight = run_on(plateau_curve, 1.5);
    CHECK(tight.stop_reason == "post-peak strain");
    // The first peak, not the later maximum at 1.8 x its strain, which this ratio misses.
    CHECK(tight.peak_stress == Approx(20e6).epsilon(1e-3));
    CHECK(tight.strain_at_peak == Approx(2e-3).epsilon(0.03));
    const double end = tight.curve.back().platen_strain;
    CHECK(end > 1.5 * tight.strain_at_peak);
    CHECK(tight.curve[tight.curve.size() - 2].platen_strain <= 1.5 * tight.strain_at_peak);  // the first point past it
    CHECK(tight.curve.back().stress > 0.97 * tight.peak_stress);  // on the plateau: stop_fraction would not have ended it
    CHECK(tight.curve.size() < off.curve.size());
    CHECK(same_points(tight, off, tight.curve.size()));  // what it recorded is the run without the stop, cut short
}

TEST_CASE("strain stop: counted on the gauge strain the curve is reduced on, the platen strain without gauges",
          "[experiments][loading]") {
    // Gauges that miss the first 5e-4 of the platen travel (the platens' seating): the peak at a
    // platen strain of 2e-3 is at 1.5e-3 on the gauges, so 1.5 x it is passed at a platen strain
    // of 2.75e-3; without gauges (NaN) at 3e-3.
    const PlatenTestResult seated = run_on(plateau_curve, 1.5, [](double e) { return e - 5e-4; });
    const PlatenTestResult plain = run_on(plateau_curve, 1.5, [](double) { return std::nan(""); });
    CHECK(seated.stop_reason == "post-peak strain");
    CHECK(plain.stop_reason == "post-peak strain");
    CHECK(seated.curve.back().platen_strain == Approx(2.75e-3).margin(6e-5));
    CHECK(plain.curve.back().platen_strain == Approx(3.0e-3).margin(6e-5));
    CHECK(seated.peak_stress == plain.peak_stress);
}

TEST_CASE("strain stop: a maximum inside the ramp is the seating's and does not start it", "[experiments][loading]") {
    // 1 MPa at 1e-4 (inside the 2e-4 ramp), a dip to 0.9 MPa held to 1e-3, then the plateau curve
    // shifted past it: a strain stop counted from the seating maximum would end the test at 1.3e-4.
    const StressOfStrain seated = [](double e) {
        if (e <= 1e-4) return 1e10 * e;
        if (e <= 1e-3) return 0.9e6;
        return std::max(0.9e6, plateau_curve(e - 1e-3));
    };
    const PlatenTestResult r = run_on(seated, 1.3);
    CHECK(r.stop_reason == "post-peak strain");
    CHECK(r.peak_stress == Approx(20e6).epsilon(1e-3));
    CHECK(r.strain_at_peak == Approx(3e-3).epsilon(0.03));
    CHECK(r.curve.back().platen_strain > 1.3 * r.strain_at_peak);
}

TEST_CASE("strain stop: a ratio at or under 1 is refused, naming the field", "[experiments][loading]") {
    PlatenTestSpec spec;
    CHECK_FALSE(spec.invalid_reason());
    spec.stop_strain_ratio = 1.0;
    REQUIRE(spec.invalid_reason());
    CHECK(*spec.invalid_reason() == "PlatenTestSpec::stop_strain_ratio = 1 violates 0 (off) or > 1");
    spec.stop_strain_ratio = 0.5;
    CHECK(spec.invalid_reason());
    spec.stop_strain_ratio = 1.5;
    CHECK_FALSE(spec.invalid_reason());
}
