// Rigid-body motion of a bonded cluster stores no bond force and breaks nothing
// (docs/model.md "What the tests check"): every particle is driven kinematically along the exact rigid
// motion (chord velocities), with the spin equal to the body's angular velocity.
#include <catch2/catch.hpp>
#include <cmath>

#include "core_fixtures.hpp"

using namespace gradem;
using namespace gradem::test;

namespace {

// Rotation of v about unit axis k by angle a (Rodrigues).
Vec3 rotate(const Vec3& v, const Vec3& k, double a) {
    return std::cos(a) * v + std::sin(a) * cross(k, v) + (1.0 - std::cos(a)) * dot(k, v) * k;
}

World bonded_cluster() {
    World world(jittered_cluster(3, 1.0e-3, 11), frictionless(1.0e9), undamped());
    ParticleSet& p = world.edit_particles();
    for (auto& f : p.flags) f = kFixedVelocity | kFixedSpin;
    BondParams bp;
    bp.effective_modulus = 1.0e9;
    bp.tensile_strength_mean = 1.0e6;
    bp.cohesion_mean = 1.0e6;
    REQUIRE(world.install_bonds(bp, 0.5e-3) > 30);
    world.set_time_step(1.0e-6);
    return world;
}

double max_bond_load(const World& world) {
    double m = 0.0;
    for (const ParallelBond& b : world.bonds())
        m = std::max({m, std::fabs(b.normal_force), norm(b.shear_force)});
    return m;
}

}  // namespace

TEST_CASE("rigid translation: bond forces stay exactly zero", "[core][invariance]") {
    World world = bonded_cluster();
    for (std::int32_t i = 0; i < static_cast<std::int32_t>(world.particles().size()); ++i)
        world.set_particle_motion(i, {0.3, -0.2, 0.1}, {});
    world.run(2000);
    CHECK(max_bond_load(world) == 0.0);
    CHECK(world.break_events().empty());
}

TEST_CASE("rigid rotation by 0.3 rad: no bond force, no break", "[core][invariance]") {
    World world = bonded_cluster();
    const Vec3 axis = (1.0 / std::sqrt(3.0)) * Vec3{1, 1, 1};
    const Vec3 centre{2.0e-3, 2.0e-3, 2.0e-3};
    const double rate = 10.0, dt = 1.0e-6;  // 1e-5 rad per step
    const int steps = 30000;
    const auto n = static_cast<std::int32_t>(world.particles().size());
    for (int s = 0; s < steps; ++s) {
        for (std::int32_t i = 0; i < n; ++i) {
            const Vec3 r = world.particles().position[static_cast<std::size_t>(i)] - centre;
            world.set_particle_motion(i, (1.0 / dt) * (rotate(r, axis, rate * dt) - r), rate * axis);
        }
        world.step();
    }
    // Reference: the force a 1e-9 strain puts on a bond of this cluster, E* pi R^2 * 1e-9.
    const double reference = 1.0e9 * kPi * 1.0e-6 * 1.0e-9;
    CHECK(max_bond_load(world) < reference);
    CHECK(world.break_events().empty());
    CHECK(world.intact_bond_count() == world.bonds().size());
}
