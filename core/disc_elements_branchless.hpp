#pragma once
// compressed_part() of core/disc_elements.hpp written with selects instead of branches, so that
// a loop over many (disc, element) pairs vectorises: every path is computed and the one the
// branching code takes is kept. The kept path does the same IEEE operations in the same order,
// so the results are bitwise compressed_part()'s (tests/core/test_disc_elements_branchless.cpp
// compares the two on random gap fields and layouts). The reasoning that makes a select equal a
// branch:
//   - a term that the branching code does not add is added as +0: the moment sums start at +0 and
//     never become -0 (x + y is -0 only if both are -0), and s + (+0) = s for every other s;
//   - the zero line's crossings with the arcs ("kinks") all lie strictly inside the element's
//     angular range, so the branching code's sort of [edge a0, kinks, edge a1] leaves the edges at
//     the ends and sorts the kinks stably (strict <, in insertion order): here the kink slots are
//     sorted by the same compare-and-swap passes without the early exit (a pass that stops
//     swapping would only compare an already sorted prefix), an absent kink at +inf;
//   - the angle wrap `while (angle < a0) angle += 2π` runs at most twice for angles φ ± β in
//     [-2π, 2π] and a0 in [0, 2π), its counterpart at most once: done as three and two
//     conditional steps.
#include <cmath>
#include <limits>

#include "core/disc_elements.hpp"

