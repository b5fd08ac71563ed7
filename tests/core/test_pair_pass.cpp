// The fused contact + parallel-bond pass (core/world_pairs.cpp) keeps the bookkeeping
// of the two separate phases it replaced: bond energies summed per fixed bond block in bond
// order, breaks logged in bond order, everything independent of the thread count. The packing
// has several pair and bond blocks (> 2 x kBlockSize bonds), overlapping and open bonded pairs,
// and breaks.
#include <catch2/catch.hpp>

#include <cmath>
#include <cstring>

#include "core/parallel.hpp"
#include "core_fixtures.hpp"
#include "forces_in_pass_check.hpp"
#include "../with_threads.hpp"

using namespace gradem;
using namespace gradem::test;

namespace {

BondParams bond_params() {
    BondParams bp;
    bp.effective_modulus = 1.0e9;
    bp.tensile_strength_mean = 4.0e6;
    bp.tensile_strength_std = 1.2e6;
    bp.cohesion_mean = 8.0e6;
    bp.cohesion_std = 2.0e6;
    bp.friction_angle_deg = 15.0;
    bp.moment_factor = 0.8;
    return bp;
}

// A 12^3 bonded lattice, partly overlapping, squeezed between platens: overlapping contacts, then breaks.
World squeezed_lattice(const SimParams& sim = SimParams{}) {
    const ContactParams contact = platen_scene_contact();
    World world(jittered_cluster(12, 1.0e-3, 7), contact, sim);
    world.scale_radii(1.06);  // some neighbours overlap: contacts beside bonds
    world.install_bonds(bond_params(), 0.5e-3);
    add_platens(world, 0.3);
    return world;
}

// Bond strain energy of a set of bonds as the bond phase sums it: per fixed block of bonds in
// bond order, blocks in order (bond_law.hpp's disc energy of each intact bond).
double bond_energy_by_blocks(const World& world, const std::vector<ParallelBond>& bonds) {
    const BondParams& bp = world.bond_params();
    const auto& r = world.particles().radius;
    double total = 0.0;
    for (std::size_t b0 = 0; b0 < bonds.size(); b0 += static_cast<std::size_t>(kBlockSize)) {
        double block = 0.0;
        for (std::size_t k = b0; k < std::min(bonds.size(), b0 + static_cast<std::size_t>(kBlockSize)); ++k) {
            const ParallelBond& b = bonds[k];
            if (b.state != BondState::intact) continue;
            const double ra = r[static_cast<std::size_t>(b.i)], rb = r[static_cast<std::size_t>(b.j)];
            const BondSection sec = bond_section(bp.radius_multiplier, ra, rb);
            const BondSection s = bond_section_of_radius(sec.radius, 1.0 / sec.radius);
            block += bond_strain_energy(b, s, bond_stiffness(bp.effective_modulus, bp.stiffness_ratio, ra, rb));
        }
        total += block;
    }
    return total;
}

}  // namespace

TEST_CASE("fused pair pass: bond strain energy is the bond-block sum over the bonds", "[core][pair_pass]") {
    with_threads(2, [] {
        World world = squeezed_lattice();
        REQUIRE(world.bonds().size() > 2 * static_cast<std::size_t>(kBlockSize));
        world.run(2000);
        REQUIRE(world.active_contact_count() > 50);             // pairs overlap ...
        REQUIRE(world.break_events().size() > 50);              // ... and bonds have broken
        const std::vector<ParallelBond> before = world.bonds();
        world.run(1);  // the ledger now reports the evaluation at `before`
        CHECK(raw_bits(world.energy().strain_bond) == raw_bits(bond_energy_by_blocks(world, before)));
        CHECK(world.energy().strain_bond > 0.0);
    });
}

namespace {

struct Outcome {
    std::uint64_t hash;
    std::vector<std::uint64_t> energy;
    std::vector<BreakEvent> breaks;
};

Outcome squeeze(int threads, const SimParams& sim = SimParams{}) {
    return with_threads(threads, [&] {
        World world = squeezed_lattice(sim);
        world.run(2500);
        const EnergyLedger& e = world.energy();
        return Outcome{world.state_hash(),
                       {raw_bits(e.kinetic), raw_bits(e.strain_contact), raw_bits(e.strain_bond), raw_bits(e.damping), raw_bits(e.friction),
                        raw_bits(e.bond_break), raw_bits(e.boundary_work), raw_bits(e.reference)},
                       world.break_events()};
    });
}

}  // namespace

