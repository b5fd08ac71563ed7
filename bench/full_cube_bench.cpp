// The full-size cube (issue 10 item 5): the study's 50 mm cube with its gradation cut at the
// No. 100 sieve. Genesis of ~1.2 M grains is not run here (see bench/README.md: its time and
// memory are extrapolated from measured genesis rows); this mode measures what can be measured
// directly on 2 cores:
//   - N: grains sampled by mass from the pre-blended curve for the 50 mm cube at phi = 0.60;
//   - the cost of 1000 bonded steps at that N, on an O(N) dense packing (experiments/
//     quick_packing: radius ratio 3, ~2.5 bonds per grain) whose smallest grain is the real
//     one (d = 0.149 mm), so the automatic time step is close to the real specimen's;
//   - peak memory of that World;
//   - the steps of a whole test: with the "auto" strain rate (experiments/cube_test.cpp) the
//     time to the stop is a fixed number of wave transits of the cube, t = transits L / c with
//     c = sqrt(E*/rho), so steps = transits L / (c dt). `transits_to_stop` is measured on the
//     default cube (bench/README.md) and passed in.
#include "bench/full_cube_bench.hpp"

#include <cmath>
#include <cstdio>

#include "bench/genesis_bench.hpp"
#include "experiments/grain_sampler.hpp"

namespace gradem::bench {
namespace {

constexpr double kEdge = 50.0e-3;          // [m] the study's cube
constexpr double kMinDiameter = 0.149e-3;  // [m] No. 100 sieve
constexpr double kSolidFraction = 0.60;    // [-] as the default cube
constexpr double kModulus = 10.0e9;        // [Pa] E* of the timed World (gradem_bench.cpp)
constexpr double kDensity = 2650.0;        // [kg/m^3] of the quick packing

}  // namespace

void run_full_cube_bench(int threads, std::int64_t steps, double transits_to_stop, bool json) {
    exp::SizeRule rule;
    rule.min_diameter = kMinDiameter;
    rule.max_diameter = 0.0;
    const exp::GrainSample grains = exp::sample_grains(pre_blended_curve(), rule, kSolidFraction * kEdge * kEdge * kEdge, 1);
    const auto n = static_cast<std::int64_t>(grains.diameters.size());

    exp::QuickPackingSpec spec;
    spec.target_count = n;
    spec.max_radius = 0.5 * kMinDiameter * spec.radius_ratio;  // smallest radius = the real one
    const exp::QuickPacking packing = exp::make_quick_packing(spec);
    const TimedRun run = time_bonded_run(packing, threads, steps);

    const double per_1000 = run.seconds * 1000.0 / static_cast<double>(steps);
    const double wave_speed = std::sqrt(kModulus / kDensity);
    const double test_steps = transits_to_stop * kEdge / (wave_speed * run.time_step);
    const double test_seconds = test_steps / 1000.0 * per_1000 * static_cast<double>(n) / static_cast<double>(run.particles);
    if (json) {
        std::printf("{\"kind\": \"full_cube\", \"n\": %lld, \"d50_mm\": %.3f, \"timed_particles\": %lld, \"timed_bonds\": %lld, "
                    "\"threads\": %d, \"steps\": %lld, \"seconds_per_1000_steps\": %.2f, \"time_step_s\": %.4g, "
                    "\"peak_rss_mib\": %.0f, \"transits_to_stop\": %.0f, \"test_steps\": %.4g, \"test_hours\": %.3g}\n",
                    static_cast<long long>(n), grains.d50 * 1e3, static_cast<long long>(run.particles),
                    static_cast<long long>(run.bonds), threads, static_cast<long long>(steps), per_1000, run.time_step,
                    static_cast<double>(run.peak_rss) / 1048576.0, transits_to_stop, test_steps, test_seconds / 3600.0);
        return;
    }
    std::printf("full-size cube: 50 mm, pre-blended sand cut at 0.149 mm: N = %lld grains (d50 %.3f mm)\n",
                static_cast<long long>(n), grains.d50 * 1e3);
    std::printf("timed: %lld spheres, %lld bonds, %d threads, %lld steps: %.2f s per 1000 steps, dt %.3g s, peak RSS %.0f MiB\n",
                static_cast<long long>(run.particles), static_cast<long long>(run.bonds), threads,
                static_cast<long long>(steps), per_1000, run.time_step, static_cast<double>(run.peak_rss) / 1048576.0);
    std::printf("whole compression test (auto rate, %.0f wave transits to the stop): %.3g steps, %.3g h on %d threads\n",
                transits_to_stop, test_steps, test_seconds / 3600.0, threads);
}

}  // namespace gradem::bench
