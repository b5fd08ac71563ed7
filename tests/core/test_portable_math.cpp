// portable_atan2 and portable_acos (core/portable_math.hpp): within 1 and 2 ulp of the correctly
// rounded value over every octant and 0.08 / 0.16 ulp on average, std::atan2's special values, and NaN where it has NaN. The
// reference is the long double function rounded to double (x86: 64-bit significand, 11 bits
// more than a double).
#include <catch2/catch.hpp>

#include <cmath>
#include <cstdint>
#include <limits>
#include <random>

#include "core/portable_math.hpp"

using namespace gradem;

namespace {

/// |a - b| in units in the last place of b (b finite, nonzero or zero).
double ulps(double a, double b) {
    if (a == b) return 0.0;
    const double ulp = std::nextafter(std::fabs(b), std::numeric_limits<double>::infinity()) - std::fabs(b);
    return std::fabs(a - b) / ulp;
}

double reference_atan2(double y, double x) {
    return static_cast<double>(std::atan2(static_cast<long double>(y), static_cast<long double>(x)));
}
double reference_acos(double c) { return static_cast<double>(std::acos(static_cast<long double>(c))); }

}  // namespace

TEST_CASE("portable_atan2: within 1 ulp over every octant, and at the table points", "[core][math]") {
    static_assert(std::numeric_limits<long double>::digits > std::numeric_limits<double>::digits);
    std::mt19937_64 rng(20261206);
    std::uniform_real_distribution<double> unit(-1.0, 1.0);
    std::uniform_real_distribution<double> decades(-8.0, 8.0);
    double worst = 0.0, sum = 0.0;
    constexpr int samples = 200000;
    for (int n = 0; n < samples; ++n) {
        // every octant, ratios over 8 decades either way, magnitudes over 16
        const double scale = std::pow(10.0, decades(rng));
        const double y = unit(rng) * std::pow(10.0, 0.5 * decades(rng)) * scale, x = unit(rng) * scale;
        const double e = ulps(portable_atan2(y, x), reference_atan2(y, x));
        worst = std::max(worst, e);
        sum += e;
    }
    CHECK(worst <= 1.0);
    // the mean, about 0.078 ulp (standard error about 0.001): without the table's lo parts or
    // π's and π/2's it is over 0.09
    CHECK(sum / samples <= 0.085);
    // ratios at and around the table points k/8, where the reduced argument changes sides
    double worst_table = 0.0;
    for (int k = 0; k <= 8; ++k) {
        for (double d : {-1e-3, -1e-9, 0.0, 1e-9, 1e-3}) {
            const double a = 0.125 * k + d;
            if (a < 0.0 || a > 1.0) continue;
            for (double sx : {1.0, -1.0})
                for (double sy : {1.0, -1.0}) {
                    worst_table = std::max(worst_table, ulps(portable_atan2(sy * a, sx), reference_atan2(sy * a, sx)));
                    worst_table = std::max(worst_table, ulps(portable_atan2(sy, sx * a), reference_atan2(sy, sx * a)));
                }
        }
    }
    CHECK(worst_table <= 1.0);
    CHECK(portable_atan2(1.0, 1.0) == reference_atan2(1.0, 1.0));  // π/4: the table's last point
    // near the largest doubles (scaled down before 15 x the larger one would overflow) and the
    // smallest (subnormal) ones
    for (double big : {0x1p1000, 1e307, std::numeric_limits<double>::max()})
        for (double ratio : {0.0, 0.01, 0.3, 0.5, 0.77, 1.0}) {
            CHECK(ulps(portable_atan2(ratio * big, big), reference_atan2(ratio * big, big)) <= 1.0);
            CHECK(ulps(portable_atan2(-big, ratio * big), reference_atan2(-big, ratio * big)) <= 1.0);
        }
    const double tiny = std::numeric_limits<double>::denorm_min();
    CHECK(ulps(portable_atan2(3.0 * tiny, 7.0 * tiny), reference_atan2(3.0 * tiny, 7.0 * tiny)) <= 1.0);
}

TEST_CASE("portable_atan2: signed zeros, axes, infinities and NaN as std::atan2", "[core][math]") {
    const double inf = std::numeric_limits<double>::infinity(), nan = std::numeric_limits<double>::quiet_NaN();
    const double pi = reference_atan2(0.0, -1.0), half_pi = reference_atan2(1.0, 0.0);
    CHECK(portable_atan2(0.0, 1.0) == 0.0);
    CHECK_FALSE(std::signbit(portable_atan2(0.0, 1.0)));
    CHECK(std::signbit(portable_atan2(-0.0, 1.0)));
    CHECK(portable_atan2(0.0, -1.0) == pi);
    CHECK(portable_atan2(-0.0, -1.0) == -pi);
    CHECK(portable_atan2(0.0, 0.0) == 0.0);
    CHECK(portable_atan2(0.0, -0.0) == pi);
    CHECK(portable_atan2(-0.0, -0.0) == -pi);
    CHECK(portable_atan2(2.0, 0.0) == half_pi);
    CHECK(portable_atan2(2.0, -0.0) == half_pi);
    CHECK(portable_atan2(-2.0, 0.0) == -half_pi);
    CHECK(portable_atan2(1.0, inf) == 0.0);
    CHECK(portable_atan2(1.0, -inf) == pi);
    CHECK(portable_atan2(inf, 1.0) == half_pi);
    CHECK(portable_atan2(-inf, -1.0) == -half_pi);
    CHECK(std::isnan(portable_atan2(nan, 1.0)));
    CHECK(std::isnan(portable_atan2(1.0, nan)));
    CHECK(std::isnan(portable_atan2(inf, inf)));  // std::atan2 gives π/4 here; no caller needs it
}

TEST_CASE("portable_acos: within 2 ulp on [-1, 1], exact at the ends, NaN outside", "[core][math]") {
    std::mt19937_64 rng(3);
    std::uniform_real_distribution<double> unit(-1.0, 1.0);
    double worst = 0.0, sum = 0.0;
    constexpr int samples = 200000;
    for (int n = 0; n < samples; ++n) {
        const double c = unit(rng);
        const double e = ulps(portable_acos(c), reference_acos(c));
        worst = std::max(worst, e);
        sum += e;
    }
    CHECK(sum / samples <= 0.170);  // about 0.161 (0.18 without the table's lo parts)
    for (int e = 1; e <= 52; ++e) {  // near the ends, where acos is steep: 1 - 2^-e, -1 + 2^-e
        const double d = std::ldexp(1.0, -e);
        worst = std::max(worst, ulps(portable_acos(1.0 - d), reference_acos(1.0 - d)));
        worst = std::max(worst, ulps(portable_acos(-1.0 + d), reference_acos(-1.0 + d)));
    }
    CHECK(worst <= 2.0);
    CHECK(portable_acos(1.0) == 0.0);
    CHECK(portable_acos(-1.0) == reference_atan2(0.0, -1.0));
    CHECK(portable_acos(0.0) == reference_atan2(1.0, 0.0));
    CHECK(std::isnan(portable_acos(1.0 + 1e-15)));
    CHECK(std::isnan(portable_acos(-2.0)));
    CHECK(std::isnan(portable_acos(std::numeric_limits<double>::infinity())));
    CHECK(std::isnan(portable_acos(std::numeric_limits<double>::quiet_NaN())));
}
