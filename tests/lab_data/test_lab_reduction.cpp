// reduce_curve against analytic curves: Popovics ascending branch (Popovics 1973) with a steeper
// Thorenfeldt-type descending branch, sampled with noise; oracles computed from the law here.
#include <catch2/catch.hpp>

#include <cmath>
#include <random>

#include "lab_data/curve_reduction.hpp"
#include "lab_data/popovics.hpp"

using namespace gradem::lab;

namespace {

struct Law {
    double fc = 21e6, eps_c = 0.0030, e0 = 12e9, k = 1.6;
    [[nodiscard]] double n() const { return e0 / (e0 - fc / eps_c); }
    [[nodiscard]] double stress(double eps) const {
        const double x = eps / eps_c;
        return fc * n() * x / (n() - 1 + std::pow(x, x <= 1 ? n() : n() * k));
    }
    [[nodiscard]] double slope(double eps) const {  // dσ/dε on the ascending branch
        const double x = eps / eps_c, d = n() - 1 + std::pow(x, n());
        return fc / eps_c * n() * (n() - 1 + (1 - n()) * std::pow(x, n())) / (d * d);
    }
    [[nodiscard]] double strain_at(double stress_pa) const {  // ascending branch, by bisection
        double lo = 0, hi = eps_c;
        for (int i = 0; i < 200; ++i) ((stress((lo + hi) / 2) < stress_pa) ? lo : hi) = (lo + hi) / 2;
        return (lo + hi) / 2;
    }
    [[nodiscard]] double c469_chord() const {
        const double s2 = 0.4 * fc;
        return (s2 - stress(50e-6)) / (strain_at(s2) - 50e-6);
    }
};

StressStrainCurve sample(const Law& law, double stress_noise_pa, double strain_noise, unsigned seed = 42) {
    std::mt19937 rng(seed);
    std::normal_distribution<double> ds(0.0, stress_noise_pa), de(0.0, strain_noise);
    StressStrainCurve c;
    for (double eps = 0; eps <= 1.5 * law.eps_c; eps += 10e-6) {
        c.strain.push_back(eps + de(rng));
        c.stress_pa.push_back(law.stress(eps) + ds(rng));
        c.crosshead_strain.push_back(2.5 * eps);
        c.time_s.push_back(eps / 1e-4);  // 1e-4 strain per second
    }
    return c;
}

}  // namespace

TEST_CASE("lab: analytic curve with noise: peak within 0.5 % chord modulus within 2 %", "[lab][reduction]") {
    const Law law;
    // Noise: 0.1 % of peak on stress (load cell), 2 microstrain on the extensometer.
    const CurveReduction r = reduce_curve(sample(law, 0.001 * law.fc, 2e-6));
    REQUIRE(r.status == ReductionStatus::ok);
    CHECK(r.peak_stress_pa == Approx(law.fc).epsilon(0.005));
    CHECK(r.strain_at_peak == Approx(law.eps_c).epsilon(0.02));
    CHECK(r.chord_modulus_pa == Approx(law.c469_chord()).epsilon(0.02));
    CHECK(r.chord_s2_pa == Approx(0.4 * r.peak_stress_pa));
    CHECK(r.tangent_modulus_pa == Approx(law.slope(law.strain_at(0.5 * law.fc))).epsilon(0.03));
    CHECK(r.strain_at_peak_crosshead == Approx(2.5 * law.eps_c).epsilon(0.02));
    CHECK(r.stress_rate_pa_per_s > 0);
}

TEST_CASE("lab: Popovics fit recovers E f'c and eps'c with small standard errors", "[lab][reduction][popovics]") {
    const Law law;
    const CurveReduction r = reduce_curve(sample(law, 0.001 * law.fc, 2e-6));
    const PopovicsFit& p = r.popovics;
    REQUIRE(p.converged);
    CHECK(p.elastic_modulus_pa == Approx(law.e0).epsilon(0.02));
    CHECK(p.peak_stress_pa == Approx(law.fc).epsilon(0.005));
    CHECK(p.strain_at_peak == Approx(law.eps_c).epsilon(0.02));
    CHECK(p.n == Approx(law.n()).epsilon(0.05));
    CHECK(p.elastic_modulus_se_pa > 0);
    CHECK(p.elastic_modulus_se_pa < 0.01 * p.elastic_modulus_pa);
    CHECK(p.peak_stress_se_pa < 0.005 * p.peak_stress_pa);
    CHECK(p.rms_residual_pa == Approx(0.001 * law.fc).epsilon(0.3));  // the noise we added
    CHECK(popovics_stress(law.eps_c, law.fc, law.eps_c, law.e0) == Approx(law.fc));
}

