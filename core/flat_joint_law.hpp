#pragma once
// Flat joint (Potyondy 2012 semantics, 3D; models.md §3 "First implementation"). The interface
// is the bond disc of radius R̄ = λ̄ min(R_A, R_B) (bond_law.hpp), split into N_r x N_α
// annular-sector elements e: r in R̄ [i, i+1]/N_r, α in 2π [j, j+1]/N_α, measured in a frame
// (t1, t2) of the contact plane that is installed once and then carried with the pair
// (rotate_into_plane, like the stored shear force). Each element has area A_e, centroid x_e and
// central second moments C_e (2x2 tensor in (t1, t2)), and its own state: bonded flag, centroid
// opening δ_e [m] (tension +) and shear force F_s,e on B [N]. Per step, with the pair's
// increments (pair_kinematics.hpp):
//     δ_e  += dU_n + (dθ_b x x_e).n            F_s,e = rot(F_s,e) - k̄_s A_e (dU_s + dθ_t n x x_e)
// Bonded element: F_n,e = k̄_n A_e δ_e (tension +), plus its own bending moment -k̄_n C_e θ_b and
// twist moment -k̄_s (C_yy + C_zz) θ_t n from the joint's accumulated rotations θ_b, θ_t (the
// linear stress field over the element; with every element bonded the joint has exactly the
// parallel bond's k̄_n Ā, k̄_s Ā, k̄_n Ī, k̄_s J̄). Breaks in tension if σ_e = F_n,e/A_e >= σ̄_c,
// else in shear if τ_e = |F_s,e|/A_e >= c̄ - min(σ_e, σ̄_c) tan φ̄.
// Broken element: compression only, F_n,e = k̄_n A_e min(δ_e, 0) at its centroid, and Coulomb
// friction |F_s,e| <= μ |F_n,e| (μ = FlatJointParams::residual_friction); slip energy is counted.
// So a partly broken joint still resists rotation through its compressed elements.
// Resultant on B about the contact point: F = Σ (F_s,e - F_n,e n), M = Σ x_e x f_e + own moments.
// The bond record holds that resultant (normal_force = -F.n, etc.).
// Cracks: one BreakEvent per element break (element index, centroid position); when the last
// element breaks the whole joint is released (its remaining compression energy goes to
// bond_break) and the pair continues as a plain linear contact.
// Simplifications (stated): element stresses are centroid averages (no β̄, no bending stress
// within an element, so a 1x1 joint cannot break in pure bending); a broken element acts at its
// centroid only (no partly open elements, no own moment); no residual cohesion (fj_cohres), no
// gapped/slit elements; a fully broken joint hands over to the linear contact (PFC keeps the
// joint as a frictional interface of elements).
// Contact: by default (BondParams::replaces_contact) an intact joint REPLACES the pair's linear
// contact (PFC's flatjoint is the pair's whole contact model): its elements alone carry
// compression; replaces_contact = false keeps the contact in parallel. Installed at zero force.
// Time step: the undamaged disc (= parallel bond).
#include <cmath>
#include <span>
#include <vector>

#include "core/parallel_bond_law.hpp"

