// Neighbour-search benchmark: ns per particle of one full pair search (find_pairs, skin
// 0.15 R_min as the World uses) for the uniform cell grid and the multi-level grid, at radius
// ratios R_max/R_min = 1, 10 and 50 with the same particle count, two size distributions:
//   power_law - number density ~ r^-3.5 (Fuller grading, volume passing ~ d^0.5);
//   bimodal   - two sizes, each half of the solid volume (at ratio 50 and N = 2e5 this is a
//               handful of large grains among the small ones: the cement-paste case).
// Specimen: centres uniform in a cube at total solid fraction 0.35; a grain whose centre lies
// inside a grain more than twice its size is redrawn, so small grains surround large ones
// instead of filling them (pair counts are those of a loose packing). Skips the cell grid
// where its estimated distance checks per particle exceed 5000 (it would take minutes).
// Rows: {"kind": "neighbors", "method", "sizes", "size_ratio", "n", "threads", "pairs",
// "levels", "ns_per_particle", "ratio_to_monodisperse"} with the ratio taken against the same
// method and distribution at size ratio 1 ("ratio_to_cell_grid_monodisperse" against the
// cell grid's ratio-1 time) and "cpu_ns_per_particle" (process CPU time, all threads: less
// sensitive than wall time to other processes on a shared machine).
#include "bench/neighbor_bench.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <ctime>
#include <map>
#include <stdexcept>
#include <string>

#include "core/multilevel_grid.hpp"
#include "core/neighbor_search.hpp"
#include "core/parallel.hpp"
#include "core/random.hpp"

