// The flat joint as an interface (core/flat_joint_law.hpp): what it keeps once its elements are
// unbonded, the joint types, the friction angle and the gap stiffness, each against a hand
// calculation. Two spheres of radius R, B on +x (n = x), joint frame t1 = z, t2 = -y.
#include <catch2/catch.hpp>
#include <cmath>

#include "bond_rig.hpp"
#include "core/flat_joint_law.hpp"

using namespace gradem;
using namespace gradem::test;

namespace {

BondParams slit_joint(std::int32_t nr, std::int32_t na) {
    BondParams bp = joint(nr, na);
    bp.law<FlatJointLaw>().bonded_fraction = 0.0;
    return bp;
}

/// Moves B toward A by `depth` [m] over `steps` steps, then holds it.
void press(BondRig& rig, double depth, int steps) {
    rig.set_motion({-depth / (steps * rig.dt), 0, 0}, {});
    for (int s = 0; s < steps; ++s) rig.world.step();
    rig.set_motion({}, {});
}

/// Integrals over the part ξ < c of the unit disc: ∫ dA, ∫ ξ dA, ∫ ξ² dA (circular segment).
struct Segment { double area, first, second; };
Segment disc_below(double c) {
    c = std::clamp(c, -1.0, 1.0);
    auto area = [](double x) { return x * std::sqrt(1 - x * x) + std::asin(x); };
    auto first = [](double x) { return -2.0 / 3.0 * std::pow(1 - x * x, 1.5); };
    auto second = [](double x) { return 0.25 * (x * (2 * x * x - 1) * std::sqrt(1 - x * x) + std::asin(x)); };
    return {area(c) - area(-1.0), first(c) - first(-1.0), second(c) - second(-1.0)};
}

}  // namespace

// A bonded joint pressed to σ and sheared breaks when τ = c̄ + |σ| tan φ̄ (all elements at
// once: uniform stresses); broken and closed, it then slides at |F_s| = μ_r |F_n|, and it
// still acts (an interface, not a released bond).
TEST_CASE("flat joint: the friction angle adds |sigma| tan(phi) to the shear strength, broken and closed, "
          "the joint slides at mu_r N", "[core][flat_joint]") {
    for (double phi_deg : {0.0, 30.0}) {
        INFO("phi " << phi_deg);
        BondParams bp = joint(1, 4);
        bp.cohesion_mean = 4.0e6;
        bp.tensile_strength_mean = 2.0e6;
        bp.friction_angle_deg = phi_deg;
        BondRig rig(bp);
        const double sigma = -5.0e6;  // [Pa], compression
        press(rig, -sigma / rig.stiffness.normal, 200);
        REQUIRE(rig.axial_stress() == Approx(sigma).epsilon(1e-6));
        const double strength = bp.cohesion_mean - sigma * std::tan(phi_deg * kPi / 180.0);
        const double per_step = strength / 1000.5;  // shear stress increment [Pa]
        rig.set_motion({0, per_step / rig.stiffness.shear / rig.dt, 0}, {});
        int broke = 0;
        for (int s = 1; s <= 1500 && rig.intact(); ++s) {
            rig.world.step();
            if (!rig.intact()) broke = s;
        }
        REQUIRE(broke > 0);
        const auto& events = rig.world.break_events();
        REQUIRE(events.size() == 4u);
        for (const BreakEvent& e : events) {
            CHECK(e.mode == BondState::broken_shear);
            const double envelope = bp.cohesion_mean - e.tensile_stress * std::tan(phi_deg * kPi / 180.0);
            CHECK(e.shear_stress >= envelope);
            CHECK(e.shear_stress < envelope + 1.5 * per_step);
            CHECK(e.shear_stress == Approx(strength).epsilon(3e-3));
        }
        CHECK(rig.bond().state == BondState::broken_shear);
        CHECK(rig.bond().interface == 1);
        for (std::size_t e = 0; e < 4; ++e) CHECK_FALSE(flat_joint_element_bonded(rig.world.bond_side_state(0), e));
        for (int s = 0; s < 300; ++s) rig.world.step();
        CHECK(bond_acts(rig.bond()));
        const double normal = rig.bond().normal_force;
        CHECK(normal == Approx(sigma * rig.section.area).epsilon(2e-3));
        CHECK(norm(rig.bond().shear_force) == Approx(0.5 * std::fabs(normal)).epsilon(1e-9));
        CHECK(rig.world.energy().friction > 0.0);
    }
}

