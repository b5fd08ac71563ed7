// Parallel bond: force/moment laws for pure tension, shear, twist and bending, and breakage on
// the step predicted from the strengths (Potyondy & Cundall 2004; docs/model.md "What the tests check").
// B is driven kinematically (prescribed velocity/spin), A is held fixed.
#include <catch2/catch.hpp>
#include <cmath>

#include "core_fixtures.hpp"

using namespace gradem;
using namespace gradem::test;

namespace {

constexpr double kR = 1.0e-3;           // both radii [m]
constexpr double kGap = 1.0e-9;         // installation gap: keeps the linear part inactive
constexpr double kModulus = 1.0e10;     // Ē* [Pa]
constexpr double kKappa = 1.5;

struct BondRig {
    World world;
    BondSection section = bond_section(1.0, kR, kR);
    BondStiffness stiffness = bond_stiffness(kModulus, kKappa, kR, kR);
    double dt = 1.0e-7;

    explicit BondRig(const BondParams& bp, double gap = kGap)
        : world(sphere_pair(kR, kR, gap), frictionless(kModulus), undamped()) {
        ParticleSet& p = world.edit_particles();
        p.flags[0] = p.flags[1] = kFixedVelocity | kFixedSpin;
        REQUIRE(world.install_bonds(bp, 2.0 * gap) == 1);
        world.set_time_step(dt);
    }
    const ParallelBond& bond() const { return world.bonds().front(); }
    // Drive B with (v, w) for n steps; returns the number of steps taken before the break
    // (or n if it held).
    int drive(const Vec3& v, const Vec3& w, int n, const Vec3& wa = {}) {
        world.set_particle_motion(0, {}, wa);
        world.set_particle_motion(1, v, w);
        for (int s = 0; s < n; ++s) {
            world.step();
            if (bond().state != BondState::intact) return s + 1;
        }
        return n;
    }
};

BondParams strong_bond() {
    BondParams b;
    b.effective_modulus = kModulus;
    b.stiffness_ratio = kKappa;
    b.tensile_strength_mean = 1.0e12;
    b.cohesion_mean = 1.0e12;
    return b;
}

}  // namespace

TEST_CASE("pure tension: F_n = k_n A du, force on B pulls it back", "[core][bond]") {
    BondRig rig(strong_bond());
    const double v = 1.0e-4;  // m/s -> 1e-11 m per step
    rig.drive({v, 0, 0}, {}, 500);
    const ParticleSet& p = rig.world.particles();
    const double opening = norm(p.position[1] - p.position[0]) - 2.0 * kR - kGap;
    const double expected = rig.stiffness.normal * rig.section.area * opening;
    CHECK(rig.bond().normal_force == Approx(expected).epsilon(1e-9));
    CHECK(p.force[1].x == Approx(-expected).epsilon(1e-9));
    CHECK(p.force[0].x == Approx(expected).epsilon(1e-9));
    CHECK(norm(rig.bond().shear_force) == 0.0);
}

TEST_CASE("pure shear: F_s = k_s A du_s", "[core][bond]") {
    BondRig rig(strong_bond());
    const double v = 1.0e-4;
    rig.drive({0, v, 0}, {}, 500);
    const double slide = rig.world.particles().position[1].y;
    const double expected = rig.stiffness.shear * rig.section.area * slide;
    CHECK(-rig.bond().shear_force.y == Approx(expected).epsilon(1e-9));
    CHECK(rig.world.particles().force[1].y == Approx(-expected).epsilon(1e-9));
}

TEST_CASE("pure twist: M_t = k_s J theta", "[core][bond]") {
    BondRig rig(strong_bond());
    const double w = 1.0e-2;  // rad/s about the bond axis
    rig.drive({}, {w, 0, 0}, 400);
    const double theta = 400 * rig.dt * w;
    CHECK(-rig.bond().twist_moment == Approx(rig.stiffness.shear * rig.section.polar * theta).epsilon(1e-9));
    CHECK(rig.world.particles().torque[1].x == Approx(rig.bond().twist_moment).epsilon(1e-12));
    CHECK(norm(rig.bond().shear_force) < 1e-20);
}

TEST_CASE("pure bending: M_b = k_n I theta (counter-rotating spheres, contact point fixed)",
          "[core][bond]") {
    BondRig rig(strong_bond(), 0.0);
    const double w = 1.0e-2;
    rig.drive({}, {0, w, 0}, 400, {0, -w, 0});
    const double theta = 400 * rig.dt * 2.0 * w;
    CHECK(-rig.bond().bend_moment.y ==
          Approx(rig.stiffness.normal * rig.section.inertia * theta).epsilon(1e-9));
    CHECK(std::fabs(rig.bond().normal_force) < 1e-12);
    CHECK(norm(rig.bond().shear_force) < 1e-12);
}

TEST_CASE("tension break on the predicted step", "[core][bond]") {
    BondParams bp = strong_bond();
    bp.tensile_strength_mean = 2.0e6;
    BondRig rig(bp);
    const double per_step = bp.tensile_strength_mean / rig.stiffness.normal / 1000.5;
    // sigma = k_n * opening reaches sigma_c after 1000.5 increments: breaks on the 1001st step.
    const int predicted = static_cast<int>(std::ceil(bp.tensile_strength_mean / rig.stiffness.normal / per_step));
    const int broke = rig.drive({per_step / rig.dt, 0, 0}, {}, 20000);
    CHECK(predicted == 1001);
    CHECK(broke == predicted);
    REQUIRE(rig.world.break_events().size() == 1);
    const BreakEvent& e = rig.world.break_events().front();
    CHECK(e.mode == BondState::broken_tension);
    CHECK(e.tensile_stress >= bp.tensile_strength_mean);
    CHECK(e.normal.x == Approx(1.0));
    CHECK(e.step == broke);
    CHECK(rig.bond().normal_force == 0.0);  // a broken bond carries nothing
}

