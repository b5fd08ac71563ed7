#pragma once
// atan2 and acos from IEEE-754 basic operations only (+, -, *, /, sqrt, each correctly
// rounded), so they give the same bits on every machine and with every C library. The C
// library's own atan2 and acos do not: glibc picks an implementation per processor at load
// time (an FMA variant where the processor has FMA, a baseline one otherwise), and the two
// differ in the last bit for some arguments, which a flat-joint compression test amplifies into
// a different load curve. The flat joint's disc elements (core/disc_elements.hpp) call these.
//
// Method (built with -ffp-contract=off, no reassociation: the same operations everywhere):
//   atan a, a = num/den in [0, 1]: the nearest table point c = k/8 (k = 0..8, found by
//   comparisons) and the addition formula, with one division,
//     atan a = atan c + atan u,   u = (a - c) / (1 + a c) = (num - c den) / (den + c num),   |u| <= 1/16,
//   atan c tabulated as a double-double (hi + lo, from a 60-digit evaluation), atan u by its
//   Taylor series to u^13 (the first term left out, u^15/15, is under 1e-18 of u), evaluated by
//   Estrin's scheme;
//   atan2 y/x by the octant: a = min(|x|,|y|)/max(|x|,|y|), the angle t, π/2 - t, π/2 + t or
//   π - t (the constant as hi + lo), the sign of y;
//   acos c = atan2(sqrt((1 - c)(1 + c)), c), accurate near c = ±1 (1 - c and 1 + c exact there).
// Accuracy: atan2 within 1 ulp of the correctly rounded value (0.08 ulp on average), acos within
// 2 (0.16 on average) (tests/core/test_portable_math.cpp, against the long double functions);
// the C library's are within 1. Arguments: finite; NaN gives NaN.
// portable_atan2_branchless is the same function with selects for branches (the same bits), for
// loops over lanes that must vectorise (core/disc_elements_branchless.hpp).
#include <cmath>