namespace gradem {

/// Geometry of one element of a unit-radius joint (scale: A R̄², x R̄, C R̄⁴).
struct FlatElementGeometry {
    double area = 0;               ///< A_e
    double y = 0, z = 0;           ///< centroid in (t1, t2)
    double cyy = 0, czz = 0, cyz = 0;  ///< central ∫(y-y_e)² dA, ∫(z-z_e)² dA, ∫(y-y_e)(z-z_e) dA
};

/// The N_r x N_α elements of a unit disc, element index = i_r N_α + i_α.
inline std::vector<FlatElementGeometry> flat_joint_elements(std::int32_t nr, std::int32_t na) {
    std::vector<FlatElementGeometry> out;
    const double da = 2.0 * kPi / na;
    for (std::int32_t ir = 0; ir < nr; ++ir) {
        const double r0 = static_cast<double>(ir) / nr, r1 = static_cast<double>(ir + 1) / nr;
        for (std::int32_t ia = 0; ia < na; ++ia) {
            const double a0 = ia * da, a1 = (ia + 1) * da;
            FlatElementGeometry g;
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
            out.push_back(g);
        }
    }
    return out;
}

/// The installed in-plane axis t1 for normal n: n x (the axis of n's smallest component).
inline Vec3 flat_joint_initial_axis(const Vec3& n) {
    const double ax = std::fabs(n.x), ay = std::fabs(n.y), az = std::fabs(n.z);
    const Vec3 e = (ax <= ay && ax <= az) ? Vec3{1, 0, 0} : (ay <= az ? Vec3{0, 1, 0} : Vec3{0, 0, 1});
    const Vec3 t = cross(n, e);
    return (1.0 / norm(t)) * t;
}

/// Side-state layout: t1 (3), θ_b (3), θ_t (1), then per element: bonded, δ_e, F_s,e (3).
inline constexpr std::size_t kFlatJointHeader = 7, kFlatElementSize = 5;

struct FlatElementState {
    bool bonded = true;
    double opening = 0.0;  ///< δ_e [m], tension +
    Vec3 shear_force;      ///< F_s,e on B [N]
};

inline FlatElementState flat_joint_element(std::span<const double> s, std::size_t e) {
    const double* p = s.data() + kFlatJointHeader + e * kFlatElementSize;
    return {p[0] != 0.0, p[1], {p[2], p[3], p[4]}};
}
inline Vec3 flat_joint_axis(std::span<const double> s) { return {s[0], s[1], s[2]}; }

struct FlatJointLaw {
    static constexpr BondModel kModel = BondModel::flat_joint;

    struct Context {
        std::vector<FlatElementGeometry> elements;
        double tan_phi = 0.0, friction = 0.5;
        bool track = true;
    };
    static Context context(const BondParams& p, bool track) {
        return {flat_joint_elements(p.flat.radial_elements, p.flat.angular_elements),
                std::tan(p.friction_angle_deg * kPi / 180.0), p.flat.residual_friction, track};
    }
    static std::size_t side_size(const BondParams& p) {
        return kFlatJointHeader + kFlatElementSize * static_cast<std::size_t>(p.flat.radial_elements) *
                                      static_cast<std::size_t>(p.flat.angular_elements);
    }
    static void install(const BondParams& p, const Vec3& normal, double* side) {
        const Vec3 t = flat_joint_initial_axis(normal);
        side[0] = t.x, side[1] = t.y, side[2] = t.z;
        const std::size_t n = (side_size(p) - kFlatJointHeader) / kFlatElementSize;
        for (std::size_t e = 0; e < n; ++e) side[kFlatJointHeader + e * kFlatElementSize] = 1.0;
    }

