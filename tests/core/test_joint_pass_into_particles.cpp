// The flat joint's pass adds each joint's force and moments to the particles whose pairs are all
// acting joints in one thread's share of the bond blocks, in bond order (SimParams::forces_in_pass;
// core/flat_joint_pass.cpp), instead of writing the joint's slot for the gather. That must be
// unobservable: the particles' sums, the slots as read (rebuilt from the bonds), the unbalanced-
// force ratio and the crack log bit for bit those of the slots and the gather, for any thread
// count, through breaks and releases (a released joint's particles go back to the gather).
#include <catch2/catch.hpp>

#include "bond_rig.hpp"
#include "core/contact_law.hpp"
#include "core_fixtures.hpp"
#include "forces_in_pass_check.hpp"
#include "../with_threads.hpp"

using namespace gradem;
using namespace gradem::test;

namespace {

// Flat joints (N_r 1, N_α 4) in a 12^3 cluster (3 bond blocks: the shares of 2 and 3 threads
// split particles' joints) squeezed between platens past its first releases; `mixed`: bonded,
// gapped and slit joints with a friction angle.
World squeezed_joints(const SimParams& sim, bool mixed) {
    World world(jittered_cluster(12, 1.0e-3, 99), platen_scene_contact(), sim);
    BondParams bp;
    bp.model = BondModel::flat_joint;
    bp.effective_modulus = 1.0e9;
    bp.tensile_strength_mean = 1.0e6;
    bp.tensile_strength_std = 0.3e6;
    bp.cohesion_mean = 2.0e6;
    bp.cohesion_std = 0.5e6;
    if (mixed) {
        auto& joint = bp.law<FlatJointLaw>();
        joint.bonded_fraction = 0.6;
        joint.gapped_fraction = 0.2;
        joint.gap_ratio = 0.01;
        joint.stiffness_over_gap = true;
        bp.friction_angle_deg = 25.0;
    }
    world.install_bonds(bp, 0.5e-3);
    add_platens(world, 0.6);
    return world;
}

/// What the run reads of its forces after `steps` steps, with its crack log (bond, step) and its
/// released joints' count as `other`.
ForcesSeen squeeze(int threads, bool forces_in_pass, bool mixed, int steps) {
    SimParams sim;
    sim.forces_in_pass = forces_in_pass;
    return with_threads(threads, [&] {
        World world = squeezed_joints(sim, mixed);
        world.run(steps);
        ForcesSeen f = forces_seen(world);
        for (const BreakEvent& e : world.break_events()) {
            f.other.push_back(static_cast<std::uint64_t>(e.bond));
            f.other.push_back(static_cast<std::uint64_t>(e.step));
        }
        std::uint64_t released = 0;
        for (const ParallelBond& b : world.bonds()) released += !bond_acts(b);
        f.other.push_back(released);
        return f;
    });
}

}  // namespace

TEST_CASE("flat joint pass into particles: forces, slots as read and crack log bitwise those of the slots",
          "[core][flat_joint][pair_pass]") {
    for (const bool mixed : {false, true}) {
        INFO((mixed ? "bonded, gapped and slit joints" : "bonded joints"));
        constexpr int kSteps = 3500;  // past the releases of separated joints (~40)
        const ForcesSeen slots = squeeze(1, false, mixed, kSteps);
        REQUIRE(slots.other.back() > 20);      // joints released: their particles went back to the gather
        REQUIRE(slots.other.size() > 4000);    // > 2000 breaks
        check_forces_in_pass([&](int threads, bool forces_in_pass) { return squeeze(threads, forces_in_pass, mixed, kSteps); });
    }
}

TEST_CASE("flat joint pass into particles: slots left behind are rebuilt before a set-up change, not after it",
          "[core][flat_joint][pair_pass]") {
    // The slots are rebuilt from the positions the forces were evaluated at (the moment on i
    // takes x_j - x_i): editing the particles after a step must not reach the slots of the
    // evaluation before it.
    auto slots_after_edit = [](int threads, bool forces_in_pass) {
        SimParams sim;
        sim.forces_in_pass = forces_in_pass;
        return with_threads(threads, [&] {
            World world = squeezed_joints(sim, false);
            world.run(300);
            for (Vec3& x : world.edit_particles().position) x = 1.01 * x;
            std::vector<std::uint64_t> out;
            for (const PairOutput& o : world.pair_outputs()) append_bits(out, o.torque_i);
            return out;
        });
    };
    const std::vector<std::uint64_t> written = slots_after_edit(1, false);
    for (int threads : {1, 2}) {
        INFO("threads " << threads);
        CHECK(slots_after_edit(threads, true) == written);
    }
}

TEST_CASE("flat joint pass into particles: a released joint's particles take the contact that follows",
          "[core][flat_joint][pair_pass]") {
    // One joint pulled until it is released, then pushed back into overlap within the Verlet
    // skin (no neighbour rebuild): from the step after the release the pair is a contact, which
    // the contacts phase writes into the slot, so the particles must be summed by the gather
    // again. The force on B is then exactly the linear contact's k_n δ.
    BondParams bp = rig_bond(BondModel::flat_joint);
    bp.tensile_strength_mean = 2.0e6;
    bp.cohesion_mean = 1.0e12;  // no shear break
    BondRig rig(bp, 0.0);
    REQUIRE(rig.world.sim_params().forces_in_pass);
    const double onset = bp.tensile_strength_mean / rig.stiffness.normal;  // δ_c [m]
    const int steps = 3000;
    rig.set_motion({3.0 * onset / (steps * rig.dt), 0, 0}, {});
    int step = 0;
    for (; step < steps && bond_acts(rig.bond()); ++step) rig.world.step();
    REQUIRE(step < steps);  // released while pulled
    REQUIRE(rig.world.profile().pair_steps_into_particles > 0);  // the joint went into the particles
    const std::int64_t rebuilds = rig.world.profile().rebuilds;
    const double overlap = 0.5 * onset;
    const double back = rig.opening() + overlap;
    rig.set_motion({-back / (200 * rig.dt), 0, 0}, {});
    for (int s = 0; s < 200; ++s) rig.world.step();
    REQUIRE(rig.world.profile().rebuilds == rebuilds);  // the owners were not built anew
    REQUIRE(-rig.opening() == Approx(overlap).epsilon(1e-6));
    const double contact_k = contact_normal_stiffness(kRigModulus, kRigRadius, kRigRadius);
    CHECK(rig.world.particles().force[1].x == Approx(contact_k * -rig.opening()).epsilon(1e-9));
}