TEST_CASE("fused pair pass: energies and crack log identical for 1, 2 and 3 threads", "[core][pair_pass]") {
    auto run = [](int threads) { return squeeze(threads); };
    const Outcome one = run(1);
    REQUIRE(one.breaks.size() > 100);
    for (int threads : {2, 3}) {
        INFO("threads " << threads);
        const Outcome other = run(threads);
        CHECK(other.hash == one.hash);
        CHECK(other.energy == one.energy);
        REQUIRE(other.breaks.size() == one.breaks.size());
        for (std::size_t k = 0; k < one.breaks.size(); ++k) {
            CHECK(other.breaks[k].bond == one.breaks[k].bond);
            CHECK(other.breaks[k].step == one.breaks[k].step);
            CHECK(raw_bits(other.breaks[k].position.x) == raw_bits(one.breaks[k].position.x));
            CHECK(raw_bits(other.breaks[k].tensile_stress) == raw_bits(one.breaks[k].tensile_stress));
        }
    }
    // breaks are logged in bond order within a step
    for (std::size_t k = 1; k < one.breaks.size(); ++k)
        if (one.breaks[k].step == one.breaks[k - 1].step) CHECK(one.breaks[k].bond > one.breaks[k - 1].bond);
}

TEST_CASE("fused pair pass: the stream-prefetch branch gives bitwise the same results", "[core][pair_pass]") {
    // The lattice's arrays are far under the default 32 MiB threshold, so the default pass runs
    // without stream prefetches; with the threshold at 0 and every slot written the other
    // compiled branch runs.
    SimParams prefetching;
    prefetching.stream_prefetch_above_bytes = 0;
    prefetching.forces_in_pass = false;
    const Outcome plain = squeeze(1);
    REQUIRE(plain.breaks.size() > 100);
    for (int threads : {1, 2}) {
        INFO("threads " << threads);
        const Outcome other = squeeze(threads, prefetching);
        CHECK(other.hash == plain.hash);
        CHECK(other.energy == plain.energy);
        CHECK(other.breaks.size() == plain.breaks.size());
    }
}

TEST_CASE("fused pair pass: its batched state is unobservable: reading the records every step changes no bit",
          "[core][pair_pass]") {
    // The pass keeps the contact and bond state in its own batches and writes it back into the
    // pair and bond records only when they are read or the pair list is rebuilt
    // (core/pair_batch.hpp). Reading the records after every step must give the same run.
    const Outcome plain = squeeze(1);
    const Outcome observed = with_threads(2, [] {
        World world = squeezed_lattice();
        double force_sum = 0.0;  // every step reads every bond record
        for (int s = 0; s < 2500; ++s) {
            world.step();
            for (const ParallelBond& b : world.bonds()) force_sum += std::fabs(b.normal_force);
        }
        CHECK(force_sum > 0.0);
        REQUIRE(world.profile().rebuilds >= 2);  // the batches were rebuilt mid-run
        const EnergyLedger& e = world.energy();
        return Outcome{world.state_hash(),
                       {raw_bits(e.kinetic), raw_bits(e.strain_contact), raw_bits(e.strain_bond), raw_bits(e.damping), raw_bits(e.friction),
                        raw_bits(e.bond_break), raw_bits(e.boundary_work), raw_bits(e.reference)},
                       world.break_events()};
    });
    REQUIRE(plain.breaks.size() > 100);
    CHECK(observed.hash == plain.hash);
    CHECK(observed.energy == plain.energy);
    CHECK(observed.breaks.size() == plain.breaks.size());
}

TEST_CASE("fused pair pass: the pairs' forces added to their particles in the pass, and the slots rebuilt when "
          "read, are bitwise those of the slots and the gather",
          "[core][pair_pass]") {
    // SimParams::forces_in_pass: a thread sums the pairs of the particles whose pairs all lie in
    // its share of the pass, in the gather's order, and writes no slot for them (one thread: no
    // slot at all); the other particles' pairs go through their slots and the gather. Reading
    // the slots rebuilds them from the batches. A squeezed lattice after 2500 steps.
    check_forces_in_pass([](int threads, bool forces_in_pass) {
        SimParams sim;
        sim.forces_in_pass = forces_in_pass;
        return with_threads(threads, [&] {
            World world = squeezed_lattice(sim);
            world.run(2500);
            return forces_seen(world);
        });
    });
}

TEST_CASE("fused pair pass: slots left behind by the pass are rebuilt before a set-up change, not after it",
          "[core][pair_pass]") {
    // After a step in which the pass added the forces to the particles the slots are not
    // written; a change of the contact law's parameters must not reach the slots of the
    // evaluation before it.
    auto slots_after_change = [](int threads, bool forces_in_pass) {
        SimParams sim;
        sim.forces_in_pass = forces_in_pass;
        return with_threads(threads, [&] {
            World world = squeezed_lattice(sim);
            world.run(300);
            ContactParams stiffer = world.contact_params();
            stiffer.effective_modulus *= 2.0;
            world.set_contact_params(stiffer);
            std::vector<std::uint64_t> out;
            for (const PairOutput& o : world.pair_outputs()) append_bits(out, o.force_j);
            return out;
        });
    };
    const std::vector<std::uint64_t> written = slots_after_change(1, false);
    for (int threads : {1, 2}) {
        INFO("threads " << threads);
        const std::vector<std::uint64_t> rebuilt = slots_after_change(threads, true);
        REQUIRE(rebuilt.size() == written.size());
        CHECK(rebuilt == written);
    }
}
