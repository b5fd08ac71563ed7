// The genesis specimen of gradem-bench's --specimens rows (bench/specimen_bench.hpp).
#include "bench/specimen_bench.hpp"

#include <chrono>
#include <cmath>
#include <stdexcept>

#include "bench/genesis_bench.hpp"
#include "bench/material_settings.hpp"
#include "experiments/virtual_tests/cube_specimen.hpp"
#include "experiments/specimen/packing_cache.hpp"

namespace gradem::bench {
namespace {

constexpr double kCalibrationEdge = 3.5e-3;     // [m] the main job's cube (calibrate/configs/joint.toml)
constexpr double kCalibrationGrains = 4349.0;   // its pre-blended grains (seed 1)

// The calibration cube's genesis (experiments/configs/calibration_cube.toml) at another edge.
exp::SpecimenSpec specimen_spec(std::int64_t grains) {
    exp::SpecimenSpec spec;
    spec.size_rule.min_diameter = 0.149e-3;
    spec.size_rule.max_diameter = 0.8e-3;
    spec.genesis.edge = kCalibrationEdge * std::cbrt(static_cast<double>(grains) / kCalibrationGrains);
    spec.genesis.equilibrium_ratio = 0.05;
    spec.genesis.max_steps = 400000;  // large packings need more minimisation iterations
    spec.seed = 1;
    return spec;
}

}  // namespace

exp::Packing specimen_packing(std::int64_t grains, const std::filesystem::path& cache_dir, double& seconds,
                              bool& cached) {
    const auto t0 = std::chrono::steady_clock::now();
    exp::Packing k = exp::load_or_generate(pre_blended_curve(), specimen_spec(grains), cache_dir, &cached);
    seconds = cached ? 0.0 : std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    return k;
}

exp::MaterialParams specimen_material(const BondCase& c) {
    const exp::MaterialParams m = bench_material(c.model, 11.0e9, 17.0e6, 8.5e6, 1e-6 * kSpecimenGapUm, c.settings);
    if (auto why = m.invalid_reason()) throw UsageError(*why);
    return m;
}

World specimen_world(const exp::Packing& packing, const exp::MaterialParams& m) {
    World world = exp::bonded_cube_specimen(packing, m);
    const double height = world.walls()[1].point.z - world.walls()[0].point.z;
    world.wall(0).velocity = {0, 0, 0.5 * height};  // strain rate 1/s, as the lattice rows
    world.wall(1).velocity = {0, 0, -0.5 * height};
    return world;
}

}  // namespace gradem::bench
