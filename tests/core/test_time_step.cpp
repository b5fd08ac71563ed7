// One dt per step: with the automatic time step, the step that rebuilds the
// neighbour list (and so picks a new dt) must compute its increments with the dt the particles
// moved with. Oracle: a bond stretched at constant speed carries F_n = k_n Ā x opening exactly,
// whatever the dt history, while a third grain flying past changes the critical time step at
// the rebuilds.
#include <catch2/catch.hpp>
#include <cmath>

#include "core_fixtures.hpp"

using namespace gradem;
using namespace gradem::test;

TEST_CASE("automatic dt: a rebuild that changes dt keeps the bond force = k_n A x opening",
          "[core][time_step]") {
    const double r = 1.0e-3, gap = 1.0e-9;
    ParticleSet p;
    p.add({0, 0, 0}, r, kDensity);                  // A
    p.add({2 * r + gap, 0, 0}, r, kDensity);        // B, bonded to A
    p.add({-2.5 * r, 0, 0.9 * r}, 0.5 * r, kDensity);  // C: passes by A
    for (auto& f : p.flags) f = kFixedVelocity | kFixedSpin;
    World world(std::move(p), frictionless(1.0e10), undamped());
    BondParams bp;
    bp.effective_modulus = 1.0e10;
    bp.tensile_strength_mean = bp.cohesion_mean = 1.0e12;
    REQUIRE(world.install_bonds(bp, 2 * gap) == 1);
    const double rest = 2 * r + gap;
    world.set_particle_motion(1, {1.0e-4, 0, 0}, {});
    world.set_particle_motion(2, {30.0, 0, 0}, {});  // fast: many rebuilds, dt changes when C nears A
    std::vector<double> dts;
    double worst = 0.0;
    const BondSection s = bond_section(1.0, r, r);
    const BondStiffness k = bond_stiffness(1.0e10, 1.5, r, r);
    for (int step = 0; step < 400; ++step) {
        world.step();
        if (dts.empty() || world.time_step() != dts.back()) dts.push_back(world.time_step());
        const ParticleSet& q = world.particles();
        const double opening = norm(q.position[1] - q.position[0]) - rest;
        const double expected = k.normal * s.area * opening;
        worst = std::max(worst, std::fabs(world.bonds()[0].normal_force - expected) / std::fabs(expected));
        if (q.position[2].x > 1.5 * r) break;  // C is past A
    }
    REQUIRE(dts.size() >= 2);  // the time step really changed during the run
    CHECK(worst < 1e-9);
}
