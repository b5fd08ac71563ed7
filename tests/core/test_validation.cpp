// Bad parameters are refused with the field, the value and the rule; an unstable time step is
// reported as divergence instead of producing garbage.
#include <catch2/catch.hpp>
#include <string>

#include "core_fixtures.hpp"

using namespace gradem;
using namespace gradem::test;

namespace {
std::string reason_of(const std::optional<std::string>& r) { return r.value_or(""); }
}  // namespace

TEST_CASE("invalid parameters name the field, the value and the rule", "[core][validation]") {
    ContactParams c;
    c.effective_modulus = -1.0;
    CHECK(reason_of(c.invalid_reason()) == "ContactParams::effective_modulus = -1 violates > 0");
    c = {};
    c.stiffness_ratio = 0.0;
    CHECK(reason_of(c.invalid_reason()).find("stiffness_ratio = 0 violates > 0") != std::string::npos);
    BondParams b;
    b.radius_multiplier = 1.5;
    CHECK(reason_of(b.invalid_reason()) == "BondParams::radius_multiplier = 1.5 violates in (0, 1]");
    b = {};
    b.tensile_strength_mean = -3.0;
    CHECK(reason_of(b.invalid_reason()).find("tensile_strength_mean = -3") != std::string::npos);
    b = {};
    b.stiffness_ratio = -1.0;
    CHECK(reason_of(b.invalid_reason()).find("BondParams::stiffness_ratio") != std::string::npos);
    SimParams s;
    s.local_damping = 1.0;
    CHECK(reason_of(s.invalid_reason()) == "SimParams::local_damping = 1 violates in [0, 1)");
    s = {};
    s.time_step = -1e-9;
    CHECK(reason_of(s.invalid_reason()).find("time_step") != std::string::npos);
    CHECK_FALSE(ContactParams{}.invalid_reason());
    CHECK_FALSE(BondParams{}.invalid_reason());
    CHECK_FALSE(SimParams{}.invalid_reason());
}

TEST_CASE("a negative radius is refused when the World is built", "[core][validation]") {
    ParticleSet p = sphere_pair(1e-3, 1e-3, 0.0);
    p.radius[1] = -1e-3;
    CHECK_THROWS_WITH(World(p, ContactParams{}, SimParams{}),
                      Catch::Contains("particle 1: radius = -0.001 violates > 0"));
    World ok(sphere_pair(1e-3, 1e-3, 0.0), ContactParams{}, SimParams{});
    BondParams bad;
    bad.moment_factor = 2.0;
    CHECK_THROWS_WITH(ok.install_bonds(bad, 0.0), Catch::Contains("moment_factor = 2"));
}

TEST_CASE("a time step above the stable limit is detected as divergence", "[core][validation]") {
    World world(simple_cubic(4, 1.0e-3, 0.0), frictionless(1.0e9), undamped());
    BondParams bp;
    bp.effective_modulus = 1.0e9;
    bp.tensile_strength_mean = bp.cohesion_mean = 1.0e12;
    world.install_bonds(bp, 1e-12);
    world.set_particle_motion(0, {1e-3, 0, 0}, {});
    world.set_time_step(3.0 * world.critical_time_step());
    const RunStatus status = world.run(20000);
    CHECK(status == RunStatus::diverged);
    CHECK_FALSE(world.status_reason().empty());
    CHECK(world.step_count() < 20000);
    // The same set-up at a stable step runs through.
    World stable(simple_cubic(4, 1.0e-3, 0.0), frictionless(1.0e9), undamped());
    stable.install_bonds(bp, 1e-12);
    stable.set_particle_motion(0, {1e-3, 0, 0}, {});
    stable.set_time_step(0.8 * stable.critical_time_step());
    CHECK(stable.run(20000) == RunStatus::running);
}
