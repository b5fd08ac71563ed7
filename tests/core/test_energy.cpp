// Energy bookkeeping: without damping the leap-frog energy (kinetic invariant + strain) is
// conserved; with damping, friction and moving walls the ledger balances.
#include <catch2/catch.hpp>
#include <cmath>

#include "core_fixtures.hpp"

using namespace gradem;
using namespace gradem::test;

namespace {

BondParams elastic_bonds(double modulus) {
    BondParams bp;
    bp.effective_modulus = modulus;
    bp.tensile_strength_mean = 1.0e12;
    bp.cohesion_mean = 1.0e12;
    return bp;
}

}  // namespace

TEST_CASE("undamped vibration of a bonded cluster conserves energy to 1e-6", "[core][energy]") {
    // Gapped lattice: only bonds act, the linear springs never close.
    World world(simple_cubic(4, 1.0e-3, 2.0e-6), frictionless(1.0e9), undamped());
    world.install_bonds(elastic_bonds(1.0e9), 3.0e-6);
    SplitMix64 rng(3);
    for (std::int32_t i = 0; i < 64; ++i)
        world.set_particle_motion(i, {rng.uniform(-1e-3, 1e-3), rng.uniform(-1e-3, 1e-3), rng.uniform(-1e-3, 1e-3)},
                                  {rng.uniform(-1, 1), rng.uniform(-1, 1), rng.uniform(-1, 1)});
    world.set_time_step(0.2 * world.critical_time_step());
    world.step();
    const double e0 = world.energy().total();
    REQUIRE(e0 > 0.0);
    double worst = 0.0;
    for (int s = 0; s < 10000; ++s) {
        world.step();
        worst = std::max(worst, std::fabs(world.energy().total() - e0) / e0);
    }
    CHECK(worst < 1.0e-6);
    CHECK(world.energy().strain_bond > 0.0);  // energy really moved between the forms
    CHECK(world.energy().damping == 0.0);
}

TEST_CASE("damped, frictional compression between platens: the ledger closes to 1e-3",
          "[core][energy]") {
    const ContactParams contact = platen_scene_contact();
    World world(jittered_cluster(5, 1.0e-3, 5), contact, SimParams{});
    BondParams bp = elastic_bonds(1.0e9);
    bp.tensile_strength_mean = 2.0e6;  // some bonds break: break energy enters the ledger
    bp.cohesion_mean = 2.0e6;
    world.install_bonds(bp, 0.5e-3);
    add_platens(world, 0.05, 0.3);
    world.run(20000);
    const EnergyLedger& e = world.energy();
    REQUIRE(world.status() == RunStatus::running);
    REQUIRE(e.boundary_work > 0.0);
    CHECK(e.damping > 0.0);
    CHECK(e.friction >= 0.0);
    CHECK(std::fabs(e.balance_error()) < 1.0e-3 * e.boundary_work);
}
