// Simple-cubic bonded lattice under uniaxial compression along a lattice axis:
// E = (k_n + k̄_n Ā) / (2R), which is pi E*/2 for λ̄ = 1 and Ē* = E* (docs/model.md "What the tests check").
#include <catch2/catch.hpp>

#include "core/contact_law.hpp"
#include "core_fixtures.hpp"

using namespace gradem;
using namespace gradem::test;

TEST_CASE("simple-cubic lattice modulus is (k_n + k_n_bar A) / 2R", "[core][lattice]") {
    const int n = 4;
    const double r = 1.0e-3, modulus = 1.0e9;
    ContactParams contact = frictionless(modulus);
    World world(simple_cubic(n, r, 0.0), contact, SimParams{});
    BondParams bp;
    bp.effective_modulus = modulus;
    bp.tensile_strength_mean = bp.cohesion_mean = 1.0e12;
    REQUIRE(world.install_bonds(bp, 1.0e-12) == 3u * n * n * (n - 1));
    // Bottom layer held, top layer pushed down slowly; both layers may not rotate.
    ParticleSet& p = world.edit_particles();
    const double top_z = (n - 1) * 2.0 * r;
    for (std::size_t i = 0; i < p.size(); ++i)
        if (p.position[i].z == 0.0 || p.position[i].z == top_z) p.flags[i] = kFixedVelocity | kFixedSpin;
    const double dt = 0.5 * world.critical_time_step();
    world.set_time_step(dt);
    const double strain_target = 1.0e-4, height = top_z;
    const int load_steps = 20000;
    const double speed = strain_target * height / (load_steps * dt);
    for (std::size_t i = 0; i < p.size(); ++i)
        if (p.position[i].z == top_z) world.set_particle_motion(static_cast<std::int32_t>(i), {0, 0, -speed}, {});
    world.run(load_steps);
    for (std::size_t i = 0; i < p.size(); ++i)
        world.set_particle_motion(static_cast<std::int32_t>(i), {}, {});
    world.run(20000);  // relax to equilibrium at the final strain
    double top_force = 0.0, top_now = 0.0;
    for (std::size_t i = 0; i < world.particles().size(); ++i)
        if (world.particles().flags[i] && world.particles().position[i].z > r) {
            top_force += world.particles().force[i].z;
            top_now = world.particles().position[i].z;
        }
    const double strain = (height - top_now) / height;
    const double stress = top_force / (n * n * 4.0 * r * r);  // each column carries (2R)^2
    const double kn = contact_normal_stiffness(modulus, r, r);
    const double kbar_a = modulus / (2.0 * r) * kPi * r * r;
    CHECK(stress / strain == Approx((kn + kbar_a) / (2.0 * r)).epsilon(0.01));
    CHECK(stress / strain == Approx(kPi * modulus / 2.0).epsilon(0.01));
}
