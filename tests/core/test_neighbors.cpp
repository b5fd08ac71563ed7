// The cell grid finds exactly the pairs a brute-force search finds, sorted, for a
// polydisperse cloud (radius ratio 3), and the same list for any thread count.
#include <catch2/catch.hpp>

#include "core/neighbor_search.hpp"
#include "core/parallel.hpp"
#include "core/random.hpp"

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
