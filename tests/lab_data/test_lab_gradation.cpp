// Gradation indices of the study's two sands (Table 2), checked against values worked out by
// hand with log-size interpolation: D = d_lo · (d_hi/d_lo)^((p − p_lo)/(p_hi − p_lo)).
#include <catch2/catch.hpp>

#include <cmath>

#include "lab_data/c144.hpp"
#include "lab_data/gradation.hpp"
#include "lab_data/sieve_table.hpp"

using namespace gradem::lab;

namespace {

const std::vector<double> kSieves = {4.75e-3, 2.36e-3, 1.18e-3, 0.595e-3, 0.4e-3, 0.3e-3, 0.149e-3, 0.075e-3};

GradationCurve curve(std::vector<double> pct) {
    for (double& p : pct) p /= 100;
    return GradationCurve::from_points(kSieves, pct);
}
const GradationCurve kPreBlended = curve({100.0, 99.6, 98.1, 91.9, 83.2, 69.9, 25.6, 0.0});
const GradationCurve kVanBuren = curve({100.0, 99.8, 95.5, 82.5, 51.9, 14.4, 0.6, 0.0});

C144Limits study_limits() { return read_c144_limits(std::string(GRADEM_LAB_STUDY) + "/astm_c144_natural_sand.csv"); }

}  // namespace

TEST_CASE("lab: pre-blended sand: D-values Cu Cc USCS SP fineness modulus", "[lab][gradation]") {
    const GradationIndices g = analyse_gradation(kPreBlended);
    // D10 between 0.075 mm (0 %) and 0.149 mm (25.6 %): 0.075·(0.149/0.075)^(10/25.6) = 0.09807 mm.
    CHECK(g.d10_m * 1e3 == Approx(0.09807).epsilon(1e-3));
    // D30, D50, D60 between 0.149 mm (25.6 %) and 0.3 mm (69.9 %).
    CHECK(g.d30_m * 1e3 == Approx(0.15973).epsilon(1e-3));
    CHECK(g.d50_m * 1e3 == Approx(0.21907).epsilon(1e-3));
    CHECK(g.d60_m * 1e3 == Approx(0.25657).epsilon(1e-3));
    CHECK(g.cu == Approx(2.6163).epsilon(1e-3));
    CHECK(g.cc == Approx(1.0140).epsilon(1e-3));
    CHECK(g.uscs == "SP");  // Cu < 6: poorly graded, as the study classified it
    CHECK(g.fines_fraction == 0.0);
    CHECK(g.gravel_fraction == 0.0);
    // FM (ASTM C125): cumulative % retained 74.4 + 30.1 + 8.1 + 1.9 + 0.4 + 0 (+ 0 above) = 114.9.
    CHECK(g.fineness_modulus == Approx(1.149));
}

TEST_CASE("lab: Van Buren sand: D-values Cu Cc USCS SP fineness modulus", "[lab][gradation]") {
    const GradationIndices g = analyse_gradation(kVanBuren);
    CHECK(g.d10_m * 1e3 == Approx(0.24000).epsilon(1e-3));  // 0.149 (0.6 %) .. 0.3 mm (14.4 %)
    CHECK(g.d30_m * 1e3 == Approx(0.33814).epsilon(1e-3));  // 0.3 (14.4 %) .. 0.4 mm (51.9 %)
    CHECK(g.d50_m * 1e3 == Approx(0.39421).epsilon(1e-3));
    CHECK(g.d60_m * 1e3 == Approx(0.44433).epsilon(1e-3));  // 0.4 (51.9 %) .. 0.595 mm (82.5 %)
    CHECK(g.cu == Approx(1.8514).epsilon(1e-3));
    CHECK(g.cc == Approx(1.0722).epsilon(1e-3));
    CHECK(g.uscs == "SP");
    // 99.4 + 85.6 + 17.5 + 4.5 + 0.2 + 0 = 207.2.
    CHECK(g.fineness_modulus == Approx(2.072));
}

