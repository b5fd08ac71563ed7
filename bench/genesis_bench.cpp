// Genesis rows of gradem-bench: time, equilibrium and porosity of specimen genesis for the
// study's pre-blended sand with the default cube's size rule (0.149 .. 1.0 mm, solid fraction
// 0.60), the cube edge scaled so that about N grains are sampled (the default 3.2 mm cube holds
// ~3200). Not a test: the numbers depend on the machine.
#include "bench/genesis_bench.hpp"

#include <cmath>
#include <cstdio>

#include "bench/full_cube_bench.hpp"
#include "core/parallel.hpp"
#include "experiments/specimen/genesis.hpp"

namespace gradem::bench {

// The study's Table 2, pre-blended sand (sieve size [m], mass fraction passing), as in
// lab_data/datasets/study.
lab::GradationCurve pre_blended_curve() {
    return lab::GradationCurve::from_points({4.75e-3, 2.36e-3, 1.18e-3, 0.595e-3, 0.4e-3, 0.3e-3, 0.149e-3, 0.075e-3},
                                            {1.0, 0.996, 0.981, 0.919, 0.832, 0.699, 0.256, 0.0});
}

namespace {

constexpr double kDefaultEdge = 3.2e-3;      // [m]
constexpr double kDefaultGrains = 3226.0;    // grains of the default cube (seed 1)

exp::SpecimenSpec spec_for(std::int64_t n) {
    exp::SpecimenSpec spec;
    spec.size_rule.min_diameter = 0.149e-3;
    spec.size_rule.max_diameter = 1.0e-3;
    spec.genesis.edge = kDefaultEdge * std::cbrt(static_cast<double>(n) / kDefaultGrains);
    spec.genesis.max_steps = 400000;
    spec.seed = 1;
    return spec;
}

}  // namespace

void run_genesis_bench(const std::vector<std::int64_t>& sizes, bool json) {
    if (!json)
        std::printf("%9s %8s %3s %9s %10s %8s %9s %8s %6s %9s\n", "N", "edge mm", "thr", "seconds", "iterations",
                    "DEM", "ratio", "porosity", "conv", "floaters");
    for (std::int64_t n : sizes) {
        const exp::SpecimenSpec spec = spec_for(n);
        const exp::Packing k = exp::generate_packing(pre_blended_curve(), spec);
        if (json)
            std::printf("{\"kind\": \"genesis\", \"n\": %zu, \"edge_mm\": %.4f, \"threads\": %d, \"seconds\": %.3f, "
                        "\"iterations\": %lld, \"dem_steps\": %lld, \"unbalanced_ratio\": %.4g, \"porosity\": %.4f, "
                        "\"converged\": %s, \"floaters\": %.4f, \"peak_rss_mib\": %.1f}\n",
                        k.radius.size(), k.edge() * 1e3, thread_count(), k.seconds, static_cast<long long>(k.relax_iterations),
                        static_cast<long long>(k.steps), k.unbalanced_ratio, k.porosity, k.converged ? "true" : "false",
                        k.floaters_after, static_cast<double>(peak_rss_bytes()) / 1048576.0);
        else
            std::printf("%9zu %8.3f %3d %9.2f %10lld %8lld %9.3g %8.4f %6s %8.2f%%\n", k.radius.size(), k.edge() * 1e3,
                        thread_count(), k.seconds, static_cast<long long>(k.relax_iterations), static_cast<long long>(k.steps),
                        k.unbalanced_ratio, k.porosity, k.converged ? "yes" : "NO", 100.0 * k.floaters_after);
        std::fflush(stdout);
    }
}

}  // namespace gradem::bench