namespace gradem {

namespace portable_math_detail {

// atan(k/8) = hi[k] + lo[k], k = 0..8 (hi the double nearest atan(k/8), lo the double nearest
// the rest).
inline constexpr double kAtanHi[9] = {0x0.0p+0,
                                      0x1.fd5ba9aac2f6ep-4,
                                      0x1.f5b75f92c80ddp-3,
                                      0x1.6f61941e4def1p-2,
                                      0x1.dac670561bb4fp-2,
                                      0x1.1e00babdefeb4p-1,
                                      0x1.4978fa3269ee1p-1,
                                      0x1.700a7c5784634p-1,
                                      0x1.921fb54442d18p-1};
inline constexpr double kAtanLo[9] = {0x0.0p+0,
                                      -0x1.cd37686760c17p-59,
                                      0x1.8ab6e3cf7afbdp-57,
                                      -0x1.c63aae6f6e918p-56,
                                      0x1.a2b7f222f65e2p-56,
                                      -0x1.928df287a668fp-58,
                                      0x1.2419a87f2a458p-56,
                                      -0x1.8c34d25aadef6p-56,
                                      0x1.1a62633145c07p-55};
inline constexpr double kPiHi = 0x1.921fb54442d18p+1, kPiLo = 0x1.1a62633145c07p-53;          // π
inline constexpr double kHalfPiHi = 0x1.921fb54442d18p+0, kHalfPiLo = 0x1.1a62633145c07p-54;  // π/2

/// atan(num/den) for 0 <= num <= den, den > 0 finite [rad]. One division: the table point
/// k/8 nearest num/den is counted by comparisons (16 num >= (2j+1) den, j = 0..7), and
/// u = (num - c den)/(den + c num) is the reduced argument (a - c)/(1 + a c) with a = num/den.
inline double atan_ratio(double num, double den) {
    const double n16 = 16.0 * num;
    const int k = (n16 >= den) + (n16 >= 3.0 * den) + (n16 >= 5.0 * den) + (n16 >= 7.0 * den) + (n16 >= 9.0 * den) +
                  (n16 >= 11.0 * den) + (n16 >= 13.0 * den) + (n16 >= 15.0 * den);
    const double c = 0.125 * k;
    const double u = (num - c * den) / (den + c * num);
    const double u2 = u * u, u4 = u2 * u2;
    // atan u - u = u^3 p, p = -1/3 + u^2/5 - u^4/7 + u^6/9 - u^8/11 + u^10/13 (Estrin's scheme:
    // the pairs side by side, a short chain of dependent operations)
    const double p = (-1.0 / 3.0 + u2 * (1.0 / 5.0)) +
                     u4 * ((-1.0 / 7.0 + u2 * (1.0 / 9.0)) + u4 * (-1.0 / 11.0 + u2 * (1.0 / 13.0)));
    return kAtanHi[k] + (u + (kAtanLo[k] + u * u2 * p));
}

/// atan_ratio with the table point chosen by selects (the thresholds grow with k, so the last one
/// met is the count of those met): the same bits, and a loop over lanes that calls it vectorises.
inline double atan_ratio_branchless(double num, double den) {
    const double n16 = 16.0 * num;
    double hi = kAtanHi[0], lo = kAtanLo[0], c = 0.0;
#pragma GCC unroll 8
    for (int k = 1; k <= 8; ++k) {
        const bool above = n16 >= (2 * k - 1) * den;
        hi = above ? kAtanHi[k] : hi;
        lo = above ? kAtanLo[k] : lo;
        c = above ? 0.125 * k : c;
    }
    const double u = (num - c * den) / (den + c * num);
    const double u2 = u * u, u4 = u2 * u2;
    const double p = (-1.0 / 3.0 + u2 * (1.0 / 5.0)) +
                     u4 * ((-1.0 / 7.0 + u2 * (1.0 / 9.0)) + u4 * (-1.0 / 11.0 + u2 * (1.0 / 13.0)));
    return hi + (u + (lo + u * u2 * p));
}

}  // namespace portable_math_detail

/// atan2(y, x) in [-π, π] [rad], as std::atan2 for finite arguments (signed zeros included:
/// atan2(±0, +0) = ±0, atan2(±0, -0) = ±π); NaN if either is NaN or both are infinite.
inline double portable_atan2(double y, double x) {
    using namespace portable_math_detail;
    const double ax = std::fabs(x), ay = std::fabs(y);
    if (std::isnan(x) || std::isnan(y) || (std::isinf(x) && std::isinf(y))) return (x - x) + (y - y);  // NaN
    const bool steep = ay > ax;  // above the diagonal: the angle from the y axis
    double num = steep ? ax : ay, den = steep ? ay : ax;
    // scaled by a power of two (exact): 15 den and den + c num stay finite, c den keeps its bits
    if (den > 0x1p1000) num *= 0x1p-64, den *= 0x1p-64;
    else if (den < 0x1p-900) num *= 0x1p900, den *= 0x1p900;
    const double t = (num == 0.0 || std::isinf(den)) ? 0.0 : atan_ratio(num, den);
    double r;                                   // the angle of (|x| or -|x|, |y|), by octant:
    if (!steep) r = std::signbit(x) ? kPiHi + (kPiLo - t) : t;     // π - t, or t
    else r = kHalfPiHi + (std::signbit(x) ? kHalfPiLo + t : kHalfPiLo - t);  // π/2 + t, or π/2 - t
    return std::copysign(r, y);
}

/// portable_atan2 with selects for its branches (every path computed, one kept), so that a loop
/// over lanes that calls it vectorises: the same operations on the kept path, the same bits for
/// every argument (tests/core/test_disc_elements_branchless.cpp).
inline double portable_atan2_branchless(double y, double x) {
    using namespace portable_math_detail;
    const double ax = std::fabs(x), ay = std::fabs(y);
    const bool steep = ay > ax;
    const double den0 = steep ? ay : ax;
    const double scale = den0 > 0x1p1000 ? 0x1p-64 : (den0 < 0x1p-900 ? 0x1p900 : 1.0);  // x 1: exact
    const double num = (steep ? ax : ay) * scale, den = den0 * scale;
    const double ratio = atan_ratio_branchless(num, den);
    const double t = ((num == 0.0) | std::isinf(den)) ? 0.0 : ratio;
    const bool negative_x = std::copysign(1.0, x) < 0.0;  // std::signbit(x)
    const double flat = negative_x ? kPiHi + (kPiLo - t) : t;
    const double tall = kHalfPiHi + (negative_x ? kHalfPiLo + t : kHalfPiLo - t);
    const double r = std::copysign(steep ? tall : flat, y);
    // NaN where either is NaN or both are infinite, as two selects: one select on the three
    // tests keeps GCC 12 from vectorising the loops that call this
    const bool nan_argument = std::isnan(x) | std::isnan(y);
    const bool both_infinite = std::isinf(x) & std::isinf(y);
    const double r_or_nan = nan_argument ? (x - x) + (y - y) : r;
    return both_infinite ? (x - x) + (y - y) : r_or_nan;
}

/// acos(c) in [0, π] [rad] for c in [-1, 1]; NaN outside.
inline double portable_acos(double c) {
    if (!(c >= -1.0 && c <= 1.0)) return (c - c) / (c - c);  // NaN (an infinity too)
    return portable_atan2(std::sqrt((1.0 - c) * (1.0 + c)), c);
}

}  // namespace gradem