TEST_CASE("bending moment adds beta R M / I to the tensile stress", "[core][bond]") {
    BondParams bp = strong_bond();
    bp.tensile_strength_mean = 1.0e6;
    bp.moment_factor = 0.5;
    BondRig rig(bp, 0.0);
    const double w = 0.97, per_step = 2.0 * w * rig.dt;
    // sigma = beta k_n R theta  -> theta_c = sigma_c / (beta k_n R)
    const double theta_c = bp.tensile_strength_mean / (bp.moment_factor * rig.stiffness.normal * kR);
    const int predicted = static_cast<int>(std::ceil(theta_c / per_step));
    CHECK(rig.drive({}, {0, w, 0}, 10000, {0, -w, 0}) == predicted);
    CHECK(rig.bond().state == BondState::broken_tension);
}

TEST_CASE("shear break on the predicted step, compression raises the strength by tan(phi)",
          "[core][bond]") {
    const double cohesion = 1.0e6, v = 0.93e-3;
    auto break_step = [&](double phi_deg, double precompression_steps) {
        BondParams bp = strong_bond();
        bp.cohesion_mean = cohesion;
        bp.friction_angle_deg = phi_deg;
        BondRig rig(bp);
        rig.drive({-v, 0, 0}, {}, static_cast<int>(precompression_steps));
        const double sigma = rig.bond().normal_force / rig.section.area;  // < 0, compression
        const double tau_c = cohesion - sigma * std::tan(phi_deg * kPi / 180.0);
        const int predicted = static_cast<int>(std::ceil(tau_c / (rig.stiffness.shear * v * rig.dt)));
        const int broke = rig.drive({0, v, 0}, {}, 100000);
        CHECK(rig.bond().state == BondState::broken_shear);
        return std::pair{broke, predicted};
    };
    const auto [b0, p0] = break_step(0.0, 300);
    CHECK(b0 == p0);
    const auto [b30, p30] = break_step(30.0, 300);
    CHECK(b30 == p30);
    CHECK(b30 > b0);  // compression + friction angle -> stronger in shear
}

TEST_CASE("strength scatter: per-bond strengths follow the truncated normal", "[core][bond]") {
    ParticleSet p = simple_cubic(12, 1.0e-3, 0.0);
    World world(std::move(p), frictionless(1e9), undamped());
    BondParams bp = strong_bond();
    bp.tensile_strength_mean = 5.0e6;
    bp.tensile_strength_std = 1.0e6;
    bp.seed = 7;
    const std::size_t n = world.install_bonds(bp, 1.0e-9);
    REQUIRE(n == 3u * 12u * 12u * 11u);
    double sum = 0, sum2 = 0;
    for (const ParallelBond& b : world.bonds()) {
        sum += b.tensile_strength;
        sum2 += b.tensile_strength * b.tensile_strength;
        CHECK(b.tensile_strength > 0.0);
    }
    const double mean = sum / n, std = std::sqrt(sum2 / n - mean * mean);
    CHECK(mean == Approx(5.0e6).epsilon(0.02));
    CHECK(std == Approx(1.0e6).epsilon(0.05));
    // Same seed, same pair -> same strength, whatever the installation order.
    World again(simple_cubic(12, 1.0e-3, 0.0), frictionless(1e9), undamped());
    again.install_bonds(bp, 1.0e-9);
    CHECK(again.bonds()[100].tensile_strength == world.bonds()[100].tensile_strength);
}

// The World keeps per-bond constants (R̄, 1/R̄, k̄_n, k̄_s) instead of recomputing them every
// step; they must follow every change of the stiffness parameters and of the radii.
TEST_CASE("bond stiffness follows set_bond_stiffness and scale_radii (per-bond constants refreshed)",
          "[core][bond]") {
    BondRig rig(strong_bond());
    const double v = 1.0e-4;  // m/s -> 1e-11 m per step
    const auto opening = [&] {
        const ParticleSet& p = rig.world.particles();
        return norm(p.position[1] - p.position[0]);
    };
    rig.drive({v, 0, 0}, {}, 200);
    const double f0 = rig.bond().normal_force, d0 = opening();
    CHECK(f0 == Approx(rig.stiffness.normal * rig.section.area * (d0 - 2.0 * kR - kGap)).epsilon(1e-9));

    rig.world.set_bond_stiffness(2.0 * kModulus, kKappa);  // k̄_n doubles
    rig.drive({v, 0, 0}, {}, 200);
    const double f1 = rig.bond().normal_force, d1 = opening();
    CHECK(f1 - f0 == Approx(2.0 * rig.stiffness.normal * rig.section.area * (d1 - d0)).epsilon(1e-6));

    const double factor = 1.01;  // R̄ and Ā grow, k̄_n = Ē*/(R_A + R_B) shrinks: k̄_n Ā x factor
    rig.world.scale_radii(factor);
    rig.world.set_time_step(rig.dt);
    rig.drive({v, 0, 0}, {}, 200);
    const double f2 = rig.bond().normal_force, d2 = opening();
    const BondSection s2 = bond_section(1.0, factor * kR, factor * kR);
    const BondStiffness k2 = bond_stiffness(2.0 * kModulus, kKappa, factor * kR, factor * kR);
    CHECK(f2 - f1 == Approx(k2.normal * s2.area * (d2 - d1)).epsilon(1e-6));
    CHECK(k2.normal * s2.area == Approx(2.0 * factor * rig.stiffness.normal * rig.section.area).epsilon(1e-12));
}