// A slit joint (unbonded, no initial gap) pressed by δ0 and bent by θ: gap g = -δ0 + θ z over
// the disc; the compressed part z < δ0/θ carries σ = k_n g. Normal force and moment against
// the circular-segment integrals, from fully closed to mostly open, for several layouts.
TEST_CASE("flat joint: an unbonded joint resists bending through its compressed part, as the hand "
          "integral over the disc", "[core][flat_joint]") {
    const std::pair<int, int> layouts[] = {{1, 1}, {1, 4}, {2, 6}, {3, 8}};
    for (const auto& [nr, na] : layouts) {
        INFO("N_r " << nr << " N_a " << na);
        BondRig rig(slit_joint(nr, na), 0.0);
        REQUIRE(rig.bond().state == BondState::none);
        REQUIRE(bond_acts(rig.bond()));
        const double kn = rig.stiffness.normal, R = rig.section.radius, depth = 1.0e-6;
        press(rig, depth, 100);
        const double w = 3.7, per_step = 2.0 * w * rig.dt;
        const int steps = static_cast<int>(depth / (0.15 * R) / per_step);  // to c = 0.15
        rig.set_motion({}, {0, w, 0}, {0, -w, 0});
        double worst_force = 0.0, worst_moment = 0.0;
        for (int s = 1; s <= steps; ++s) {
            rig.world.step();
            const double theta = s * per_step;
            const Segment g = disc_below(depth / (theta * R));
            const double fn = kn * R * R * (-depth * g.area + theta * R * g.first);
            const double pz = kn * R * R * R * (-depth * g.first + theta * R * g.second);
            worst_force = std::max(worst_force, std::fabs(rig.bond().normal_force - fn) / std::fabs(fn));
            worst_moment = std::max(worst_moment, std::fabs(rig.world.particles().torque[1].y + pz) / std::fabs(pz));
        }
        // Radially exact, Gauss in angle between the kinks: measured worst 4.7e-6 (1x4), 6e-12 (1x1).
        CHECK(worst_force < 2e-5);
        CHECK(worst_moment < 2e-5);
        CHECK(bond_acts(rig.bond()));
    }
}

// A gapped joint (g_0 = gap_ratio R̄) carries nothing until its gap has closed, then
// F_n = k_n A (δ + g_0): the hand solution of a uniform press.
TEST_CASE("flat joint: a gapped joint carries nothing until its initial gap closes", "[core][flat_joint]") {
    BondParams bp = joint(1, 4);
    bp.law<FlatJointLaw>().bonded_fraction = 0.0;
    bp.law<FlatJointLaw>().gapped_fraction = 1.0;
    bp.law<FlatJointLaw>().gap_ratio = 2.0e-3;
    BondRig rig(bp);
    const double g0 = bp.law<FlatJointLaw>().gap_ratio * rig.section.radius;
    REQUIRE(rig.world.bond_side_state(0)[flat_side::initial_gap] == Approx(g0).epsilon(1e-12));
    REQUIRE(flat_joint_type(rig.world.bond_side_state(0)) == FlatJointType::gapped);
    const double per_step = 3.0 * g0 / 3000.0;
    rig.set_motion({-per_step / rig.dt, 0, 0}, {});
    bool carried_early = false;
    double worst = 0.0;
    for (int s = 1; s <= 3000; ++s) {
        rig.world.step();
        const double delta = rig.opening();
        if (delta > -g0 * (1 - 1e-6)) {
            carried_early = carried_early || rig.bond().normal_force != 0.0;
        } else if (delta < -g0 * (1 + 1e-3)) {
            const double expected = rig.stiffness.normal * rig.section.area * (delta + g0);
            worst = std::max(worst, std::fabs(rig.bond().normal_force - expected) / std::fabs(expected));
        }
    }
    CHECK_FALSE(carried_early);
    CHECK(worst < 1e-6);
    CHECK(rig.bond().normal_force < 0.0);
}

