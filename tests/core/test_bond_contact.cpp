// Soft bond and flat joint with BondParams::replaces_contact (PFC softbond/flatjoint: one spring
// set). Oracles on one bonded pair driven kinematically (bond_rig.hpp), bond radius λ̄ = 0.5 so
// the bond's normal stiffness k̄_n Ā = Ē π (λ̄ R)²/(2R) is a quarter of the contact's
// k_n = E π R²/(2R) and the two cannot be confused:
//   * intact, compressed by δ: the pair's force is exactly k̄_n Ā δ (replaces_contact = true), or
//     (k̄_n Ā + k_n) δ with the contact in parallel (replaces_contact = false);
//   * broken (pulled past its cut-off / every element broken), then compressed by δ: exactly the
//     linear contact's k_n δ;
//   * the step the bond is released in tension (the pair open): exactly zero force and moment.
#include <catch2/catch.hpp>
#include <cmath>

#include "bond_rig.hpp"
#include "core/contact_law.hpp"

using namespace gradem;
using namespace gradem::test;

namespace {

constexpr double kLambda = 0.5;
constexpr double kStrength = 2.0e6;  // σ̄_c [Pa]

BondParams one_spring_set(BondModel model, bool replaces) {
    BondParams bp = rig_bond(model);
    bp.radius_multiplier = kLambda;
    bp.replaces_contact = replaces;
    bp.tensile_strength_mean = kStrength;
    bp.cohesion_mean = 1.0e12;  // no shear break
    bp.law<SoftBondLaw>().softening_factor = 1.0;
    bp.law<SoftBondLaw>().cut_fraction = 0.0;
    bp.law<FlatJointLaw>().radial_elements = 2;
    bp.law<FlatJointLaw>().angular_elements = 3;
    return bp;
}

/// Moves B along x by `distance` [m] in `steps` steps.
void move_b(BondRig& rig, double distance, int steps) {
    rig.set_motion({distance / (steps * rig.dt), 0, 0}, {});
    for (int s = 0; s < steps; ++s) rig.world.step();
    rig.set_motion({}, {});
}

/// Normal force on B along +x (compression pushes B away from A) [N].
double force_on_b(const BondRig& rig) { return rig.world.particles().force[1].x; }

}  // namespace

TEST_CASE("soft bond / flat joint replacing the contact: a compressed intact pair carries exactly the bond "
          "stiffness, in parallel the contact's is added", "[core][soft_bond][flat_joint]") {
    for (BondModel model : {BondModel::soft_bond, BondModel::flat_joint}) {
        for (bool replaces : {true, false}) {
            INFO(bond_model_name(model) << (replaces ? ", replaces the contact" : ", contact in parallel"));
            BondRig rig(one_spring_set(model, replaces), 0.0);
            const double bond_k = rig.stiffness.normal * rig.section.area;  // k̄_n Ā [N/m]
            const double contact_k = contact_normal_stiffness(kRigModulus, kRigRadius, kRigRadius);
            REQUIRE(bond_k == Approx(0.25 * contact_k).epsilon(1e-12));
            const double overlap = 0.5 * kStrength / rig.stiffness.normal;  // well inside the elastic range
            move_b(rig, -overlap, 200);
            REQUIRE(rig.intact());
            const double delta = -rig.opening();
            const double expected = (replaces ? bond_k : bond_k + contact_k) * delta;
            CHECK(force_on_b(rig) == Approx(expected).epsilon(1e-9));
        }
    }
}

TEST_CASE("soft bond / flat joint replacing the contact: once broken in tension, compression meets the "
          "linear contact alone", "[core][soft_bond][flat_joint]") {
    for (BondModel model : {BondModel::soft_bond, BondModel::flat_joint}) {
        INFO(bond_model_name(model));
        BondRig rig(one_spring_set(model, true), 0.0);
        const double onset = kStrength / rig.stiffness.normal;  // δ_c [m]
        // Soft bond (ζ = 1, γ = 0): breaks at 2 δ_c; flat joint: every element at δ_c. Pull to 3 δ_c.
        move_b(rig, 3.0 * onset, 3000);
        REQUIRE_FALSE(rig.intact());
        const double overlap = 0.5 * onset;
        move_b(rig, -(rig.opening() + overlap), 3000);
        const double delta = -rig.opening();
        REQUIRE(delta == Approx(overlap).epsilon(1e-6));
        const double contact_k = contact_normal_stiffness(kRigModulus, kRigRadius, kRigRadius);
        CHECK(force_on_b(rig) == Approx(contact_k * delta).epsilon(1e-9));
    }
}

TEST_CASE("soft bond / flat joint replacing the contact: the bond owns the pair's force, which is zero in "
          "the step the bond is released in tension", "[core][soft_bond][flat_joint]") {
    // The contacts phase skips a pair whose acting bond replaces the contact and the bond phase
    // sets the pair's force (core/bond_pass.hpp bond_output): in the step the bond is released,
    // with the pair open, no spring acts on it, so the force must be exactly 0, not the bond's
    // force of the step before.
    for (BondModel model : {BondModel::soft_bond, BondModel::flat_joint}) {
        INFO(bond_model_name(model));
        BondRig rig(one_spring_set(model, true), 0.0);
        const double onset = kStrength / rig.stiffness.normal;  // δ_c [m]
        const int steps = 3000;
        rig.set_motion({3.0 * onset / (steps * rig.dt), 0, 0}, {});
        double tension_before = 0.0;  // |force on B| the step before the release [N]
        int step = 0;
        for (; step < steps && bond_acts(rig.bond()); ++step) {
            tension_before = std::fabs(force_on_b(rig));
            rig.world.step();
        }
        REQUIRE(step < steps);  // released while pulled
        REQUIRE(tension_before > 0.0);
        CHECK(rig.opening() > 0.0);
        CHECK(force_on_b(rig) == 0.0);
        CHECK(norm(rig.world.particles().torque[1]) == 0.0);
    }
}
