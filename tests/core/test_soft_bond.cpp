// Soft bond (core/soft_bond_law.hpp; docs/bond_laws.md "Soft bond"): a single bond pulled in
// tension traces the elastic line, then the softening line of slope -ζ k_n, and breaks where the
// softened stress reaches γ σ_c; the energy dissipated is the area under the curve,
// G Ā = σ_c²/(2 k_n) [1 + (1-γ²)/ζ] Ā. Unloading and reloading follow the damaged secant;
// compression never damages; pure bending starts softening at β k_n R θ = σ_c. A broken bond
// leaves its pair to the linear contact.
#include <catch2/catch.hpp>
#include <cmath>

#include "bond_rig.hpp"
#include "core/contact_law.hpp"
#include "core/soft_bond_law.hpp"

using namespace gradem;
using namespace gradem::test;

namespace {

constexpr double kStrength = 2.0e6;  // σ_c [Pa]
constexpr double kZeta = 0.5, kGamma = 0.2;

BondParams soft_params() {
    BondParams bp = rig_bond(BondModel::soft_bond);
    bp.tensile_strength_mean = kStrength;
    bp.law<SoftBondLaw>().softening_factor = kZeta;
    bp.law<SoftBondLaw>().cut_fraction = kGamma;
    return bp;
}

double damage_of(const BondRig& rig) { return soft_bond_state(rig.world.bond_side_state(0)).damage; }

}  // namespace

TEST_CASE("soft bond in tension: elastic line, softening slope -zeta k_n, break at gamma sigma_c, "
          "dissipation = area under the curve", "[core][soft_bond]") {
    BondRig rig(soft_params());
    const double kn = rig.stiffness.normal, area = rig.section.area;
    const double onset = kStrength / kn;                                       // δ_c
    const double cutoff = onset + (1.0 - kGamma) * kStrength / (kZeta * kn);   // δ_b
    const double per_step = cutoff / 10400.5;
    rig.set_motion({per_step / rig.dt, 0, 0}, {});
    double work = 0.0, last_force = 0.0, last_opening = 0.0, worst_elastic = 0.0, worst_soft = 0.0;
    int steps = 0, softening_steps = 0;
    double d1 = 0, s1 = 0, d2 = 0, s2 = 0;
    while (rig.intact() && steps < 20000) {
        rig.world.step();
        ++steps;
        const double delta = rig.opening();
        if (!rig.intact()) break;
        const double sigma = rig.axial_stress();
        work += 0.5 * (last_force + sigma * area) * (delta - last_opening);
        last_force = sigma * area;
        last_opening = delta;
        if (delta < onset * (1 - 1e-9)) {
            worst_elastic = std::max(worst_elastic, std::fabs(sigma - kn * delta) / kStrength);
            CHECK(damage_of(rig) == 0.0);
        } else if (delta > onset * (1 + 1e-9)) {
            const double predicted = kStrength - kZeta * kn * (delta - onset);
            worst_soft = std::max(worst_soft, std::fabs(sigma - predicted) / kStrength);
            if (softening_steps == 100) d1 = delta, s1 = sigma;
            if (softening_steps == 5000) d2 = delta, s2 = sigma;
            ++softening_steps;
        }
    }
    CHECK(worst_elastic < 1e-6);
    CHECK(worst_soft < 1e-6);
    CHECK((s2 - s1) / (d2 - d1) == Approx(-kZeta * kn).epsilon(1e-6));
    // Breaks on the first step whose opening reaches δ_b.
    CHECK(steps == static_cast<int>(std::ceil(cutoff / per_step)));
    REQUIRE(rig.world.break_events().size() == 1);
    CHECK(rig.world.break_events().front().mode == BondState::broken_tension);
    CHECK(rig.bond().normal_force == 0.0);
    rig.world.step();  // the ledger describes the start of a step: one more to book the break
    const double fracture = kStrength * kStrength / (2.0 * kn) * (1.0 + (1.0 - kGamma * kGamma) / kZeta) * area;
    CHECK(work == Approx(fracture).epsilon(2e-4));
    const EnergyLedger& e = rig.world.energy();
    CHECK(e.bond_damage > 0.0);
    CHECK(e.bond_damage + e.bond_break == Approx(fracture).epsilon(2e-4));
    CHECK(e.strain_bond == 0.0);
    // The broken bond no longer replaces its pair's contact: pushed into overlap, the pair
    // carries the linear contact's k_n |δ| on each side.
    rig.set_motion({-100 * per_step / rig.dt, 0, 0}, {});
    while (rig.rest_distance + rig.opening() > 2.0 * kRigRadius - 1.0e-7) rig.world.step();
    const double overlap = 2.0 * kRigRadius - (rig.rest_distance + rig.opening());
    const double contact_kn = contact_normal_stiffness(kRigModulus, kRigRadius, kRigRadius);
    CHECK(rig.world.particles().force[1].x == Approx(contact_kn * overlap).epsilon(1e-9));
    CHECK(rig.world.particles().force[0].x == Approx(-contact_kn * overlap).epsilon(1e-9));
}

