#pragma once
// A segmented contact disc: a disc of radius R̄ split into N_r x N_α annular-sector elements,
// and the integrals of a linear normal gap field over an element's compressed part. The
// geometry of an interface law whose disc is cut into elements (docs/bond_laws.md has the law
// that uses it).
//
// Element e: r in [r0, r1] = [i, i+1]/N_r, α in [a0, a1] = 2π [j, j+1]/N_α of the unit disc,
// measured in the disc's in-plane frame (t1, t2); index e = i N_α + j. Physical quantities
// scale with R̄: area A R̄², centroid x R̄, central second moments C R̄⁴.
//
// Gap field over the interface (tension/opening +): g(ξ) = γ + w.ξ [m], ξ in the unit disc
// (x = R̄ ξ), γ the gap at the disc centre, w = R̄ n x θ_b. An element without bond carries
// σ(x) = k̄_n min(g, 0) (no tension), so over its compressed part Ω = {ξ in the element, g < 0}
//     ∫ min(g,0) dA = γ M0 + w.M1,   ∫ min(g,0) ξ dA = γ M1 + M2 w,   ∫ min(g,0)² dA = γ F + w.P
// with M0, M1, M2 the area moments of Ω of order 0, 1, 2 about the disc centre (F, P the first
// two integrals). The moments are exact, in closed form: the angles where the zero line g = 0
// crosses the element's arcs (kinks) cut [a0, a1] into pieces; on each piece every ray's
// compressed part is [r0, r1], [r0, L], [L, r1] or empty (L the line), so the piece's region is
// a difference of two fans from the centre, each a circular sector (arc r) or a triangle (the
// line between the piece's end rays), whose moments are polynomials of the end points and the
// sector's angle (detail::add_sector, add_triangle). No quadrature: exact to round-off.
//
// Speed: the zero line's direction (one atan2) and each arc's crossings (one acos, the crossing
// points by angle addition, no sin/cos call) are computed once per disc and step
// (ZeroLineCache), the element's own edge directions are tabulated (cos0, sin0, cos1, sin1),
// and the element table itself is built once per layout (disc_element_table). The flat joint's
// pass runs compressed_part() through its branch-free copy (core/disc_elements_branchless.hpp),
// vectorised across the elements of many joints; the two give the same bits.
// Portability: atan2 and acos are core/portable_math.hpp's, the same bits on every machine
// (the C library's differ in the last bit between its processor-specific variants).
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <map>
#include <memory>
#include <mutex>
#include <span>
#include <utility>
#include <vector>

#include "core/portable_math.hpp"
#include "core/vec3.hpp"

