#pragma once
// Geometry of a flat joint's interface (docs/bond_laws.md, "Flat joint"): the bond disc of
// radius R̄ split into N_r x N_α annular-sector elements, and the integrals of a linear normal
// gap field over an element's compressed part.
//
// Element e: r in [r0, r1] = [i, i+1]/N_r, α in [a0, a1] = 2π [j, j+1]/N_α of the unit disc,
// measured in the joint's in-plane frame (t1, t2); index e = i N_α + j. Physical quantities
// scale with R̄: area A R̄², centroid x R̄, central second moments C R̄⁴.
//
// Gap field over the interface (tension/opening +): g(x) = γ + w.x, x in the contact plane
// from the contact point, with w = n x θ_b the gradient from the accumulated bending rotation
// θ_b. An unbonded element carries σ(x) = k̄_n min(g(x), 0) (no tension), so
//     F_n = ∫ σ dA,   P = ∫ σ x dA (its first moment: the moment on B is n x P),
//     U   = ½ ∫ σ²/k̄_n dA (its strain energy).
// Along a ray x = ρ u(α) the field is linear in ρ, so the radial integrals over the compressed
// part of [r0, r1] are exact polynomials; the angular integral is Gauss-Legendre (one node per
// 2π/32 at least, 4 per element at least) on each piece between the angles where the zero line
// crosses the element's arcs, so each piece integrates a smooth function.
//
// Speed (the law's slit and broken joints spend most of their time here): an element the zero
// line does not cut along its arcs is one piece whose nodes are the element's own, so their
// cos/sin and weights are tabulated once (FlatElementGeometry::node_cos, ...); a cut piece takes
// its nodes' cos/sin from sincos (the same libm call the per-node code made), then the ray
// integrals of all its nodes in one branch-free loop the compiler vectorises, then the sums in
// node order. Every value is computed by the same IEEE operations as before, so the results
// are bitwise those of the node-by-node code (the pinned hashes, tests/core/test_determinism.cpp).
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <math.h>  // sincos (GNU)
#include <utility>
#include <vector>

#include "core/vec3.hpp"

