#pragma once
// Two spheres joined by one bond: A at the origin, B on +x; both driven kinematically
// (prescribed velocity and spin), so the bond sees exactly the imposed relative motion.
#include <catch2/catch.hpp>

#include "core_fixtures.hpp"

namespace gradem::test {

inline constexpr double kRigRadius = 1.0e-3;   // both radii [m]
inline constexpr double kRigGap = 1.0e-9;      // installation gap: keeps the linear part inactive
inline constexpr double kRigModulus = 1.0e10;  // Ē* [Pa]
inline constexpr double kRigKappa = 1.5;

inline BondParams rig_bond(BondModel model) {
    BondParams b;
    b.model = model;
    b.effective_modulus = kRigModulus;
    b.stiffness_ratio = kRigKappa;
    b.tensile_strength_mean = 1.0e12;
    b.cohesion_mean = 1.0e12;
    return b;
}

/// A flat joint of N_r x N_α elements on the rig's stiffness, residual friction 0.5.
inline BondParams joint(std::int32_t nr, std::int32_t na) {
    BondParams bp = rig_bond(BondModel::flat_joint);
    bp.law<FlatJointLaw>().radial_elements = nr;
    bp.law<FlatJointLaw>().angular_elements = na;
    bp.law<FlatJointLaw>().residual_friction = 0.5;
    return bp;
}

struct BondRig {
    World world;
    BondSection section;
    BondStiffness stiffness;
    double dt = 1.0e-7;
    double rest_distance;

    /// `reach`: the largest gap bonds are installed across (default 2 gap + 1e-12 m).
    explicit BondRig(const BondParams& bp, double gap = kRigGap, double reach = -1.0)
        : world(sphere_pair(kRigRadius, kRigRadius, gap), frictionless(bp.effective_modulus),
                undamped()),
          section(bond_section(bp.radius_multiplier, kRigRadius, kRigRadius)),
          stiffness(bond_stiffness(bp.effective_modulus, bp.stiffness_ratio, kRigRadius, kRigRadius)),
          rest_distance(2.0 * kRigRadius + gap) {
        ParticleSet& p = world.edit_particles();
        p.flags[0] = p.flags[1] = kFixedVelocity | kFixedSpin;
        REQUIRE(world.install_bonds(bp, reach < 0.0 ? 2.0 * gap + 1.0e-12 : reach) == 1);
        world.set_time_step(dt);
    }
    const ParallelBond& bond() const { return world.bonds().front(); }
    bool intact() const { return bond().state == BondState::intact; }
    /// Opening of the pair since installation [m].
    double opening() const {
        const ParticleSet& p = world.particles();
        return norm(p.position[1] - p.position[0]) - rest_distance;
    }
    /// Axial stress the bond transmits, F_n/Ā [Pa], tension positive.
    double axial_stress() const { return bond().normal_force * section.inv_area; }
    void set_motion(const Vec3& vb, const Vec3& wb, const Vec3& wa = {}) {
        world.set_particle_motion(0, {}, wa);
        world.set_particle_motion(1, vb, wb);
    }
};

}  // namespace gradem::test