TEST_CASE("lab: a linear-elastic curve has chord = tangent = E exactly", "[lab][reduction]") {
    StressStrainCurve c;
    const double e = 10e9;
    for (int i = 0; i <= 300; ++i) { c.strain.push_back(i * 1e-5); c.stress_pa.push_back(e * i * 1e-5); }
    for (int i = 1; i <= 20; ++i) { c.strain.push_back(3e-3 + i * 1e-5); c.stress_pa.push_back(30e6 - i * 1e6); }
    ReductionOptions o;
    o.fit_popovics = false;
    const CurveReduction r = reduce_curve(c, o);
    REQUIRE(r.status == ReductionStatus::ok);
    CHECK(r.peak_stress_pa == Approx(30e6));
    CHECK(r.strain_at_peak == Approx(3e-3));
    CHECK(r.chord_modulus_pa == Approx(e));
    CHECK(r.tangent_modulus_pa == Approx(e));
    CHECK(std::isnan(r.strain_at_peak_crosshead));
    CHECK(std::isnan(r.poisson_ratio));
}

TEST_CASE("lab: Poisson's ratio from a lateral strain channel (ASTM C469)", "[lab][reduction]") {
    StressStrainCurve c;
    for (int i = 0; i <= 300; ++i) {
        c.strain.push_back(i * 1e-5);
        c.stress_pa.push_back(10e9 * i * 1e-5);
        c.lateral_strain.push_back(-0.2 * i * 1e-5);
    }
    ReductionOptions o;
    o.fit_popovics = false;
    CHECK(reduce_curve(c, o).poisson_ratio == Approx(0.2));
}

TEST_CASE("lab: a modulus window the curve never reaches is reported not guessed", "[lab][reduction][errors]") {
    StressStrainCurve c;  // very stiff: 40 % of peak is reached at 40 microstrain, before ε1
    for (int i = 0; i <= 150; ++i) { c.strain.push_back(i * 1e-6); c.stress_pa.push_back(std::min(1.0, i / 100.0) * 10e6); }
    const CurveReduction r = reduce_curve(c);
    CHECK(r.status == ReductionStatus::modulus_window_not_reached);
    CHECK_THAT(r.message, Catch::Contains("chord window is empty"));
    CHECK(std::isnan(r.chord_modulus_pa));
    CHECK(r.peak_stress_pa == Approx(10e6));  // what could be computed still is

    StressStrainCurve tiny;  // strain never reaches 50 microstrain
    for (int i = 0; i <= 20; ++i) { tiny.strain.push_back(i * 1e-6); tiny.stress_pa.push_back(i * 1e5); }
    const CurveReduction t = reduce_curve(tiny);
    CHECK(t.status == ReductionStatus::modulus_window_not_reached);
    CHECK_THAT(t.message, Catch::Contains("never reaches the lower chord strain"));
}

TEST_CASE("lab: invalid curves and options", "[lab][reduction][errors]") {
    StressStrainCurve c;
    c.strain = {0, 1, 2};
    c.stress_pa = {0, 1};
    CHECK(reduce_curve(c).status == ReductionStatus::invalid_curve);
    c.stress_pa = {0, 1, 2};
    CHECK_THAT(reduce_curve(c).message, Catch::Contains("at least 5 samples"));
    c.strain = {0, 1e-4, 2e-4, 3e-4, 4e-4, 5e-4};
    c.stress_pa = {0, 1e6, NAN, 3e6, 2e6, 1e6};
    const CurveReduction r = reduce_curve(c);
    CHECK(r.status == ReductionStatus::invalid_curve);
    CHECK(r.problem_index == 2);
    ReductionOptions o;
    o.chord_upper_fraction = 1.5;
    CHECK(*o.invalid_reason() == "ReductionOptions::chord_upper_fraction = 1.5 violates 0 < x < 1");
}