namespace gradem {

/// One element of the unit disc.
struct FlatElementGeometry {
    double area = 0;                   ///< A_e
    double inv_area = 0;               ///< 1/A_e
    double y = 0, z = 0;               ///< centroid in (t1, t2)
    double cyy = 0, czz = 0, cyz = 0;  ///< central ∫(y-y_e)² dA, ∫(z-z_e)² dA, ∫(y-y_e)(z-z_e) dA
    double polar = 0;                  ///< cyy + czz, the central polar moment
    double r0 = 0, r1 = 0;             ///< radial bounds
    double a0 = 0, a1 = 0;             ///< angular bounds [rad]
    double reach = 0;                  ///< max distance from the centroid to a point of the element
    std::vector<double> node, weight;  ///< angular Gauss-Legendre rule on [-1, 1]
    /// The rule on the whole element [a0, a1] (the uncut piece): cos and sin of the node angles
    /// mid + half node_q and the weights half weight_q (mid, half: the piece's centre and half width).
    std::vector<double> node_cos, node_sin, node_weight;
};

/// Most angular nodes per piece (the rule has max(4, ceil(32 / N_α)) <= 32).
inline constexpr std::size_t kMaxAngularNodes = 32;

/// cos a, sin a of a node angle: one libm sincos, the call GCC made of the std::cos/std::sin
/// pair of the node-by-node code (so the same bits).
inline void node_trig(double a, double& c, double& s) { ::sincos(a, &s, &c); }

/// Gauss-Legendre nodes and weights on [-1, 1] (Newton on P_m; exact to round-off).
inline std::pair<std::vector<double>, std::vector<double>> gauss_legendre(int m) {
    std::vector<double> x(static_cast<std::size_t>(m)), w(static_cast<std::size_t>(m));
    for (int i = 0; i < m; ++i) {
        double t = std::cos(kPi * (i + 0.75) / (m + 0.5));
        double dp = 1.0;
        for (int it = 0; it < 100; ++it) {
            double p0 = 1.0, p1 = t;
            for (int k = 2; k <= m; ++k) {
                const double p2 = ((2.0 * k - 1.0) * t * p1 - (k - 1.0) * p0) / k;
                p0 = p1;
                p1 = p2;
            }
            dp = m * (t * p1 - p0) / (t * t - 1.0);
            const double step = p1 / dp;
            t -= step;
            if (std::fabs(step) < 1e-16) break;
        }
        x[static_cast<std::size_t>(i)] = t;
        w[static_cast<std::size_t>(i)] = 2.0 / ((1.0 - t * t) * dp * dp);
    }
    return {x, w};
}

namespace detail {

/// Farthest point of the sector from its centroid: a corner, or the outer arc's point opposite
/// the centroid direction when that lies in the sector (distance along an edge is convex).
inline double sector_reach(const FlatElementGeometry& g, double a0, double a1) {
    double reach = 0.0;
    for (double r : {g.r0, g.r1})
        for (double a : {a0, a1}) reach = std::max(reach, std::hypot(r * std::cos(a) - g.y, r * std::sin(a) - g.z));
    double opposite = std::atan2(-g.z, -g.y);
    while (opposite < a0) opposite += 2.0 * kPi;
    if (opposite <= a1) reach = std::max(reach, g.r1 + std::hypot(g.y, g.z));
    return reach;
}

}  // namespace detail

/// The N_r x N_α elements of a unit disc, element index = i_r N_α + i_α.
inline std::vector<FlatElementGeometry> flat_joint_elements(std::int32_t nr, std::int32_t na) {
    std::vector<FlatElementGeometry> out;
    const double da = 2.0 * kPi / na;
    const int nodes = std::max(4, (32 + na - 1) / na);
    const auto [gx, gw] = gauss_legendre(nodes);
    for (std::int32_t ir = 0; ir < nr; ++ir) {
        const double r0 = static_cast<double>(ir) / nr, r1 = static_cast<double>(ir + 1) / nr;
        for (std::int32_t ia = 0; ia < na; ++ia) {
            const double a0 = ia * da, a1 = (ia + 1) * da;
            FlatElementGeometry g;
            g.r0 = r0;
            g.r1 = r1;
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
            g.reach = detail::sector_reach(g, a0, a1);
            g.node = gx;
            g.weight = gw;
            const double mid = 0.5 * (a0 + a1), half = 0.5 * (a1 - a0);  // as compressed_part's uncut piece
            for (std::size_t q = 0; q < gx.size(); ++q) {
                double c = 0, s = 0;
                node_trig(mid + half * gx[q], c, s);
                g.node_cos.push_back(c);
                g.node_sin.push_back(s);
                g.node_weight.push_back(half * gw[q]);
            }
            out.push_back(std::move(g));
        }
    }
    return out;
}

/// ∫ min(γ + sρ, 0) ρ^p dρ over [r0, r1] for p = 1, 2, and ∫ min(γ + sρ, 0)² ρ dρ.
struct RayIntegrals {
    double i1 = 0, i2 = 0, e1 = 0;
};

/// Branch-free (selects; the loop over nodes vectorises): the compressed part [a, b] of the ray,
/// γ + sρ < 0, and its polynomial integrals, or zeros when it is empty.
inline RayIntegrals compressed_ray(double gamma, double s, double r0, double r1) {
    const double root = -gamma / s;  // s = 0: not used
    const double b = s > 0.0 ? std::min(r1, root) : r1;
    const double a = s < 0.0 ? std::max(r0, root) : r0;
    const bool empty = s == 0.0 ? !(gamma < 0.0) : !(b > a);
    const double a2 = a * a, b2 = b * b, a3 = a2 * a, b3 = b2 * b, a4 = a2 * a2, b4 = b2 * b2;
    const double i1 = gamma * (b2 - a2) / 2.0 + s * (b3 - a3) / 3.0;
    const double i2 = gamma * (b3 - a3) / 3.0 + s * (b4 - a4) / 4.0;
    const double e1 = gamma * gamma * (b2 - a2) / 2.0 + 2.0 * gamma * s * (b3 - a3) / 3.0 + s * s * (b4 - a4) / 4.0;
    return {empty ? 0.0 : i1, empty ? 0.0 : i2, empty ? 0.0 : e1};
}

/// The compressed part of one element of the unit disc under g = γ + w.ξ (ξ, w in (t1, t2)
/// components of the unit disc): ∫ min(g,0) dA, ∫ min(g,0) ξ dA, ∫ min(g,0)² dA.
struct CompressedPart {
    double force = 0;         ///< ∫ min(g, 0) dA
    double py = 0, pz = 0;    ///< ∫ min(g, 0) ξ dA
    double energy = 0;        ///< ∫ min(g, 0)² dA
};

namespace detail {

/// The angles in (a0, a1) where the zero line γ + w.ξ = 0 crosses the arcs r0 and r1 (the
/// kinks of the angular integrand), sorted, with a0 and a1 at the ends.
struct AngularCuts {
    double at[6];  ///< a0, up to four kinks, a1
    int count = 0;
};

inline AngularCuts angular_pieces(const FlatElementGeometry& g, double gamma, double wy, double wz) {
    AngularCuts cuts;
    cuts.at[cuts.count++] = g.a0;
    const double slope = std::hypot(wy, wz), direction = std::atan2(wz, wy);
    for (double r : {g.r0, g.r1}) {
        if (!(r > 0.0 && slope > 0.0)) continue;
        const double c = -gamma / (slope * r);  // cos(α - direction) on the zero line
        if (!(c > -1.0 && c < 1.0)) continue;
        for (double a : {direction + std::acos(c), direction - std::acos(c)}) {
            while (a < g.a0) a += 2.0 * kPi;
            while (a >= g.a0 + 2.0 * kPi) a -= 2.0 * kPi;
            if (a > g.a0 && a < g.a1 && cuts.count < 5) cuts.at[cuts.count++] = a;  // at most 4 kinks
        }
    }
    cuts.at[cuts.count++] = g.a1;
    for (int i = 1; i < cuts.count; ++i)  // insertion sort of at most 6 angles
        for (int j = i; j > 0 && cuts.at[j] < cuts.at[j - 1]; --j) std::swap(cuts.at[j], cuts.at[j - 1]);
    return cuts;
}

}  // namespace detail

namespace detail {

/// One piece's nodes: cos, sin and weight of each [-], and the count.
struct PieceNodes {
    double c[kMaxAngularNodes], s[kMaxAngularNodes], w[kMaxAngularNodes];
    std::size_t count = 0;
};

/// Adds the piece's nodes to `out`, in node order: F += w i1, P += w i2 (cos, sin), U += w e1.
inline void add_piece(CompressedPart& out, const double* c, const double* sn, const double* w, std::size_t count,
                      double gamma, double wy, double wz, double r0, double r1) {
    double tf[kMaxAngularNodes], ty[kMaxAngularNodes], tz[kMaxAngularNodes], te[kMaxAngularNodes];
    for (std::size_t q = 0; q < count; ++q) {  // vectorised: the ray integrals of every node
        const RayIntegrals r = compressed_ray(gamma, wy * c[q] + wz * sn[q], r0, r1);
        tf[q] = w[q] * r.i1;
        ty[q] = w[q] * r.i2 * c[q];
        tz[q] = w[q] * r.i2 * sn[q];
        te[q] = w[q] * r.e1;
    }
    for (std::size_t q = 0; q < count; ++q) {  // the sums in node order
        out.force += tf[q];
        out.py += ty[q];
        out.pz += tz[q];
        out.energy += te[q];
    }
}

}  // namespace detail

/// Radial integrals exact, angular Gauss-Legendre on each piece between kinks (so the rule
/// integrates a smooth function on each): measured against the closed-form disc integrals to
/// 5e-6 relative or better (tests/core/test_flat_joint_interface.cpp).
inline CompressedPart compressed_part(const FlatElementGeometry& g, double gamma, double wy, double wz) {
    CompressedPart out;
    const detail::AngularCuts cuts = detail::angular_pieces(g, gamma, wy, wz);
    const std::size_t n = std::min(g.node.size(), kMaxAngularNodes);
    if (cuts.count == 2 && g.node_cos.size() == n) {  // uncut: the element's own tabulated nodes
        detail::add_piece(out, g.node_cos.data(), g.node_sin.data(), g.node_weight.data(), n, gamma, wy, wz, g.r0, g.r1);
        return out;
    }
    detail::PieceNodes nodes;
    nodes.count = n;
    for (int piece = 0; piece + 1 < cuts.count; ++piece) {
        const double mid = 0.5 * (cuts.at[piece] + cuts.at[piece + 1]), half = 0.5 * (cuts.at[piece + 1] - cuts.at[piece]);
        for (std::size_t q = 0; q < n; ++q) {
            node_trig(mid + half * g.node[q], nodes.c[q], nodes.s[q]);
            nodes.w[q] = half * g.weight[q];
        }
        detail::add_piece(out, nodes.c, nodes.s, nodes.w, n, gamma, wy, wz, g.r0, g.r1);
    }
    return out;
}

}  // namespace gradem