TEST_CASE("soft bond: unload and reload on the damaged secant, compression undamaged",
          "[core][soft_bond]") {
    BondRig rig(soft_params());
    const double kn = rig.stiffness.normal;
    const double onset = kStrength / kn;
    const double cutoff = onset + (1.0 - kGamma) * kStrength / (kZeta * kn);
    const double per_step = cutoff / 8000.25;
    const double target = 0.5 * (onset + cutoff);
    rig.set_motion({per_step / rig.dt, 0, 0}, {});
    while (rig.opening() < target) rig.world.step();
    REQUIRE(rig.intact());
    const double omega = damage_of(rig);
    const double reached = rig.opening();
    const double expected_omega = 1.0 - (kStrength - kZeta * kn * (reached - onset)) / (kn * reached);
    CHECK(omega == Approx(expected_omega).epsilon(1e-9));
    // Unload through zero into compression, then reload to the old maximum.
    rig.set_motion({-per_step / rig.dt, 0, 0}, {});
    rig.world.step();  // books the last loading step in the ledger
    const double dissipated = rig.world.energy().bond_damage;
    double worst = 0.0;
    while (rig.opening() > -0.5 * onset) {
        rig.world.step();
        const double d = rig.opening();
        const double secant = d > 0.0 ? (1.0 - omega) * kn * d : kn * d;
        worst = std::max(worst, std::fabs(rig.axial_stress() - secant) / kStrength);
    }
    rig.set_motion({per_step / rig.dt, 0, 0}, {});
    while (rig.opening() < reached - 2.0 * per_step) {
        rig.world.step();
        const double d = rig.opening();
        const double secant = d > 0.0 ? (1.0 - omega) * kn * d : kn * d;
        worst = std::max(worst, std::fabs(rig.axial_stress() - secant) / kStrength);
    }
    CHECK(worst < 1e-6);
    CHECK(damage_of(rig) == omega);  // no new damage inside the old envelope
    CHECK(rig.world.energy().bond_damage == dissipated);
    // Past the old maximum it is back on the softening line.
    for (int s = 0; s < 200; ++s) rig.world.step();
    const double d = rig.opening();
    CHECK(rig.axial_stress() == Approx(kStrength - kZeta * kn * (d - onset)).epsilon(1e-6));
    CHECK(damage_of(rig) > omega);
}

TEST_CASE("soft bond: pure compression never damages", "[core][soft_bond]") {
    BondRig rig(soft_params());
    const double onset = kStrength / rig.stiffness.normal;
    rig.set_motion({-onset / 500.0 / rig.dt, 0, 0}, {});
    for (int s = 0; s < 5000; ++s) rig.world.step();  // 10 δ_c of closure
    CHECK(rig.intact());
    CHECK(damage_of(rig) == 0.0);
    CHECK(rig.axial_stress() == Approx(rig.stiffness.normal * rig.opening()).epsilon(1e-9));
}

TEST_CASE("soft bond in pure bending: softening starts at beta k_n R theta = sigma_c",
          "[core][soft_bond]") {
    BondParams bp = soft_params();
    bp.moment_factor = 0.5;
    BondRig rig(bp, 0.0);
    const double w = 0.97, per_step = 2.0 * w * rig.dt;  // counter-rotating: contact point fixed
    const double theta_c = kStrength / (bp.moment_factor * rig.stiffness.normal * kRigRadius);
    const int predicted = static_cast<int>(std::floor(theta_c / per_step)) + 1;  // first θ > θ_c
    rig.set_motion({}, {0, w, 0}, {0, -w, 0});
    int onset = -1;
    for (int s = 1; s <= 3 * predicted && onset < 0; ++s) {
        rig.world.step();
        if (damage_of(rig) > 0.0) onset = s;
    }
    CHECK(onset == predicted);
    CHECK(rig.intact());
    // The transmitted moment is the damaged secant of the elastic one: (1-ω) k_n I θ.
    const double theta = onset * per_step;
    CHECK(-rig.bond().bend_moment.y ==
          Approx((1.0 - damage_of(rig)) * rig.stiffness.normal * rig.section.inertia * theta).epsilon(1e-9));
}

TEST_CASE("soft bond homogeneity: moduli and strengths x2 -> forces x2, strengths x2 -> "
          "first-damage load x2", "[core][soft_bond]") {
    auto trace = [](double modulus_scale, double strength_scale, double path_scale) {
        BondParams bp = soft_params();
        bp.effective_modulus *= modulus_scale;
        bp.tensile_strength_mean *= strength_scale;
        BondRig rig(bp);
        const double cutoff = 3.0 * kStrength / bond_stiffness(kRigModulus, kRigKappa, kRigRadius, kRigRadius).normal;
        // Tension plus a little shear; the x2 path is a geometric change (rotation of the pair
        // axis), so only the load at first damage is compared for it, to 1e-9.
        rig.set_motion({path_scale * cutoff / 3000.5 / rig.dt, 0.3 * path_scale * cutoff / 3000.5 / rig.dt, 0}, {});
        std::vector<double> force;
        double first_damage_force = 0.0;
        for (int s = 0; s < 4000 && rig.intact(); ++s) {
            rig.world.step();
            force.push_back(rig.world.particles().force[1].x);
            if (first_damage_force == 0.0 && damage_of(rig) > 0.0) first_damage_force = force.back();
        }
        return std::pair{force, first_damage_force};
    };
    const auto [base, base_first] = trace(1, 1, 1);
    const auto [both, both_first] = trace(2, 2, 1);
    const auto [strong, strong_first] = trace(1, 2, 2);
    REQUIRE(base_first != 0.0);
    REQUIRE(base.size() == both.size());
    for (std::size_t k = 0; k < base.size(); ++k) CHECK(both[k] == 2.0 * base[k]);
    CHECK(strong_first == Approx(2.0 * base_first).epsilon(1e-4));
}

