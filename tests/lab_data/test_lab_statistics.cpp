// Statistics against hand-computed values.
#include <catch2/catch.hpp>

#include <cmath>

#include "lab_data/statistics.hpp"

using namespace gradem::lab;

TEST_CASE("lab: sample summary: mean sample std (n - 1) CV min max and NaN skipped", "[lab][statistics]") {
    const SampleSummary s = summarize({1, 2, 3, 4, NAN});
    CHECK(s.n == 4);
    CHECK(s.mean == Approx(2.5));
    CHECK(s.std == Approx(std::sqrt(5.0 / 3.0)));  // Σ(x − 2.5)² = 5, n − 1 = 3
    CHECK(s.cv == Approx(std::sqrt(5.0 / 3.0) / 2.5));
    CHECK(s.min == 1);
    CHECK(s.max == 4);
    CHECK(std::isnan(summarize({7}).std));
}

TEST_CASE("lab: regularized incomplete beta and Student t p-values", "[lab][statistics]") {
    // I_x(a, b) for integer a, b is a binomial tail: I_0.5(2, 3) = (C(4,2) + C(4,3) + C(4,4)) / 16.
    CHECK(regularized_incomplete_beta(2, 3, 0.5) == Approx(11.0 / 16.0));
    CHECK(regularized_incomplete_beta(1, 1, 0.3) == Approx(0.3));
    // Critical values from t tables: t(0.975, 10) = 2.228139, t(0.95, 10) = 1.812461.
    CHECK(student_t_two_sided_p(2.228138852, 10) == Approx(0.05).epsilon(1e-6));
    CHECK(student_t_two_sided_p(-1.812461123, 10) == Approx(0.10).epsilon(1e-6));
    CHECK(student_t_two_sided_p(1.0, 1) == Approx(0.5));  // Cauchy: P(|T| > 1) = 1/2
    CHECK(student_t_two_sided_p(0.0, 5) == Approx(1.0));
}

TEST_CASE("lab: Welch t-test and effect sizes", "[lab][statistics]") {
    // a: mean 22, s² = 4 (n 3); b: mean 18.5, s² = 5/3 (n 4).
    const WelchTest w = welch_t_test({20, 22, 24}, {17, 18, 19, 20});
    const double v1 = 4.0 / 3, v2 = (5.0 / 3) / 4;
    CHECK(w.mean_difference == Approx(3.5));
    CHECK(w.t == Approx(3.5 / std::sqrt(v1 + v2)));
    CHECK(w.dof == Approx((v1 + v2) * (v1 + v2) / (v1 * v1 / 2 + v2 * v2 / 3)));
    CHECK(w.p_value == Approx(student_t_two_sided_p(w.t, w.dof)));
    CHECK(w.p_value > 0.05);  // t = 2.65 with 3.2 dof lies between the 5 % and 10 % critical values
    CHECK(w.p_value < 0.10);
    const double pooled = std::sqrt((2 * 4.0 + 3 * 5.0 / 3) / 5);
    CHECK(w.cohens_d == Approx(3.5 / pooled));
    CHECK(w.hedges_g == Approx(3.5 / pooled * (1 - 3.0 / 19)));
    CHECK(std::isnan(welch_t_test({1}, {1, 2}).p_value));
}

TEST_CASE("lab: ASTM C109 permissible range discard and retest", "[lab][statistics][c109]") {
    CHECK(c109_permissible_range(3) == 0.087);
    CHECK(c109_permissible_range(2) == 0.076);
    auto one = [](std::vector<double> x) { return c109_range_checks(x).front(); };
    const RangeCheck ok = one({20, 20.5, 21});  // range 1 / 20.5 = 4.9 %
    CHECK(ok.ok);
    CHECK(ok.range_fraction == Approx(1.0 / 20.5));
    const RangeCheck discard = one({20, 21, 23});  // 3 / 21.33 = 14 % > 8.7 %: drop 23; 20, 21: 4.9 % <= 7.6 %
    CHECK_FALSE(discard.ok);
    CHECK(discard.discarded == 2);
    CHECK_FALSE(discard.retest_required);
    const RangeCheck retest = one({18, 20, 22});  // drop 18; 20, 22: 2/21 = 9.5 % > 7.6 %
    CHECK(retest.discarded == 0);
    CHECK(retest.retest_required);
    CHECK(c109_range_checks({1, 1, 1, 1, 1, 1, 1, 1, 1}).size() == 3);
    CHECK(c109_range_checks({20, 20, 20, 20}).size() == 1);  // a single leftover cube is not checked
    const auto two = c109_range_checks({20, 20, 20, 20, 21.8});
    REQUIRE(two.size() == 2);
    CHECK(two[1].permissible_fraction == 0.076);
    CHECK_FALSE(two[1].ok);  // 1.8 / 20.9 = 8.6 % > 7.6 %
}
