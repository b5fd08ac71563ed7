// The cell grid and the multi-level grid find exactly the pairs a brute-force search finds,
// sorted, and the same list for any thread count: the cell grid on a polydisperse cloud
// (radius ratio 3), the multi-level grid at size ratios 1, 10 and 50 (bimodal and power law).
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>

#include "core/multilevel_grid.hpp"
#include "core/neighbor_search.hpp"
#include "core/parallel.hpp"
#include "core/random.hpp"
#include "core/world.hpp"
#include "core_fixtures.hpp"

using namespace gradem;

TEST_CASE("cell grid = brute force on a polydisperse cloud", "[core][neighbors]") {
    SplitMix64 rng(5);
    std::vector<Vec3> x;
    std::vector<double> r;
    for (int i = 0; i < 3000; ++i) {
        x.push_back({rng.uniform(0, 0.02), rng.uniform(0, 0.02), rng.uniform(0, 0.01)});
        r.push_back(rng.uniform(0.2e-3, 0.6e-3));
    }
    x.push_back({5.0, 5.0, 5.0});  // a stray particle far away must not break the grid
    r.push_back(0.5e-3);
    const double gap = 0.05e-3;
    std::vector<ParticlePair> brute;
    for (std::int32_t i = 0; i < static_cast<std::int32_t>(x.size()); ++i)
        for (std::int32_t j = i + 1; j < static_cast<std::int32_t>(x.size()); ++j)
            if (norm(x[static_cast<std::size_t>(j)] - x[static_cast<std::size_t>(i)]) -
                    r[static_cast<std::size_t>(i)] - r[static_cast<std::size_t>(j)] <= gap)
                brute.push_back({i, j});
    auto grid = make_cell_grid_search();
    std::vector<ParticlePair> found;
    grid->find_pairs(x, r, gap, found);
    REQUIRE(brute.size() > 1000);
    CHECK(found == brute);
#ifdef _OPENMP
    omp_set_num_threads(1);
    std::vector<ParticlePair> serial;
    grid->find_pairs(x, r, gap, serial);
    omp_set_num_threads(2);
    CHECK(serial == found);
#endif
}

// ---------------------------------------------------------------------------------------
// Multi-level grid (core/multilevel_grid.cpp)
// ---------------------------------------------------------------------------------------

namespace {

enum class Sizes { bimodal, power_law };

struct Cloud {
    std::vector<Vec3> x;
    std::vector<double> r;
};

// Radii with R_max / R_min = ratio exactly: bimodal (1 % large by number) or a truncated power
// law with number density ~ r^-3.5 (Fuller grading by volume, d^0.5 passing).
std::vector<double> radii(int n, double ratio, Sizes sizes, SplitMix64& rng) {
    const double r_max = 0.5e-3, r_min = r_max / ratio;
    std::vector<double> r(static_cast<std::size_t>(n), r_min);
    if (sizes == Sizes::bimodal) {
        for (int i = 0; i < std::max(1, n / 100); ++i) r[static_cast<std::size_t>(i * 97 % n)] = r_max;
        return r;
    }
    const double a = std::pow(r_min, -2.5), b = std::pow(r_max, -2.5);
    for (double& v : r) v = std::pow(a - rng.uniform() * (a - b), -1.0 / 2.5);
    r[0] = r_max;
    r[1] = r_min;
    return r;
}

// Grains larger than R_max / 3 spread through a box at solid fraction 0.3; of the others, half
// sit on the surface of a random large grain (gaps from -2 to +3 of their reach, so contacts,
// near misses and overlaps all occur) and half crowd a sub-cube at solid fraction 0.2.
Cloud cloud(int n, double ratio, Sizes sizes, std::uint64_t seed) {
    SplitMix64 rng(seed);
    Cloud c;
    c.r = radii(n, ratio, sizes, rng);
    const double r_max = *std::max_element(c.r.begin(), c.r.end());
    std::vector<std::size_t> large, small;
    double large_volume = 0.0, small_volume = 0.0;
    for (std::size_t i = 0; i < c.r.size(); ++i) {
        const double v = 4.0 / 3.0 * kPi * c.r[i] * c.r[i] * c.r[i];
        if (c.r[i] > r_max / 3.0) large.push_back(i), large_volume += v;
        else small.push_back(i), small_volume += v;
    }
    const double box = std::max(4.0 * r_max, std::cbrt(large_volume / 0.3));
    const double crowd = std::cbrt(0.5 * small_volume / 0.2);
    c.x.resize(c.r.size());
    for (std::size_t i : large) c.x[i] = {rng.uniform(0, box), rng.uniform(0, box), rng.uniform(0, box)};
    for (std::size_t k = 0; k < small.size(); ++k) {
        const std::size_t i = small[k];
        if (k % 2 == 0) {
            const std::size_t anchor = large[static_cast<std::size_t>(rng.uniform() * static_cast<double>(large.size()))];
            Vec3 dir{rng.uniform(-1, 1), rng.uniform(-1, 1), rng.uniform(-1, 1)};
            dir = (1.0 / std::max(norm(dir), 1e-9)) * dir;
            const double dist = c.r[anchor] + c.r[i] + rng.uniform(-2.0, 3.0) * c.r[i];
            c.x[i] = c.x[anchor] + dist * dir;
        } else {
            const double o = 0.5 * (box - crowd);
            c.x[i] = {o + rng.uniform(0, crowd), o + rng.uniform(0, crowd), o + rng.uniform(0, crowd)};
        }
    }
    return c;
}

// Every pair within reach, by the same test the searches use (reach = r_i + r_j + gap).
std::vector<ParticlePair> brute_force(const std::vector<Vec3>& x, const std::vector<double>& r, double gap) {
    std::vector<ParticlePair> out;
    for (std::size_t i = 0; i < x.size(); ++i)
        for (std::size_t j = i + 1; j < x.size(); ++j) {
            const double reach = r[i] + r[j] + gap;
            if (norm2(x[j] - x[i]) <= reach * reach)
                out.push_back({static_cast<std::int32_t>(i), static_cast<std::int32_t>(j)});
        }
    return out;
}

std::vector<ParticlePair> search_with_threads(NeighborSearch& search, const Cloud& c, double gap, int threads) {
#ifdef _OPENMP
    const int before = omp_get_max_threads();
    omp_set_num_threads(threads);
#else
    (void)threads;
#endif
    std::vector<ParticlePair> found;
    search.find_pairs(c.x, c.r, gap, found);
#ifdef _OPENMP
    omp_set_num_threads(before);
#endif
    return found;
}

}  // namespace