    static BondStepResult step(const Context& c, ParallelBond& b, double* side,
                               const BondSection& sec, const BondStiffness& k,
                               const PairKinematics& kin, std::vector<BondBreak>& breaks) {
        BondStepResult r;
        const Vec3& n = kin.normal;
        // Frame and accumulated rotations, carried into the current plane.
        Vec3 t1 = rotate_into_plane({side[0], side[1], side[2]}, kin);
        t1 = (1.0 / norm(t1)) * t1;
        const Vec3 t2 = cross(n, t1);
        const Vec3 bend = rotate_into_plane({side[3], side[4], side[5]}, kin) + kin.bend_angle;
        const double twist = side[6] + kin.twist_angle;
        side[0] = t1.x, side[1] = t1.y, side[2] = t1.z;
        side[3] = bend.x, side[4] = bend.y, side[5] = bend.z;
        side[6] = twist;
        const double a = dot(bend, t1), bb = dot(bend, t2);  // θ_b in (t1, t2) [rad]
        const double R = sec.radius, R2 = R * R, R4 = R2 * R2;

        Vec3 force, moment;
        double stored = 0.0;
        bool any_bonded = false;
        BondState last_mode = BondState::intact;
        for (std::size_t e = 0; e < c.elements.size(); ++e) {
            const FlatElementGeometry& g = c.elements[e];
            double* p = side + kFlatJointHeader + e * kFlatElementSize;
            const Vec3 x = (R * g.y) * t1 + (R * g.z) * t2;  // centroid from the contact point
            const double area = R2 * g.area;
            const double kna = k.normal * area, ksa = k.shear * area;
            const double opening = p[1] + kin.du_normal + dot(cross(kin.bend_angle, x), n);
            const Vec3 du = kin.du_shear + kin.twist_angle * cross(n, x);
            const Vec3 rotated = rotate_into_plane({p[2], p[3], p[4]}, kin);
            Vec3 shear = rotated - ksa * du;
            bool bonded = p[0] != 0.0;
            // Own bending/twist energy of a bonded element (linear field over it) [J].
            const double own_energy = 0.5 * k.normal * R4 * (g.czz * a * a - 2.0 * g.cyz * a * bb + g.cyy * bb * bb) +
                                      0.5 * k.shear * R4 * (g.cyy + g.czz) * twist * twist;
            bool broke_now = false;
            double energy_before = 0.0;
            if (bonded) {
                const double sigma = k.normal * opening;           // σ_e [Pa]
                const double tau = norm(shear) / area;              // τ_e [Pa]
                const double capped = sigma < b.tensile_strength ? sigma : b.tensile_strength;
                BondState mode = BondState::intact;
                if (sigma >= b.tensile_strength) mode = BondState::broken_tension;
                else if (tau >= b.cohesion - capped * c.tan_phi) mode = BondState::broken_shear;
                if (mode != BondState::intact) {
                    energy_before = 0.5 * (kna * opening * opening + norm2(shear) / ksa) + own_energy;
                    breaks.push_back({mode, static_cast<std::int32_t>(e), x, sigma, tau});
                    bonded = false;
                    broke_now = true;
                    last_mode = mode;
                }
            }
            double fn;  // F_n,e, tension + [N]
            if (bonded) {
                fn = kna * opening;
            } else {
                fn = opening < 0.0 ? kna * opening : 0.0;
                const double limit = -c.friction * fn;
                const double s2 = norm2(shear);
                if (s2 > limit * limit) {
                    const Vec3 capped = (s2 > 0.0 ? limit / std::sqrt(s2) : 0.0) * shear;
                    if (!broke_now && c.track)
                        r.slip += -0.5 * dot(rotated + capped, du) -
                                  0.5 * (norm2(capped) - norm2(rotated)) / ksa;
                    shear = capped;
                }
            }
            const double energy = 0.5 * (fn * fn / kna + norm2(shear) / ksa) + (bonded ? own_energy : 0.0);
            if (broke_now) r.released += energy_before - energy;
            stored += energy;
            p[0] = bonded ? 1.0 : 0.0;
            p[1] = opening;
            p[2] = shear.x, p[3] = shear.y, p[4] = shear.z;

            const Vec3 f = shear - fn * n;
            force += f;
            moment += cross(x, f);
            if (bonded) {
                any_bonded = true;
                moment -= (k.normal * R4) * ((a * g.czz - bb * g.cyz) * t1 + (bb * g.cyy - a * g.cyz) * t2);
                moment -= (k.shear * R4 * (g.cyy + g.czz) * twist) * n;
            }
        }
        if (!any_bonded) {  // the last element broke: the joint is released as a whole
            if (c.track) r.released += stored;
            release_bond(b, last_mode == BondState::intact ? BondState::broken_tension : last_mode);
            r.failure = b.state;
            return r;
        }
        if (!c.track) r.released = 0.0;
        if (c.track) r.stored = stored;
        b.normal_force = -dot(force, n);
        b.shear_force = force + b.normal_force * n;
        b.twist_moment = dot(moment, n);
        b.bend_moment = moment - b.twist_moment * n;
        r.force_j = force;
        r.moment_j = moment;
        return r;
    }

    static TimeStepStiffness time_step_stiffness(const BondSection& s, const BondStiffness& k,
                                                 double r) {
        return disc_time_step_stiffness(s, k, r);
    }
};

}  // namespace gradem