namespace gradem::bench {
namespace {

constexpr double kRMax = 0.5e-3;          // [m]
constexpr double kSolidFraction = 0.35;
constexpr double kSkinFraction = 0.15;    // of R_min, as SimParams::skin_fraction
constexpr double kMaxCellGridChecks = 5000.0;

struct Specimen {
    std::vector<Vec3> x;
    std::vector<double> r;
    double gap = 0.0;
};

std::vector<double> draw_radii(std::int64_t n, double ratio, bool power_law, SplitMix64& rng) {
    const double r_min = kRMax / ratio;
    std::vector<double> r(static_cast<std::size_t>(n), r_min);
    if (power_law && ratio > 1.0) {
        const double a = std::pow(r_min, -2.5), b = std::pow(kRMax, -2.5);
        for (double& v : r) v = std::pow(a - rng.uniform() * (a - b), -1.0 / 2.5);
    } else if (ratio > 1.0) {
        // Equal solid volume in both sizes: n_large / n_small = ratio^-3.
        const double large_share = 1.0 / (1.0 + ratio * ratio * ratio);
        for (double& v : r) v = rng.uniform() < large_share ? kRMax : r_min;
    }
    r[0] = kRMax;
    r[1] = r_min;
    return r;
}

Specimen make_specimen(std::int64_t n, double ratio, bool power_law) {
    SplitMix64 rng(2026);
    Specimen s;
    s.r = draw_radii(n, ratio, power_law, rng);
    s.gap = kSkinFraction * kRMax / ratio;
    double solid = 0.0;
    for (double v : s.r) solid += 4.0 / 3.0 * kPi * v * v * v;
    const double box = std::cbrt(solid / kSolidFraction);
    auto draw = [&]() { return Vec3{rng.uniform(0, box), rng.uniform(0, box), rng.uniform(0, box)}; };
    s.x.resize(s.r.size());
    for (Vec3& p : s.x) p = draw();
    // Redraw grains whose centre lies inside a grain more than twice as large (a few passes).
    auto search = make_multilevel_grid_search();
    std::vector<ParticlePair> pairs;
    for (int pass = 0; pass < 6; ++pass) {
        search->find_pairs(s.x, s.r, 0.0, pairs);
        std::vector<char> redraw(s.x.size(), 0);
        for (const ParticlePair& p : pairs) {
            const auto i = static_cast<std::size_t>(p.i), j = static_cast<std::size_t>(p.j);
            const std::size_t small = s.r[i] < s.r[j] ? i : j, large = small == i ? j : i;
            if (s.r[large] > 2.0 * s.r[small] && norm(s.x[large] - s.x[small]) < s.r[large]) redraw[small] = 1;
        }
        if (std::count(redraw.begin(), redraw.end(), 1) == 0) break;
        for (std::size_t i = 0; i < s.x.size(); ++i)
            if (redraw[i]) s.x[i] = draw();
    }
    return s;
}

// Estimated distance checks per particle of a single cell grid (27 cells of edge s_max).
double cell_grid_checks(const Specimen& s) {
    const double s_max = 2.0 * kRMax + s.gap;
    double solid = 0.0;
    for (double v : s.r) solid += 4.0 / 3.0 * kPi * v * v * v;
    const double volume = solid / kSolidFraction;
    return 27.0 * static_cast<double>(s.x.size()) * s_max * s_max * s_max / volume;
}

// Levels the multi-level grid chooses (its volume: the bounding box padded by one reach).
std::size_t level_count(const Specimen& s) {
    Vec3 lo = s.x.front(), hi = s.x.front();
    for (const Vec3& p : s.x) {
        lo = {std::min(lo.x, p.x), std::min(lo.y, p.y), std::min(lo.z, p.z)};
        hi = {std::max(hi.x, p.x), std::max(hi.y, p.y), std::max(hi.z, p.z)};
    }
    const double s_max = 2.0 * kRMax + s.gap;
    const Vec3 span = hi - lo + Vec3{s_max, s_max, s_max};
    return plan_levels(s.r, s.gap, span.x * span.y * span.z).cell.size();
}

struct Timing {
    double ns_per_particle = 0.0;      // wall clock
    double cpu_ns_per_particle = 0.0;  // CPU time of the process, all threads
    std::size_t pairs = 0;
};

double cpu_seconds() {
    timespec t{};
    clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
    return static_cast<double>(t.tv_sec) + 1e-9 * static_cast<double>(t.tv_nsec);
}

Timing time_search(NeighborSearch& search, const Specimen& s, int threads, int repeat) {
#ifdef _OPENMP
    omp_set_num_threads(threads);
#else
    (void)threads;
#endif
    std::vector<ParticlePair> pairs;
    search.find_pairs(s.x, s.r, s.gap, pairs);  // warm-up: buffers sized, pages touched
    std::vector<double> seconds, cpu;
    for (int k = 0; k < repeat; ++k) {
        const double c0 = cpu_seconds();
        const auto t0 = std::chrono::steady_clock::now();
        search.find_pairs(s.x, s.r, s.gap, pairs);
        seconds.push_back(std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count());
        cpu.push_back(cpu_seconds() - c0);
    }
    std::sort(seconds.begin(), seconds.end());
    std::sort(cpu.begin(), cpu.end());
    const double per = 1e9 / static_cast<double>(s.x.size());
    return {seconds[seconds.size() / 2] * per, cpu[cpu.size() / 2] * per, pairs.size()};
}

}  // namespace

void run_neighbor_bench(std::int64_t n, const std::vector<int>& threads, int repeat, bool json) {
    if (n < 2) throw std::invalid_argument("--neighbors needs at least 2 particles");
    if (!json)
        std::printf("%-10s %-16s %5s %9s %3s %10s %6s %10s %8s %8s %9s\n", "sizes", "method", "ratio", "N",
                    "thr", "pairs", "levels", "ns/part", "/mono", "/cell-1", "cpu-ns/p");
    for (const bool power_law : {true, false}) {
        const char* sizes = power_law ? "power_law" : "bimodal";
        std::map<std::pair<std::string, int>, double> mono;  // (method, threads) -> ns at ratio 1
        for (const double ratio : {1.0, 10.0, 50.0}) {
            const Specimen s = make_specimen(n, ratio, power_law);
            const auto levels = level_count(s);
            for (const bool multilevel : {false, true}) {
                const std::string method = multilevel ? "multilevel-grid" : "cell-grid";
                if (!multilevel && cell_grid_checks(s) > kMaxCellGridChecks) {
                    if (!json)
                        std::printf("%-10s %-16s %5.0f %9lld   skipped: ~%.3g distance checks per particle\n",
                                    sizes, method.c_str(), ratio, static_cast<long long>(n), cell_grid_checks(s));
                    continue;
                }
                auto search = multilevel ? make_multilevel_grid_search() : make_cell_grid_search();
                for (const int t : threads) {
                    const Timing timing = time_search(*search, s, t, repeat);
                    if (ratio == 1.0) mono[{method, t}] = timing.ns_per_particle;
                    const double to_mono = timing.ns_per_particle / mono[{method, t}];
                    const double to_cell = timing.ns_per_particle / mono[{"cell-grid", t}];
                    const std::size_t used_levels = multilevel ? levels : 1;
                    if (json)
                        std::printf("{\"kind\": \"neighbors\", \"method\": \"%s\", \"sizes\": \"%s\", "
                                    "\"size_ratio\": %.0f, \"n\": %lld, \"threads\": %d, \"pairs\": %zu, "
                                    "\"levels\": %zu, \"ns_per_particle\": %.2f, \"ratio_to_monodisperse\": %.3f, "
                                    "\"ratio_to_cell_grid_monodisperse\": %.3f, \"cpu_ns_per_particle\": %.2f}\n",
                                    method.c_str(), sizes, ratio, static_cast<long long>(n), t, timing.pairs,
                                    used_levels, timing.ns_per_particle, to_mono, to_cell, timing.cpu_ns_per_particle);
                    else
                        std::printf("%-10s %-16s %5.0f %9lld %3d %10zu %6zu %10.1f %8.2f %8.2f %9.1f\n", sizes,
                                    method.c_str(), ratio, static_cast<long long>(n), t, timing.pairs,
                                    used_levels, timing.ns_per_particle, to_mono, to_cell,
                                    timing.cpu_ns_per_particle);
                    std::fflush(stdout);
                }
            }
        }
    }
}

}  // namespace gradem::bench