TEST_CASE("multi-level grid = brute force at size ratios 1, 10, 50", "[core][neighbors]") {
    auto multilevel = make_multilevel_grid_search();
    for (const Sizes sizes : {Sizes::bimodal, Sizes::power_law})
        for (const double ratio : {1.0, 10.0, 50.0})
            for (const double gap_in_r_min : {0.0, 0.5}) {
                const Cloud c = cloud(3000, ratio, sizes, 11);
                const double r_min = *std::min_element(c.r.begin(), c.r.end());
                const double gap = gap_in_r_min * r_min;
                const auto expected = brute_force(c.x, c.r, gap);
                INFO("sizes " << (sizes == Sizes::bimodal ? "bimodal" : "power law") << ", ratio " << ratio
                              << ", gap " << gap_in_r_min << " r_min, " << expected.size() << " pairs");
                REQUIRE(expected.size() > 1000);
                for (const int threads : {1, 2, 3}) {
                    INFO(threads << " threads");
                    CHECK(search_with_threads(*multilevel, c, gap, threads) == expected);
                }
            }
}

// Which search "auto" ran is not observable: NeighborSearch exposes only find_pairs() and
// name() (always "auto"). What is asserted instead: the ratios straddle the documented switch
// (R_max / R_min <= kMultilevelRadiusRatio: cell grid, above: multi-level grid), so each
// search is exercised on its side, and at every ratio the automatic search returns exactly
// the brute-force pairs, which both the cell grid and the multi-level grid also return.
TEST_CASE("the automatic search returns the brute-force pairs on both sides of its switch", "[core][neighbors]") {
    auto automatic = make_neighbor_search();
    auto cell_grid = make_cell_grid_search();
    auto multilevel = make_multilevel_grid_search();
    CHECK(automatic->name() == "auto");
    struct Case { double ratio; bool multilevel_side; };
    for (const Case k : {Case{1.0, false}, Case{2.9, false}, Case{3.5, true}, Case{6.0, true}}) {
        const Cloud c = cloud(3000, k.ratio, Sizes::power_law, 12);
        const auto [lo, hi] = std::minmax_element(c.r.begin(), c.r.end());
        const double gap = 0.3 * *lo;
        const auto expected = brute_force(c.x, c.r, gap);
        INFO("ratio " << k.ratio << ", " << expected.size() << " pairs");
        REQUIRE(expected.size() > 1000);
        CHECK((*hi > kMultilevelRadiusRatio * *lo) == k.multilevel_side);
        const auto found = search_with_threads(*automatic, c, gap, 2);
        CHECK(found == expected);
        CHECK(search_with_threads(*cell_grid, c, gap, 2) == expected);
        CHECK(search_with_threads(*multilevel, c, gap, 2) == expected);
    }
}