namespace gradem {

/// What compressed_part() needs of an element: its radial and angular bounds and the directions
/// of its edges (DiscElement's r0, r1, a0, a1, cos0, sin0, cos1, sin1).
struct SectorBounds {
    double r0 = 0, r1 = 1, a0 = 0, a1 = 0, cos0 = 1, sin0 = 0, cos1 = 1, sin1 = 0;
};
inline SectorBounds sector_bounds(const DiscElement& g) {
    return {g.r0, g.r1, g.a0, g.a1, g.cos0, g.sin0, g.cos1, g.sin1};
}

namespace branchless_detail {

using detail::AreaMoments;
using detail::PieceEnd;

/// gap_field().
inline GapField gap_field(double gamma, double wy, double wz) {
    GapField f = unoriented_gap_field(gamma, wy, wz);
    const bool tilted = f.slope > 0.0;
    const double phi = portable_atan2_branchless(wz, wy);
    const double cphi = wy / f.slope, sphi = wz / f.slope;
    f.phi = tilted ? phi : 0.0;
    f.cphi = tilted ? cphi : 1.0;
    f.sphi = tilted ? sphi : 0.0;
    return f;
}

/// arc_crossing() (angle, cos and sin meaningful only where cut).
inline ArcCrossing arc_crossing(const GapField& f, double r) {
    ArcCrossing a;
    const bool defined = (r > 0.0) & (f.slope > 0.0);
    const double c = -f.gamma / (f.slope * r);
    const bool crossed = defined & (c > -1.0) & (c < 1.0);
    const double sb = std::sqrt((1.0 - c) * (1.0 + c));  // sin β
    const double beta = portable_atan2_branchless(sb, c);
    const double uncut = defined ? (c >= 1.0 ? -1.0 : 4.0) : (f.gamma < 0.0 ? -1.0 : 4.0);
    a.beta = crossed ? beta : uncut;
    a.cut = crossed;
    a.angle[0] = f.phi - beta;
    a.angle[1] = f.phi + beta;
    a.cos[0] = f.cphi * c + f.sphi * sb;
    a.sin[0] = f.sphi * c - f.cphi * sb;
    a.cos[1] = f.cphi * c - f.sphi * sb;
    a.sin[1] = f.sphi * c + f.cphi * sb;
    return a;
}

/// Kink k of arc a (radius r) wrapped into [a0, a0 + 2π), as add_kinks() has it; at +inf if the
/// arc is not cut or the kink lies outside (a0, a1).
inline PieceEnd kink(const SectorBounds& g, const ArcCrossing& a, int k, double r) {
    double angle = a.angle[k];
#pragma GCC unroll 3
    for (int step = 0; step < 3; ++step) angle = angle < g.a0 ? angle + 2.0 * kPi : angle;
#pragma GCC unroll 2
    for (int step = 0; step < 2; ++step) angle = angle >= g.a0 + 2.0 * kPi ? angle - 2.0 * kPi : angle;
    const bool inside = a.cut & (angle > g.a0) & (angle < g.a1);
    return {inside ? angle : std::numeric_limits<double>::infinity(), a.cos[k], a.sin[k], r};
}

inline void swap_if_less(PieceEnd& lower, PieceEnd& upper) {
    const bool swap = upper.angle < lower.angle;
    const PieceEnd a = lower, b = upper;
    lower.angle = swap ? b.angle : a.angle;
    lower.c = swap ? b.c : a.c;
    lower.s = swap ? b.s : a.s;
    lower.line = swap ? b.line : a.line;
    upper.angle = swap ? a.angle : b.angle;
    upper.c = swap ? a.c : b.c;
    upper.s = swap ? a.s : b.s;
    upper.line = swap ? a.line : b.line;
}

/// m += t where `use`, else m += +0 (the same bits as not adding).
inline void add_if(AreaMoments& m, const AreaMoments& t, bool use) {
    m.m0 += use ? t.m0 : 0.0;
    m.my += use ? t.my : 0.0;
    m.mz += use ? t.mz : 0.0;
    m.myy += use ? t.myy : 0.0;
    m.myz += use ? t.myz : 0.0;
    m.mzz += use ? t.mzz : 0.0;
}

/// -t, componentwise: the fan of sign -1 (add_line_fan's terms are products and quotients of
/// its signed determinant, so flipping the sign flips every term exactly).
inline AreaMoments negated(const AreaMoments& t) { return {-t.m0, -t.my, -t.mz, -t.myy, -t.myz, -t.mzz}; }

/// add_piece() for the piece between rays a and b, if `present`. InnerKinks false: r0 is 0, so
/// the inner sector is empty and never added.
template <bool InnerKinks>
inline void add_piece(AreaMoments& m, const SectorBounds& g, const GapField& f, const ArcCrossing& inner,
                      const ArcCrossing& outer, const PieceEnd& a, const PieceEnd& b, bool present) {
    double d = 0.5 * (a.angle + b.angle) - f.phi;
    d = d > kPi ? d - 2.0 * kPi : d;
    const double from_axis = std::fabs(d);
    const bool inner_compressed = from_axis > inner.beta, outer_compressed = from_axis > outer.beta;
    AreaMoments outer_sector, fan;
    detail::add_sector(outer_sector, 1.0, g.r1, a, b);
    detail::add_line_fan(fan, 1.0, a, b, g.r0, g.r1);
    const bool loaded = present & (outer_compressed | inner_compressed);
    add_if(m, outer_compressed ? outer_sector : fan, loaded);
    if constexpr (InnerKinks) {
        AreaMoments inner_sector;
        detail::add_sector(inner_sector, -1.0, g.r0, a, b);
        add_if(m, inner_compressed ? inner_sector : negated(fan), loaded & (!inner_compressed | (g.r0 > 0.0)));
    } else {
        add_if(m, negated(fan), loaded & !inner_compressed);
    }
}

}  // namespace branchless_detail

/// compressed_part(g, f, arc_crossing(f, g.r0), arc_crossing(f, g.r1)) for the gap field
/// γ + (wy, wz).ξ, without branches. InnerKinks: whether any element of the layout has r0 > 0
/// (N_r > 1); without, the inner arc is the disc's centre and never cut, so its kink slots and
/// their pieces are left out.
template <bool InnerKinks>
inline CompressedPart compressed_part_branchless(const SectorBounds& g, double gamma, double wy, double wz) {
    using namespace branchless_detail;
    const GapField f = branchless_detail::gap_field(gamma, wy, wz);
    const ArcCrossing outer = branchless_detail::arc_crossing(f, g.r1);
    ArcCrossing inner;  // without inner kinks r0 is 0: arc_crossing()'s disc centre, never cut
    if constexpr (InnerKinks) inner = branchless_detail::arc_crossing(f, g.r0);
    else inner.beta = f.gamma < 0.0 ? -1.0 : 4.0;
    constexpr int kSlots = InnerKinks ? 4 : 2;
    PieceEnd slot[kSlots];
    if constexpr (InnerKinks) {
        slot[0] = kink(g, inner, 0, g.r0);
        slot[1] = kink(g, inner, 1, g.r0);
    }
    slot[kSlots - 2] = kink(g, outer, 0, g.r1);
    slot[kSlots - 1] = kink(g, outer, 1, g.r1);
#pragma GCC unroll 4
    for (int i = 1; i < kSlots; ++i)
#pragma GCC unroll 4
        for (int j = i; j > 0; --j) swap_if_less(slot[j - 1], slot[j]);
    int kinks = 0;
#pragma GCC unroll 4
    for (int k = 0; k < kSlots; ++k) kinks += slot[k].angle != std::numeric_limits<double>::infinity();
    const PieceEnd edge0{g.a0, g.cos0, g.sin0, -f.gamma / (f.wy * g.cos0 + f.wz * g.sin0)};
    const PieceEnd edge1{g.a1, g.cos1, g.sin1, -f.gamma / (f.wy * g.cos1 + f.wz * g.sin1)};
    AreaMoments m;
#pragma GCC unroll 5
    for (int k = 0; k <= kSlots; ++k) {  // piece k: from edge a0 or kink k-1 to kink k or edge a1
        const PieceEnd& from = k == 0 ? edge0 : slot[k - 1];
        const PieceEnd to = k < kinks ? (k < kSlots ? slot[k] : edge1) : edge1;
        add_piece<InnerKinks>(m, g, f, inner, outer, from, to, k <= kinks);
    }
    return detail::part_of_moments(f, m);
}

}  // namespace gradem
