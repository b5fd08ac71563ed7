// The full-size cube: the study's 50 mm cube with its gradation cut at the
// No. 100 sieve. N is sampled exactly (about 1e7 grains at 0.149 mm, 1.3e6 at the No. 50 sieve,
// 0.3 mm); a World of 1e7 spheres does not fit the 2 GiB asked (~1 kB per sphere), so the
// cost is measured on `timed` spheres and scaled linearly to N (the cost per particle-step
// is flat in N within 1.3x between 2e4 and 2e5: bench/README.md). Genesis is not run here
// (its time and memory are extrapolated from measured genesis rows, bench/README.md).
//   - N: grains sampled by mass from the pre-blended curve for the 50 mm cube at phi = 0.60;
//   - the cost of 1000 bonded steps on an O(N) dense packing (experiments/quick_packing:
//     radius ratio 3, ~2.5 bonds per grain) whose smallest grain is the real one, so the
//     automatic time step is close to the real specimen's;
//   - peak memory per sphere of that World;
//   - the steps of a whole test: with the "auto" strain rate (experiments/virtual_tests/cube_test.cpp) the
//     time to the stop is a fixed number of wave transits of the cube, t = transits L / c with
//     c = sqrt(E*/rho), so steps = transits L / (c dt). `transits_to_stop` is measured on the
//     default cube (bench/README.md) and passed in.
#include "bench/full_cube_bench.hpp"

#include <cmath>
#include <cstdio>

#include "bench/genesis_bench.hpp"
#include "experiments/specimen/grain_sampler.hpp"

namespace gradem::bench {
namespace {

constexpr double kEdge = 50.0e-3;          // [m] the study's cube
constexpr double kMinDiameter = 0.149e-3;  // [m] No. 100 sieve
constexpr double kSolidFraction = 0.60;    // [-] as the default cube
constexpr double kModulus = 11.0e9;        // [Pa] E* of the default cube (wave speed of `transits`)
constexpr double kDensity = 2640.0;        // [kg/m^3] its grain density

}  // namespace

void run_full_cube_bench(const FullCubeOptions& o) {
    exp::QuickPackingSpec spec;
    spec.target_count = o.timed;
    spec.max_radius = 0.5 * o.min_diameter * spec.radius_ratio;  // smallest radius = the real one
    const TimedRun run = time_bonded_run(exp::make_quick_packing(spec), o.threads, o.steps);

    exp::SizeRule rule;  // sampled after the timed run: its peak RSS is the World's
    rule.min_diameter = o.min_diameter;
    rule.max_diameter = 0.0;
    const exp::GrainSample grains = exp::sample_grains(pre_blended_curve(), rule, kSolidFraction * kEdge * kEdge * kEdge, 1);
    const auto n = static_cast<double>(grains.diameters.size());

    const double timed = static_cast<double>(run.particles);
    const double per_1000 = run.seconds * 1000.0 / static_cast<double>(o.steps) * n / timed;  // at N
    const double rss_per_sphere = static_cast<double>(run.peak_rss) / timed;
    const double world_per_sphere = static_cast<double>(run.world_bytes) / timed;
    const double dt = o.time_step > 0.0 ? o.time_step : run.time_step;
    const double wave_speed = std::sqrt(kModulus / kDensity);
    const double test_steps = o.transits_to_stop * kEdge / (wave_speed * dt);
    const double test_hours = test_steps / 1000.0 * per_1000 / 3600.0;
    if (o.json) {
        std::printf("{\"kind\": \"full_cube\", \"n\": %.0f, \"min_diameter_mm\": %.3f, \"d50_mm\": %.3f, \"timed_particles\": %lld, "
                    "\"timed_bonds\": %lld, \"threads\": %d, \"steps\": %lld, \"seconds_per_1000_steps\": %.1f, "
                    "\"time_step_s\": %.4g, \"world_bytes_per_sphere\": %.0f, \"peak_rss_bytes_per_sphere\": %.0f, "
                    "\"memory_gib\": %.2f, \"transits_to_stop\": %.0f, \"test_steps\": %.4g, \"test_hours\": %.3g}\n",
                    n, o.min_diameter * 1e3, grains.d50 * 1e3, static_cast<long long>(run.particles),
                    static_cast<long long>(run.bonds), o.threads, static_cast<long long>(o.steps), per_1000, dt,
                    world_per_sphere, rss_per_sphere, rss_per_sphere * n / 1073741824.0, o.transits_to_stop, test_steps,
                    test_hours);
        return;
    }
    std::printf("full-size cube: 50 mm, pre-blended sand cut at %.3f mm: N = %.4g grains (d50 %.3f mm)\n",
                o.min_diameter * 1e3, n, grains.d50 * 1e3);
    std::printf("timed: %lld spheres, %lld bonds, %d threads, %lld steps; World %.0f B, peak RSS %.0f B per sphere\n",
                static_cast<long long>(run.particles), static_cast<long long>(run.bonds), o.threads,
                static_cast<long long>(o.steps), world_per_sphere, rss_per_sphere);
    std::printf("scaled to N: %.1f s per 1000 steps, %.2f GiB (peak RSS)\n", per_1000, rss_per_sphere * n / 1073741824.0);
    std::printf("whole compression test (auto rate, %.0f wave transits to the stop, dt %.3g s): %.3g steps, %.3g h on %d threads\n",
                o.transits_to_stop, dt, test_steps, test_hours, o.threads);
}

}  // namespace gradem::bench
