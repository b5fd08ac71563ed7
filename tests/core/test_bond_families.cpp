// Bond families: particles carry a family tag and bonds take their parameters from
// the table entry of their family pair. Oracles: a table whose entries all equal one parameter
// set reproduces the single-parameter installation bitwise; a specimen of one family
// reproduces the single-family result of that family's parameters; a pair whose entry is
// empty gets no bond; each bond's strength and stiffness are its own family's; the result is
// bitwise the same for 1, 2 and 3 threads.
#include <catch2/catch.hpp>

#include "core/parallel.hpp"
#include "core_fixtures.hpp"

using namespace gradem;
using namespace gradem::test;

namespace {

BondParams bond(double modulus, double strength) {
    BondParams b;
    b.effective_modulus = modulus;
    b.tensile_strength_mean = strength;
    b.tensile_strength_std = 0.3 * strength;
    b.cohesion_mean = 2.0 * strength;
    b.cohesion_std = 0.5 * strength;
    return b;
}

// A jittered cluster with family tags from `tag(i)`, compressed between two platens past its
// first breaks; bonds from `install`. Returns the state hash.
template <class Tag, class Install>
std::uint64_t compress(Tag tag, Install install, std::size_t* bonds = nullptr, int steps = 800) {
    ParticleSet p = jittered_cluster(6, 1.0e-3, 99);
    for (std::size_t i = 0; i < p.size(); ++i) p.family[i] = tag(i);
    const ContactParams contact = platen_scene_contact();
    World world(std::move(p), contact, SimParams{});
    const std::size_t n = install(world);
    if (bonds) *bonds = n;
    add_platens(world, 0.3);
    world.run(steps);
    return world.state_hash();
}

std::uint8_t alternate(std::size_t i) { return static_cast<std::uint8_t>(i % 2); }

}  // namespace

TEST_CASE("bond families: equal entries reproduce the single-parameter installation bitwise", "[core][families]") {
    const BondParams a = bond(1.0e9, 1.0e6);
    const std::uint64_t single = compress(alternate, [&](World& w) { return w.install_bonds(a, 0.5e-3); });
    BondFamilyTable t = BondFamilyTable::empty(2);
    t.set(0, 0, a);
    t.set(0, 1, a);
    t.set(1, 1, a);
    CHECK(compress(alternate, [&](World& w) { return w.install_bonds(t, 0.5e-3); }) == single);
}

TEST_CASE("bond families: a one-family specimen reproduces that family's single-family result", "[core][families]") {
    const BondParams sand = bond(1.0e9, 1.0e6), paste = bond(0.4e9, 3.0e6);
    BondFamilyTable t = BondFamilyTable::empty(2);
    t.set(0, 0, sand);
    t.set(0, 1, sand);
    t.set(1, 1, paste);
    const auto all_paste = [](std::size_t) { return std::uint8_t{1}; };
    const auto all_sand = [](std::size_t) { return std::uint8_t{0}; };
    CHECK(compress(all_paste, [&](World& w) { return w.install_bonds(t, 0.5e-3); }) ==
          compress(all_paste, [&](World& w) { return w.install_bonds(paste, 0.5e-3); }));
    CHECK(compress(all_sand, [&](World& w) { return w.install_bonds(t, 0.5e-3); }) ==
          compress(all_sand, [&](World& w) { return w.install_bonds(sand, 0.5e-3); }));
    // ... and differs from the other family's (the parameters do act).
    CHECK(compress(all_paste, [&](World& w) { return w.install_bonds(t, 0.5e-3); }) !=
          compress(all_paste, [&](World& w) { return w.install_bonds(sand, 0.5e-3); }));
}

TEST_CASE("bond families: empty entries leave pairs unbonded, each bond draws from its family", "[core][families]") {
    ParticleSet p = jittered_cluster(5, 1.0e-3, 7);
    for (std::size_t i = 0; i < p.size(); ++i) p.family[i] = static_cast<std::uint8_t>((i * 7) % 3 == 0 ? 0 : 1);
    const std::vector<std::uint8_t> family = p.family;
    BondParams itz, paste;
    itz.tensile_strength_mean = 1.0e6;
    itz.cohesion_mean = 2.0e6;
    itz.effective_modulus = 0.5e9;
    paste.tensile_strength_mean = 5.0e6;
    paste.cohesion_mean = 7.0e6;
    BondFamilyTable t = BondFamilyTable::empty(2);  // sand-sand (0, 0): frictional only
    t.set(0, 1, itz);
    t.set(1, 1, paste);
    World world(std::move(p), ContactParams{}, SimParams{});
    world.install_bonds(t, 0.5e-3);
    // Reference: every pair within the gap, by brute force, minus the sand-sand ones.
    std::size_t expected = 0;
    const auto& x = world.particles().position;
    const auto& r = world.particles().radius;
    for (std::size_t i = 0; i < x.size(); ++i)
        for (std::size_t j = i + 1; j < x.size(); ++j)
            if (norm(x[j] - x[i]) - r[i] - r[j] <= 0.5e-3 && (family[i] == 1 || family[j] == 1)) ++expected;
    REQUIRE(world.bonds().size() == expected);
    REQUIRE(expected > 0);
    std::size_t itz_bonds = 0;
    for (const ParallelBond& b : world.bonds()) {
        const bool is_itz = family[static_cast<std::size_t>(b.i)] != family[static_cast<std::size_t>(b.j)];
        itz_bonds += is_itz ? 1 : 0;
        CHECK(b.tensile_strength == (is_itz ? 1.0e6 : 5.0e6));
        CHECK(b.cohesion == (is_itz ? 2.0e6 : 7.0e6));
        CHECK(world.bond_family_params()[b.family_pair].effective_modulus == (is_itz ? 0.5e9 : 1.0e9));
    }
    CHECK(itz_bonds > 0);
    CHECK(itz_bonds < expected);
}

TEST_CASE("bond families: bad tables and tags are refused", "[core][families]") {
    World world(jittered_cluster(2, 1.0e-3, 1), ContactParams{}, SimParams{});
    CHECK_THROWS_WITH(world.install_bonds(BondFamilyTable::empty(2), 0.1e-3), Catch::Contains("no family pair"));
    BondFamilyTable t = BondFamilyTable::empty(2);
    BondParams soft;
    soft.model = BondModel::soft_bond;
    t.set(0, 0, BondParams{});
    t.set(1, 1, soft);
    CHECK_THROWS_WITH(world.install_bonds(t, 0.1e-3), Catch::Contains("same bond model"));
    world.edit_particles().family[3] = 2;
    BondFamilyTable ok = BondFamilyTable::empty(2);
    ok.set(0, 0, BondParams{});
    CHECK_THROWS_WITH(world.install_bonds(ok, 0.1e-3), Catch::Contains("has family 2"));
}

TEST_CASE("bond families: bitwise the same for 1, 2 and 3 threads", "[core][families][determinism]") {
    BondFamilyTable t = BondFamilyTable::empty(2);
    t.set(0, 1, bond(0.5e9, 0.8e6));
    t.set(1, 1, bond(1.0e9, 1.5e6));
    std::uint64_t hash[3];
    for (int threads = 1; threads <= 3; ++threads) {
#ifdef _OPENMP
        omp_set_num_threads(threads);
#endif
        hash[threads - 1] = compress(alternate, [&](World& w) { return w.install_bonds(t, 0.5e-3); });
    }
    CHECK(hash[0] == hash[1]);
    CHECK(hash[0] == hash[2]);
}