TEST_CASE("multi-level grid on degenerate inputs", "[core][neighbors]") {
    auto multilevel = make_multilevel_grid_search();
    std::vector<ParticlePair> found{{0, 1}};
    SECTION("no particle and one particle give no pairs") {
        multilevel->find_pairs({}, {}, 0.0, found);
        CHECK(found.empty());
        multilevel->find_pairs({{1, 2, 3}}, {1e-3}, 0.0, found);
        CHECK(found.empty());
    }
    SECTION("all particles in one cell, mixed sizes, one point repeated") {
        Cloud c;
        SplitMix64 rng(3);
        for (int i = 0; i < 60; ++i) {
            c.x.push_back(i % 3 == 0 ? Vec3{1e-3, 1e-3, 1e-3}
                                     : Vec3{rng.uniform(0, 1e-5), rng.uniform(0, 1e-5), rng.uniform(0, 1e-5)});
            c.r.push_back(i % 7 == 0 ? 1e-3 : 2e-5);
        }
        const auto expected = brute_force(c.x, c.r, 0.0);
        REQUIRE(expected.size() > 500);
        for (const int threads : {1, 3}) CHECK(search_with_threads(*multilevel, c, 0.0, threads) == expected);
    }
    SECTION("a second call with particles far outside the first bounding box") {
        Cloud c = cloud(2000, 50.0, Sizes::bimodal, 4);
        multilevel->find_pairs(c.x, c.r, 0.0, found);
        for (Vec3& p : c.x) p += Vec3{-3.0, 7.5, 1e3};
        c.x[5] = {1e4, -1e4, 0.0};  // a stray grain far away must not break the grid
        const auto expected = brute_force(c.x, c.r, 1e-6);
        REQUIRE(expected.size() > 500);
        CHECK(search_with_threads(*multilevel, c, 1e-6, 2) == expected);
    }
}

TEST_CASE("level plan: one level for equal sizes, two for a bimodal mix", "[core][neighbors]") {
    SplitMix64 rng(9);
    const double volume = 1e-6;  // [m^3]
    const auto equal = radii(20000, 1.0, Sizes::bimodal, rng);
    CHECK(plan_levels(equal, 1e-5, volume).cell.size() == 1);
    for (const double ratio : {10.0, 50.0}) {
        const auto mix = radii(20000, ratio, Sizes::bimodal, rng);
        const LevelPlan plan = plan_levels(mix, 0.0, volume);
        INFO("ratio " << ratio);
        // Ogarko & Luding 2012: a bimodal mix wants one level per size; more only adds work.
        REQUIRE(plan.cell.size() == 2);
        CHECK(plan.cell.back() == 2.0 * 0.5e-3);
        CHECK(plan.cell.front() >= 2.0 * 0.5e-3 / ratio);
        CHECK(plan.cell.front() < 2.0 * 0.5e-3);
    }
}

namespace {

// Simple-cubic cluster of ~1 mm grains with a small grain (R_max/R ~ 12) jittered around every
// cell centre, bonded, compressed between platens; hash of the final state.
std::uint64_t compressed_mix_hash(std::unique_ptr<NeighborSearch> search) {
    ParticleSet p = test::jittered_cluster(7, 1.0e-3, 21);
    SplitMix64 rng(22);
    for (int k = 0; k < 6; ++k)
        for (int j = 0; j < 6; ++j)
            for (int i = 0; i < 6; ++i)
                p.add(Vec3{(i + 0.5) * 2e-3, (j + 0.5) * 2e-3, (k + 0.5) * 2e-3} +
                          Vec3{rng.uniform(-4e-4, 4e-4), rng.uniform(-4e-4, 4e-4), rng.uniform(-4e-4, 4e-4)},
                      0.08e-3, test::kDensity);
    const ContactParams contact = test::platen_scene_contact();
    World world(std::move(p), contact, SimParams{}, std::move(search));
    BondParams bp;
    bp.effective_modulus = 1.0e9;
    bp.tensile_strength_mean = 1.0e6;
    bp.cohesion_mean = 2.0e6;
    world.install_bonds(bp, 0.3e-3);
    test::add_platens(world, 0.5);
    world.run(2000);
    REQUIRE(world.status() == RunStatus::running);
    return world.state_hash();
}

}  // namespace

TEST_CASE("a World with a size ratio of 12 ends bitwise the same with either search", "[core][neighbors]") {
    // The automatic search picks the multi-level grid here (ratio > 3); the pair list, hence
    // every force and the final state, must be those of the cell grid.
    CHECK(compressed_mix_hash(make_neighbor_search()) == compressed_mix_hash(make_cell_grid_search()));
    CHECK(compressed_mix_hash(make_multilevel_grid_search()) == compressed_mix_hash(make_cell_grid_search()));
}
