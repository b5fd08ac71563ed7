#pragma once
// Geometry and relative motion of a particle pair over one step, shared by the linear-contact
// and parallel-bond kernels. Conventions (docs/model.md "Conventions"): the unit normal n points from A to B;
// gap g = |x_B - x_A| - R_A - R_B (g < 0 is overlap); the contact point sits in the middle of
// the gap, x_C = x_A + (R_A + g/2) n. The relative displacement increment of B with respect to
// A at x_C over the step is
//     dU = [(v_B + w_B x (x_C - x_B)) - (v_A + w_A x (x_C - x_A))] dt,
// split into dU_s = dU - (dU.n) n and the normal part. The normal part is taken as the exact
// change of the centre distance, dU_n = |d| - |d_prev| (positive = opening), which equals dU.n
// to first order but is objective: a rigid rotation of the pair, however fast, leaves it zero
// (rotation of spins moves x_C only within the contact plane). The relative rotation
// increment dθ = (w_B - w_A) dt splits into twist (dθ.n) and bending dθ_b = dθ - (dθ.n) n.
// Velocities are those that carried the particles to their current positions (leap-frog,
// half a step behind), so the previous normal is recovered from x - v dt without storing it.
#include "core/vec3.hpp"

namespace gradem {

/// c ? a : b component by component (a select of doubles, not of a struct, so a loop that
/// uses it stays branch-free and vectorises; by value: a select of references became a load from
/// a selected address, which blocks vectorisation).
inline Vec3 select(bool c, Vec3 a, Vec3 b) {
    return {c ? a.x : b.x, c ? a.y : b.y, c ? a.z : b.z};
}

struct PairKinematics {
    Vec3 normal;          ///< n, unit, A -> B
    Vec3 previous_normal; ///< n one step earlier (from x - v dt)
    Vec3 tilt;            ///< n_prev x n: small rotation of the contact plane [rad]
    double gap = 0.0;     ///< g [m]
    Vec3 arm_a;           ///< x_C - x_A [m]
    Vec3 arm_b;           ///< x_C - x_B [m]
    Vec3 du_shear;        ///< dU_s [m]
    double du_normal = 0; ///< dU_n [m], positive = opening
    double twist_angle = 0;  ///< dθ.n [rad]
    Vec3 bend_angle;      ///< dθ_b [rad]
    double mean_twist = 0;   ///< ½ (w_A + w_B).n dt [rad], rotation of the plane about n
};

struct PairState {
    Vec3 xa, xb, va, vb, wa, wb;
    double ra, rb;
};

/// Kinematics of pair (A, B) for a step of length dt [s].
inline PairKinematics pair_kinematics(const PairState& s, double dt) {
    // Locals first, one aggregate at the end: no zero-fill of the 200-byte result before the
    // fields are written (a zero-fill compiles to a rep stos on the hot path).
    const Vec3 d = s.xb - s.xa;
    const double dist = norm(d);
    // Reciprocals taken unconditionally and the zero-length case selected after (the same bits
    // where dist > 0; branch-free, so the loop over pairs vectorises: world_pairs.cpp).
    const double inv_dist = 1.0 / dist;
    const Vec3 normal = select(dist > 0.0, inv_dist * d, Vec3{1.0, 0.0, 0.0});
    const Vec3 d_prev = d - dt * (s.vb - s.va);
    const double dist_prev = norm(d_prev);
    const double inv_dist_prev = 1.0 / dist_prev;
    const Vec3 previous_normal = select(dist_prev > 0.0, inv_dist_prev * d_prev, normal);
    const double gap = dist - s.ra - s.rb;
    const Vec3 arm_a = (s.ra + 0.5 * gap) * normal;
    // Spin terms use mid-step lever arms (from the mean of the old and new normals), so the
    // increment is second-order accurate: a rigid rotation gives O(theta^3) per step, not O(theta^2).
    const Vec3 arm_a_mid = (s.ra + 0.5 * gap) * (0.5 * (normal + previous_normal));
    const Vec3 arm_b_mid = arm_a_mid - 0.5 * (d + d_prev);
    const Vec3 du = dt * ((s.vb + cross(s.wb, arm_b_mid)) - (s.va + cross(s.wa, arm_a_mid)));
    const Vec3 dtheta = dt * (s.wb - s.wa);
    const double twist_angle = dot(dtheta, normal);
    return PairKinematics{
        .normal = normal,
        .previous_normal = previous_normal,
        .tilt = cross(previous_normal, normal),
        .gap = gap,
        .arm_a = arm_a,
        .arm_b = arm_a - d,
        .du_shear = du - dot(du, normal) * normal,
        .du_normal = dist - dist_prev,
        .twist_angle = twist_angle,
        .bend_angle = dtheta - twist_angle * normal,
        .mean_twist = 0.5 * dt * dot(s.wa + s.wb, normal),
    };
}

/// Carries a vector stored in the old contact plane into the new one: small rotation about
/// n_old x n_new (the plane tilt), then about n by the mean spin (P&C 2004; YADE ScGeom::rotate),
/// then projection onto the new plane. The magnitude changes by O(theta^2) per step (theta the
/// rotation per step, ~1e-7 rad in a quasi-static test), which is negligible.
/// A zero vector is returned as it is (bit for bit, signed zeros included); branch-free.
inline Vec3 rotate_into_plane(const Vec3& v, const PairKinematics& k) {
    const bool zero = (v.x == 0.0) & (v.y == 0.0) & (v.z == 0.0);
    Vec3 r = v - cross(v, k.tilt);
    r = r - cross(r, k.mean_twist * k.normal);
    r = r - dot(r, k.normal) * k.normal;
    return select(zero, v, r);
}

}  // namespace gradem