namespace gradem {

/// One element of the unit disc.
struct DiscElement {
    double area = 0;                   ///< A_e
    double inv_area = 0;               ///< 1/A_e
    double y = 0, z = 0;               ///< centroid in (t1, t2)
    double cyy = 0, czz = 0, cyz = 0;  ///< central ∫(y-y_e)² dA, ∫(z-z_e)² dA, ∫(y-y_e)(z-z_e) dA
    double polar = 0;                  ///< cyy + czz, the central polar moment
    double r0 = 0, r1 = 0;             ///< radial bounds
    double a0 = 0, a1 = 0;             ///< angular bounds [rad]
    double reach = 0;                  ///< max distance from the centroid to a point of the element
    double cos0 = 1, sin0 = 0;         ///< cos a0, sin a0
    double cos1 = 1, sin1 = 0;         ///< cos a1, sin a1
    std::int32_t ring = 0;             ///< i: the element lies between arcs i and i + 1 (radius i/N_r)
};

namespace detail {

/// Farthest point of the sector from its centroid: a corner, or the outer arc's point opposite
/// the centroid direction when that lies in the sector (distance along an edge is convex).
inline double sector_reach(const DiscElement& g, double a0, double a1) {
    double reach = 0.0;
    for (double r : {g.r0, g.r1})
        for (double a : {a0, a1}) reach = std::max(reach, std::hypot(r * std::cos(a) - g.y, r * std::sin(a) - g.z));
    double opposite = portable_atan2(-g.z, -g.y);
    while (opposite < a0) opposite += 2.0 * kPi;
    if (opposite <= a1) reach = std::max(reach, g.r1 + std::hypot(g.y, g.z));
    return reach;
}

/// Element (ir, ia) of N_r x N_α: area, centroid, central second moments (closed form), reach.
inline DiscElement sector_element(std::int32_t nr, std::int32_t na, std::int32_t ir, std::int32_t ia) {
    const double da = 2.0 * kPi / na;
    const double r0 = static_cast<double>(ir) / nr, r1 = static_cast<double>(ir + 1) / nr;
    const double a0 = ia * da, a1 = (ia + 1) * da;
    DiscElement g;
    g.r0 = r0;
    g.r1 = r1;
    g.ring = ir;
    g.area = 0.5 * (r1 * r1 - r0 * r0) * da;
    const double m1 = (r1 * r1 * r1 - r0 * r0 * r0) / 3.0;
    const double q = (r1 * r1 * r1 * r1 - r0 * r0 * r0 * r0) / 4.0;
    const double sy = m1 * (std::sin(a1) - std::sin(a0));
    const double sz = m1 * (std::cos(a0) - std::cos(a1));
    const double s2 = (std::sin(2 * a1) - std::sin(2 * a0)) / 4.0;
    const double syy = q * (0.5 * da + s2), szz = q * (0.5 * da - s2);
    const double syz = q * 0.5 * (std::sin(a1) * std::sin(a1) - std::sin(a0) * std::sin(a0));
    g.y = sy / g.area;
    g.z = sz / g.area;
    g.cyy = syy - g.area * g.y * g.y;
    g.czz = szz - g.area * g.z * g.z;
    g.cyz = syz - g.area * g.y * g.z;
    g.inv_area = 1.0 / g.area;
    g.polar = g.cyy + g.czz;
    g.a0 = a0;
    g.a1 = a1;
    g.reach = sector_reach(g, a0, a1);
    g.cos0 = std::cos(a0);
    g.sin0 = std::sin(a0);
    g.cos1 = std::cos(a1);
    g.sin1 = std::sin(a1);
    return g;
}

}  // namespace detail

/// The N_r x N_α elements of a unit disc, element index = i_r N_α + i_α.
inline std::vector<DiscElement> disc_elements(std::int32_t nr, std::int32_t na) {
    std::vector<DiscElement> out;
    for (std::int32_t ir = 0; ir < nr; ++ir)
        for (std::int32_t ia = 0; ia < na; ++ia) out.push_back(detail::sector_element(nr, na, ir, ia));
    return out;
}

/// The element table of layout N_r x N_α, built once per process and layout (thread-safe; the
/// tables live until exit), so a law's per-step context allocates nothing. Equal layouts give
/// the same span (same data pointer).
inline std::span<const DiscElement> disc_element_table(std::int32_t nr, std::int32_t na) {
    static std::mutex guard;
    static std::map<std::pair<std::int32_t, std::int32_t>, std::unique_ptr<const std::vector<DiscElement>>>
        tables;
    const std::lock_guard<std::mutex> lock(guard);
    auto& table = tables[{nr, na}];
    if (!table) table = std::make_unique<const std::vector<DiscElement>>(disc_elements(nr, na));
    return {table->data(), table->size()};
}

/// A disc's normal gap over the unit disc, g(ξ) = γ + w.ξ [m], and the direction of its
/// gradient, w = |w| (cos φ, sin φ).
struct GapField {
    double gamma = 0, wy = 0, wz = 0;    ///< γ [m], w [m per unit of ξ]
    double slope = 0;                    ///< |w| [m]
    double phi = 0, cphi = 1, sphi = 0;  ///< φ [rad] in [-π, π], cos φ, sin φ
};
/// γ, w and |w|; the direction as for a level field (φ 0), for the caller to set when |w| > 0.
inline GapField unoriented_gap_field(double gamma, double wy, double wz) {
    GapField f;
    f.gamma = gamma;
    f.wy = wy;
    f.wz = wz;
    f.slope = std::sqrt(wy * wy + wz * wz);
    return f;
}
inline GapField gap_field(double gamma, double wy, double wz) {
    GapField f = unoriented_gap_field(gamma, wy, wz);
    if (f.slope > 0.0) {
        f.phi = portable_atan2(wz, wy);
        f.cphi = wy / f.slope;
        f.sphi = wz / f.slope;
    }
    return f;
}

/// Where the zero line g = 0 crosses the arc |ξ| = r: at α = φ ± β, cos β = c = -γ/(|w| r).
/// On the arc, g = γ + |w| r cos(α - φ) < 0 (compressed) exactly where |α - φ| > β (α - φ
/// wrapped into [-π, π]); β = -1: compressed everywhere, β = 4: nowhere.
struct ArcCrossing {
    double beta = 4.0;
    bool cut = false;                 ///< crossed at two angles
    double angle[2], cos[2], sin[2];  ///< φ - β, φ + β [rad]; their cos, sin (set only when cut)
};
/// cos(φ ∓ β) = cos φ c ± sin φ sin β, sin(φ ∓ β) = sin φ c ∓ cos φ sin β (angle addition, no
/// sin/cos call), sin β = sqrt((1 - c)(1 + c)).
inline ArcCrossing arc_crossing(const GapField& f, double r) {
    ArcCrossing a;
    if (!(r > 0.0 && f.slope > 0.0)) {  // the centre, or a uniform gap: the sign of γ
        a.beta = f.gamma < 0.0 ? -1.0 : 4.0;
        return a;
    }
    const double c = -f.gamma / (f.slope * r);
    if (!(c > -1.0 && c < 1.0)) {  // not crossed: c >= 1 compressed all along, c <= -1 open
        a.beta = c >= 1.0 ? -1.0 : 4.0;
        return a;
    }
    const double sb = std::sqrt((1.0 - c) * (1.0 + c));  // sin β
    a.beta = portable_atan2(sb, c);  // portable_acos(c), with its sine computed once
    a.cut = true;
    a.angle[0] = f.phi - a.beta;
    a.angle[1] = f.phi + a.beta;
    a.cos[0] = f.cphi * c + f.sphi * sb;
    a.sin[0] = f.sphi * c - f.cphi * sb;
    a.cos[1] = f.cphi * c - f.sphi * sb;
    a.sin[1] = f.sphi * c + f.cphi * sb;
    return a;
}

/// A disc's gap field and its arcs' crossings, made when an element first needs them and
/// reused by the disc's other elements in this step (elements come ring by ring, so a ring's
/// two arcs sit in two slots: arc i in slot i mod 2).
struct ZeroLineCache {
    GapField field;
    bool ready = false;
    ArcCrossing arc[2];
    std::int32_t index[2] = {-1, -1};