TEST_CASE("lab: passing_fraction interpolates linearly in log size and size_at_passing inverts it", "[lab][gradation]") {
    CHECK(kVanBuren.passing_fraction(0.3e-3) == Approx(0.144));
    // At the geometric mean of two sieves the passing is the arithmetic mean of theirs.
    CHECK(kVanBuren.passing_fraction(std::sqrt(0.3e-3 * 0.4e-3)) == Approx((0.144 + 0.519) / 2));
    for (double f : {0.05, 0.3, 0.77, 0.999})
        CHECK(kVanBuren.passing_fraction(kVanBuren.size_at_passing(f)) == Approx(f));
    CHECK(kVanBuren.passing_fraction(10e-3) == 1.0);
    CHECK(kVanBuren.passing_fraction(0.0) == 0.0);
    CHECK(kVanBuren.size_at_passing(1.0) == Approx(4.75e-3));
    const GradationCurve fines = GradationCurve::from_points({0.075e-3, 1e-3}, {0.2, 1.0});
    CHECK(std::isnan(fines.size_at_passing(0.1)));  // inside the pan fraction: unknown
    CHECK(fines.passing_fraction(0.01e-3) == 0.2);
}

TEST_CASE("lab: invalid curves are rejected with the field that broke", "[lab][gradation][errors]") {
    CHECK_THROWS_WITH(GradationCurve::from_points({1e-3, 2e-3}, {0.9, 0.5}), Catch::Contains("must not decrease"));
    CHECK_THROWS_WITH(GradationCurve::from_points({1e-3, 2e-3}, {0.5, 1.2}), Catch::Contains("passing[1] violates"));
    CHECK_THROWS_WITH(GradationCurve::from_points({1e-3, 1e-3}, {0.5, 0.6}), Catch::Contains("strictly ascending"));
}

TEST_CASE("lab: USCS symbols for other gradations", "[lab][gradation]") {
    const GradationCurve well = GradationCurve::from_points({0.075e-3, 0.15e-3, 0.6e-3, 2.36e-3, 4.75e-3}, {0.02, 0.10, 0.30, 0.75, 1.0});
    const GradationIndices w = analyse_gradation(well);
    CHECK(w.cu >= 6);
    CHECK(w.uscs == "SW");
    const GradationCurve dirty = GradationCurve::from_points({0.075e-3, 0.3e-3, 1.18e-3, 4.75e-3}, {0.08, 0.4, 0.9, 1.0});
    CHECK(analyse_gradation(dirty).uscs == "SP-SM or SP-SC");
    const GradationCurve gravel = GradationCurve::from_points({0.075e-3, 4.75e-3, 19e-3}, {0.0, 0.3, 1.0});
    CHECK(analyse_gradation(gravel).uscs.front() == 'G');
}

TEST_CASE("lab: ASTM C144: neither of the study's sands conforms as the study found", "[lab][gradation][c144]") {
    const C144Limits limits = study_limits();
    REQUIRE(limits.sieves.size() == 7);
    const C144Verdict pb = check_c144(kPreBlended, limits);
    CHECK_FALSE(pb.conforms);
    // No. 30: 91.9 > 75; No. 50: 69.9 > 35; No. 100: 25.6 > 15; 44.3 % between No. 50 and No. 100 > 25 %.
    CHECK(pb.violations.size() == 4);
    CHECK(pb.retained_no50_to_no100 == Approx(0.443));
    const C144Verdict vb = check_c144(kVanBuren, limits);
    CHECK_FALSE(vb.conforms);
    // No. 30: 82.5 > 75; No. 100: 0.6 < 2; 68.1 % between No. 30 and No. 50 > 50 %.
    CHECK(vb.violations.size() == 3);
    CHECK(vb.max_retained_consecutive == Approx(0.681));
    CHECK(vb.sieves[4].ok);  // No. 50: 14.4 within 10..35
    CHECK_FALSE(vb.sieves[5].ok);

    // A sand in the middle of every band conforms.
    const GradationCurve mid = GradationCurve::from_points({4.75e-3, 2.36e-3, 1.18e-3, 0.6e-3, 0.3e-3, 0.15e-3, 0.075e-3},
                                                           {1.0, 0.975, 0.85, 0.575, 0.225, 0.085, 0.025});
    CHECK(check_c144(mid, limits).conforms);
}