// A joint broken in tension stays an interface while the pair is within the installation
// reach: closed again it carries compression (k_n A δ); once every element is open and the
// surfaces are beyond the reach it is released (no longer acting).
TEST_CASE("flat joint: a joint broken in tension recloses in compression, and is released once its "
          "surfaces separate beyond the installation reach", "[core][flat_joint]") {
    BondParams bp = joint(1, 4);
    bp.tensile_strength_mean = 2.0e6;
    const double reach = 2.0e-6;
    BondRig rig(bp, kRigGap, reach);
    const double per_step = bp.tensile_strength_mean / rig.stiffness.normal / 500.5;
    rig.set_motion({per_step / rig.dt, 0, 0}, {});
    for (int s = 0; s < 600; ++s) rig.world.step();
    REQUIRE(rig.bond().state == BondState::broken_tension);
    CHECK(rig.bond().interface == 1);
    CHECK(rig.bond().normal_force == 0.0);
    // Back through the installed position into compression.
    rig.set_motion({-per_step / rig.dt, 0, 0}, {});
    for (int s = 0; s < 1200; ++s) rig.world.step();
    const double delta = rig.opening();
    REQUIRE(delta < 0.0);
    CHECK(rig.bond().normal_force == Approx(rig.stiffness.normal * rig.section.area * delta).epsilon(1e-6));
    // Apart beyond the reach: released.
    rig.set_motion({10 * per_step / rig.dt, 0, 0}, {});
    int released = 0;
    for (int s = 1; s <= 2000 && bond_acts(rig.bond()); ++s) {
        rig.world.step();
        if (!bond_acts(rig.bond())) released = s;
    }
    REQUIRE(released > 0);
    const double gap_at_release = rig.rest_distance + rig.opening() - 2.0 * kRigRadius;
    CHECK(gap_at_release > reach);
    CHECK(gap_at_release < reach + 10 * per_step * 1.01);
    CHECK(rig.bond().interface == 0);
    CHECK(rig.bond().state == BondState::broken_tension);
}

// k̄_n of a joint installed across a gap g: Ē*/(R_A + R_B + g) with stiffness_over_gap, the
// touching pair's Ē*/(R_A + R_B) without; zero force at installation either way.
TEST_CASE("flat joint: a joint installed across a gap has the stiffness of a bridge that long",
          "[core][flat_joint]") {
    const double gap = 0.25 * kRigRadius;
    for (bool over_gap : {false, true}) {
        INFO("stiffness_over_gap " << over_gap);
        BondParams bp = joint(1, 4);
        bp.law<FlatJointLaw>().stiffness_over_gap = over_gap;
        BondRig rig(bp, gap);
        rig.world.step();
        CHECK(rig.bond().normal_force == 0.0);
        rig.set_motion({1.0e-4, 0, 0}, {});
        for (int s = 0; s < 200; ++s) rig.world.step();
        const double length = 2.0 * kRigRadius + (over_gap ? gap : 0.0);
        const double kn = kRigModulus / length;
        CHECK(rig.bond().normal_force == Approx(kn * rig.section.area * rig.opening()).epsilon(1e-9));
    }
}

// Types drawn per joint with the strength seed: on ~1e4 joints the fractions come out as asked
// (4 binomial standard deviations), gapped joints get g_0 = gap_ratio R̄, the draw is the same
// on a second installation, and slit and gapped joints act as interfaces from the start.
TEST_CASE("flat joint: bonded, gapped and slit joints come out in the stated fractions", "[core][flat_joint]") {
    BondParams bp = joint(1, 3);
    bp.law<FlatJointLaw>().bonded_fraction = 0.55;
    bp.law<FlatJointLaw>().gapped_fraction = 0.25;
    bp.law<FlatJointLaw>().gap_ratio = 0.02;
    auto install = [&]() {
        World world(jittered_cluster(14, 1.0e-3, 7), frictionless(1.0e9), SimParams{});
        world.install_bonds(bp, 0.5e-3);
        return world;
    };
    World world = install();
    const std::size_t n = world.bonds().size();
    REQUIRE(n > 7000);
    std::size_t counts[3] = {0, 0, 0};
    std::vector<int> types;
    for (std::size_t k = 0; k < n; ++k) {
        const auto side = world.bond_side_state(k);
        const FlatJointType t = flat_joint_type(side);
        types.push_back(static_cast<int>(t));
        ++counts[static_cast<int>(t)];
        const ParallelBond& b = world.bonds()[k];
        const double rbar = std::min(world.particles().radius[static_cast<std::size_t>(b.i)],
                                     world.particles().radius[static_cast<std::size_t>(b.j)]);
        if (t == FlatJointType::gapped) CHECK(side[flat_side::initial_gap] == Approx(0.02 * rbar).epsilon(1e-12));
        else CHECK(side[flat_side::initial_gap] == 0.0);
        CHECK((b.state == BondState::intact) == (t == FlatJointType::bonded));
        CHECK(bond_acts(b));
    }
    const double fractions[3] = {0.55, 0.25, 0.20};
    for (int t = 0; t < 3; ++t) {
        INFO("type " << t);
        const double expected = fractions[t] * static_cast<double>(n);
        const double sd = std::sqrt(static_cast<double>(n) * fractions[t] * (1 - fractions[t]));
        CHECK(std::fabs(static_cast<double>(counts[t]) - expected) < 4.0 * sd);
    }
    World again = install();
    for (std::size_t k = 0; k < n; ++k) REQUIRE(static_cast<int>(flat_joint_type(again.bond_side_state(k))) == types[k]);
}