    void prepare(double gamma, double wy, double wz) {
        if (ready) return;
        field = gap_field(gamma, wy, wz);
        ready = true;
    }
    /// The crossing of arc `i` (radius r = i/N_r).
    const ArcCrossing& crossing(std::int32_t i, double r) {
        const std::int32_t slot = i & 1;
        if (index[slot] != i) {
            arc[slot] = arc_crossing(field, r);
            index[slot] = i;
        }
        return arc[slot];
    }
};

/// The compressed part of one element of the unit disc (ξ, w in (t1, t2) components):
/// ∫ min(g,0) dA [m], ∫ min(g,0) ξ dA [m], ∫ min(g,0)² dA [m²].
struct CompressedPart {
    double force = 0;       ///< ∫ min(g, 0) dA
    double py = 0, pz = 0;  ///< ∫ min(g, 0) ξ dA
    double energy = 0;      ///< ∫ min(g, 0)² dA
};

namespace detail {

/// A ray bounding a piece: its angle [rad], direction (cos, sin), and the radius where the zero
/// line meets it (exact at a kink; -γ/(w.u) on an element edge, used clamped to [r0, r1]).
struct PieceEnd {
    double angle = 0, c = 1, s = 0, line = 0;
};
/// The element's edges a0, a1 and the kinks in (a0, a1) (at most two per arc), sorted.
struct AngularCuts {
    PieceEnd at[6];
    int count = 0;
};

/// Adds arc `a`'s crossings that fall in (a0, a1), wrapped into [a0, a0 + 2π), at radius r.
inline void add_kinks(AngularCuts& cuts, const DiscElement& g, const ArcCrossing& a, double r) {
    if (!a.cut) return;
    for (int k = 0; k < 2; ++k) {
        double angle = a.angle[k];
        while (angle < g.a0) angle += 2.0 * kPi;
        while (angle >= g.a0 + 2.0 * kPi) angle -= 2.0 * kPi;
        if (angle > g.a0 && angle < g.a1) cuts.at[cuts.count++] = {angle, a.cos[k], a.sin[k], r};
    }
}

inline AngularCuts angular_cuts(const DiscElement& g, const GapField& f, const ArcCrossing& inner,
                                const ArcCrossing& outer) {
    AngularCuts cuts;
    cuts.at[cuts.count++] = {g.a0, g.cos0, g.sin0, -f.gamma / (f.wy * g.cos0 + f.wz * g.sin0)};
    if (g.r0 > 0.0) add_kinks(cuts, g, inner, g.r0);
    add_kinks(cuts, g, outer, g.r1);
    cuts.at[cuts.count++] = {g.a1, g.cos1, g.sin1, -f.gamma / (f.wy * g.cos1 + f.wz * g.sin1)};
    for (int i = 1; i < cuts.count; ++i)  // insertion sort of at most 6 angles
        for (int j = i; j > 0 && cuts.at[j].angle < cuts.at[j - 1].angle; --j) std::swap(cuts.at[j], cuts.at[j - 1]);
    return cuts;
}

/// Area moments about the disc centre: ∫ dA, ∫ ξ dA, ∫ ξ ξᵀ dA (unit disc).
struct AreaMoments {
    double m0 = 0, my = 0, mz = 0, myy = 0, myz = 0, mzz = 0;
};

/// ± the circular sector |ξ| <= r between rays a and b (Δ = b - a):
/// M0 = r² Δ/2, M1 = r³/3 (sin b - sin a, cos a - cos b),
/// M2 = r⁴/8 (Δ + (sin b cos b - sin a cos a), sin² b - sin² a, Δ - (sin b cos b - sin a cos a)).
inline void add_sector(AreaMoments& m, double sign, double r, const PieceEnd& a, const PieceEnd& b) {
    const double r2 = r * r, delta = b.angle - a.angle;
    const double k0 = sign * 0.5 * r2, k1 = sign * r2 * r / 3.0, k2 = sign * 0.125 * r2 * r2;
    const double sc = b.s * b.c - a.s * a.c;
    m.m0 += k0 * delta;
    m.my += k1 * (b.s - a.s);
    m.mz += k1 * (a.c - b.c);
    m.myy += k2 * (delta + sc);
    m.myz += k2 * (b.s * b.s - a.s * a.s);
    m.mzz += k2 * (delta - sc);
}

/// ± the triangle (0, p, q), D = p x q: M0 = D/2, M1 = D/6 (p + q),
/// M2 = D/12 (p pᵀ + q qᵀ + (p qᵀ + q pᵀ)/2).
inline void add_triangle(AreaMoments& m, double sign, double py, double pz, double qy, double qz) {
    const double det = sign * (py * qz - pz * qy);
    const double k1 = det / 6.0, k2 = det / 12.0;
    m.m0 += 0.5 * det;
    m.my += k1 * (py + qy);
    m.mz += k1 * (pz + qz);
    m.myy += k2 * (py * py + py * qy + qy * qy);
    m.myz += k2 * (py * pz + 0.5 * (py * qz + qy * pz) + qy * qz);
    m.mzz += k2 * (pz * pz + pz * qz + qz * qz);
}

/// ± the fan under the zero line between rays a and b: the triangle (0, L_a u_a, L_b u_b).
inline void add_line_fan(AreaMoments& m, double sign, const PieceEnd& a, const PieceEnd& b, double r0, double r1) {
    auto clamped = [&](double line) { return line > r0 ? (line < r1 ? line : r1) : r0; };  // NaN -> r0
    const double la = clamped(a.line), lb = clamped(b.line);
    add_triangle(m, sign, la * a.c, la * a.s, lb * b.c, lb * b.s);
}

/// The piece between rays a and b: compressed on arc r where |α - φ| > β, tested at the
/// piece's middle ray (no kink inside the piece, so the test holds on the whole piece); its
/// region is fan(outer bound) - fan(inner bound).
inline void add_piece(AreaMoments& m, const DiscElement& g, const GapField& f, const ArcCrossing& inner,
                      const ArcCrossing& outer, const PieceEnd& a, const PieceEnd& b) {
    double d = 0.5 * (a.angle + b.angle) - f.phi;  // in [-π, 3π]
    if (d > kPi) d -= 2.0 * kPi;
    const double from_axis = std::fabs(d);
    const bool inner_compressed = from_axis > inner.beta, outer_compressed = from_axis > outer.beta;
    if (outer_compressed) add_sector(m, 1.0, g.r1, a, b);        // [., r1]
    else if (inner_compressed) add_line_fan(m, 1.0, a, b, g.r0, g.r1);  // [r0, L]
    else return;                                                  // open along the piece
    if (inner_compressed) {
        if (g.r0 > 0.0) add_sector(m, -1.0, g.r0, a, b);  // [r0, .]
    } else {
        add_line_fan(m, -1.0, a, b, g.r0, g.r1);  // [L, r1]
    }
}

/// F = γ M0 + w.M1, P = γ M1 + M2 w, U = γ F + w.P from the compressed region's area moments.
inline CompressedPart part_of_moments(const GapField& f, const AreaMoments& m) {
    CompressedPart out;
    out.force = f.gamma * m.m0 + f.wy * m.my + f.wz * m.mz;
    out.py = f.gamma * m.my + f.wy * m.myy + f.wz * m.myz;
    out.pz = f.gamma * m.mz + f.wy * m.myz + f.wz * m.mzz;
    out.energy = f.gamma * out.force + f.wy * out.py + f.wz * out.pz;
    return out;
}

}  // namespace detail

/// The compressed part of element g under the gap field f, given the crossings of its inner and
/// outer arcs (arc_crossing at g.r0 and g.r1): the area moments of the compressed region in
/// closed form, piece by piece, then F = γ M0 + w.M1, P = γ M1 + M2 w, U = γ F + w.P.
/// Exact to round-off (the tests compare it with the disc's hand integrals).
inline CompressedPart compressed_part(const DiscElement& g, const GapField& f, const ArcCrossing& inner,
                                      const ArcCrossing& outer) {
    const detail::AngularCuts cuts = detail::angular_cuts(g, f, inner, outer);
    detail::AreaMoments m;
    for (int k = 0; k + 1 < cuts.count; ++k) detail::add_piece(m, g, f, inner, outer, cuts.at[k], cuts.at[k + 1]);
    return detail::part_of_moments(f, m);
}

}  // namespace gradem
