#pragma once
// The flat joint's joints in structure-of-arrays lanes (JointLanes) and the kernels that run a
// set of them (core/flat_joint_pass_lanes.cpp): the arithmetic of FlatJointLaw::step across
// kJointLanes joints at once, and the copies of the joints' state into lanes and back
// (load_joints, store_joints). core/flat_joint_pass.cpp, the law's pass, fills the sets and hands
// their joints to the scalar kernel where a lane cannot finish.
#include <cstddef>
#include <cstdint>
#include <span>

#include "core/bond_law.hpp"
#include "core/bond_pass.hpp"
#include "core/disc_elements.hpp"
#include "core/particles.hpp"
#include "core/vec3.hpp"

namespace gradem::flat_lanes {

inline constexpr int kJointLanes = 16;
inline constexpr std::size_t kMaxLaneElements = 8;  ///< joints with more elements take the scalar path

/// Inputs, intermediates and results of up to kJointLanes joints (structure of arrays).
struct JointLanes {
    int count = 0;
    // inputs: the pair's particles, the joint's header and element shear forces, its constants
    double xa[3][kJointLanes], xb[3][kJointLanes], va[3][kJointLanes], vb[3][kJointLanes];
    double wa[3][kJointLanes], wb[3][kJointLanes], ra[kJointLanes], rb[kJointLanes];
    double axis[3][kJointLanes], bend[3][kJointLanes], twist[kJointLanes], normal[kJointLanes];
    double scale[kJointLanes], radius[kJointLanes], kn[kJointLanes], ks[kJointLanes];
    double strength[kJointLanes], cohesion[kJointLanes], tan_phi[kJointLanes];
    double shear[kMaxLaneElements][2][kJointLanes];  ///< F_s,e in (t1, t2): in, then out [N]
    // inputs of joints not fully bonded: elements' bonded flags (1/0), g_0 [m], μ_r, ρ (the
    // unbonded elements' share of k̄_n), the surface gap beyond which a separated joint is released [m]
    double bonded[kMaxLaneElements][kJointLanes];
    double gap0[kJointLanes], friction[kJointLanes], unbonded_kn[kJointLanes], release_gap[kJointLanes];
    // the frame and step constants after this step's increments
    double t1[3][kJointLanes], t2[3][kJointLanes], n[3][kJointLanes], arm_b[3][kJointLanes];
    double wy[kJointLanes], wz[kJointLanes], w_norm[kJointLanes], gap[kJointLanes], bend_total[3][kJointLanes];
    double jkn[kJointLanes], jks[kJointLanes], R2[kJointLanes], ksR4[kJointLanes], inv_ks_r2[kJointLanes];
    double du1[kJointLanes], du2[kJointLanes], dtwist[kJointLanes];
    // element sums and results
    double s1[kJointLanes], s2[kJointLanes], fn[kJointLanes], p1[kJointLanes], p2[kJointLanes];
    double tw[kJointLanes], stored[kJointLanes], fails[kJointLanes];
    double slip[kJointLanes], any_bonded[kJointLanes], all_open[kJointLanes];  ///< joints not fully bonded
    // each element's normal load (joints not fully bonded): F_n, P, energy, and whether the zero
    // line cuts it; whether it cuts any of the joint's
    double el_fn[kMaxLaneElements][kJointLanes], el_p1[kMaxLaneElements][kJointLanes];
    double el_p2[kMaxLaneElements][kJointLanes], el_energy[kMaxLaneElements][kJointLanes];
    double el_cut[kMaxLaneElements][kJointLanes], any_cut[kJointLanes];
    double force[3][kJointLanes], torque[3][kJointLanes], shear_res[3][kJointLanes], bend_res[3][kJointLanes];
};

inline Vec3 lane(const double (&a)[3][kJointLanes], int l) { return {a[0][l], a[1][l], a[2][l]}; }
inline void set_lane(double (&a)[3][kJointLanes], int l, const Vec3& v) {
    a[0][l] = v.x;
    a[1][l] = v.y;
    a[2][l] = v.z;
}

/// Where the joints keep their state, per bond k: `stride` doubles of side state from
/// side + k * stride (core/flat_joint_law.hpp, flat_side), its constants, its record.
struct JointStore {
    double* side;
    std::size_t stride;
    const BondConstants* constants;
    ParallelBond* bonds;
};

/// Lanes [0, count) from their joints' state (bond[l]: lane l's bond): the header (t1, θ_b, θ_t,
/// U_n, g_0, the stiffness scale, the release gap), the elements' bonded flags and shear forces,
/// R̄, k̄_n and k̄_s. Four lanes at a time by transposes where the processor has AVX2.
void load_joints(JointLanes& L, const JointStore& store, const std::int64_t* bond, int count, std::size_t elements);

/// The lanes of [0, count) whose joints took the common path (L.fails 0) into their joints'
/// state: the new header (t1, θ_b, θ_t, U_n), element shear forces and the resultant in the bond
/// record (F̄_n, F̄_s, M̄_t, M̄_b). Lanes that fail keep their joint's old state.
void store_joints(const JointLanes& L, const JointStore& store, const std::int64_t* bond, int count,
                  std::size_t elements);

/// The particles of a set's lanes [0, count): positions, velocities and spins of both ends (the
/// lanes past it keep their dummies).
void load_particles(JointLanes& L, const ParticleSet& particles, const std::int32_t* ia, const std::int32_t* ib,
                    int count);

/// A set of fully bonded joints (intact, every element bonded) through the law's bonded branch:
/// each lane's frame, elements and resultant; L.fails marks the lanes where an element failed.
void joint_lanes(JointLanes& L, double dt, std::span<const DiscElement> elements);

/// A set of joints not fully bonded (partly bonded, slit, gapped, broken) through the law: frame,
/// each element's normal load, the elements the zero line cuts, the shear with its Coulomb cap,
/// the joints to release and the resultant; L.fails marks the lanes the scalar kernel must run.
void mixed_joint_lanes(JointLanes& L, double dt, std::span<const DiscElement> elements);

/// Every lane's inputs a harmless dummy joint: the kernels run over all kJointLanes lanes.
void dummy_inputs(JointLanes& L);

}  // namespace gradem::flat_lanes