TEST_CASE("soft bonds: damped, frictional compression between platens closes the ledger to 1e-3",
          "[core][soft_bond][energy]") {
    const ContactParams contact = platen_scene_contact();
    World world(jittered_cluster(5, 1.0e-3, 5), contact, SimParams{});
    BondParams bp;
    bp.model = BondModel::soft_bond;
    bp.effective_modulus = 1.0e9;
    bp.tensile_strength_mean = 1.0e6;
    bp.cohesion_mean = 2.0e6;
    bp.law<SoftBondLaw>() = {0.3, 0.1};
    world.install_bonds(bp, 0.5e-3);
    add_platens(world, 0.05, 0.3);
    world.run(20000);
    const EnergyLedger& e = world.energy();
    REQUIRE(world.status() == RunStatus::running);
    REQUIRE(e.boundary_work > 0.0);
    CHECK(e.bond_damage > 0.0);  // bonds really softened
    CHECK(e.damping > 0.0);
    CHECK(std::fabs(e.balance_error()) < 1.0e-3 * e.boundary_work);
}

TEST_CASE("soft bond in shear: breaks where tau = c - sigma tan(phi), as the parallel bond",
          "[core][soft_bond]") {
    const double cohesion = 1.0e6, v = 0.93e-3;
    for (double phi_deg : {0.0, 30.0}) {
        BondParams bp = soft_params();
        bp.tensile_strength_mean = 1.0e12;
        bp.cohesion_mean = cohesion;
        bp.friction_angle_deg = phi_deg;
        BondRig rig(bp);
        rig.set_motion({-v, 0, 0}, {});
        for (int s = 0; s < 300; ++s) rig.world.step();
        const double sigma = rig.axial_stress();  // < 0: compression, never damages
        const double tau_c = cohesion - sigma * std::tan(phi_deg * kPi / 180.0);
        const int predicted = static_cast<int>(std::ceil(tau_c / (rig.stiffness.shear * v * rig.dt)));
        rig.set_motion({0, v, 0}, {});
        int broke = 0;
        for (int s = 1; s <= 100000 && rig.intact(); ++s) {
            rig.world.step();
            if (!rig.intact()) broke = s;
        }
        CHECK(broke == predicted);
        CHECK(rig.bond().state == BondState::broken_shear);
    }
}

TEST_CASE("every bond law sets the time step from the undamaged disc stiffness",
          "[core][soft_bond][flat_joint]") {
    // A simple cubic lattice bonded at its touching pairs; contacts of modulus `contact_gpa`,
    // bonds of `bond_gpa`. The parallel bond acts beside the contact (the springs add); a law
    // whose bond replaces the contact has one spring per pair at a time (the larger counts).
    auto critical = [](BondModel model, bool replaces, double contact_pa, double bond_pa) {
        World world(simple_cubic(3, 1.0e-3, 1.0e-6), frictionless(contact_pa), undamped());
        BondParams bp;
        bp.model = model;
        bp.effective_modulus = bond_pa;
        bp.replaces_contact = replaces;
        world.install_bonds(bp, 2.0e-6);
        return world.critical_time_step();
    };
    World bare(simple_cubic(3, 1.0e-3, 1.0e-6), frictionless(1.0e9), undamped());
    const double pb = critical(BondModel::parallel_bond, true, 1.0e9, 5.0e9);
    CHECK(pb < 0.5 * bare.critical_time_step());  // the bonds dominate
    for (BondModel model : {BondModel::soft_bond, BondModel::flat_joint}) {
        INFO(bond_model_name(model));
        // Beside the contact: the same sum as the parallel bond's, to the bit.
        CHECK(critical(model, false, 1.0e9, 5.0e9) == pb);
        // Replacing it, the bond stiffer: the bond alone, as if the contact were not there
        // (a contact 10^6 times softer adds under 1e-6 of the stiffness to the sum).
        const double bond_alone = critical(BondModel::parallel_bond, true, 1.0e3, 5.0e9);
        CHECK(critical(model, true, 1.0e9, 5.0e9) == Approx(bond_alone).epsilon(1e-6));
        CHECK(critical(model, true, 1.0e9, 5.0e9) > pb);
        // Replacing it, the contact stiffer: the contact alone, the bare lattice's step to the bit.
        CHECK(critical(model, true, 1.0e9, 1.0e6) == bare.critical_time_step());
    }
}
