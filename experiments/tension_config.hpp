#pragma once
// The direct-tension test reads the same config file as the compression test (cube_config.hpp:
// the same specimen, material, loading, gauges and output), plus an optional [tension] table
// for what only tension has (experiments/README.md lists the keys):
//   [tension]   grip_depth_fraction, auto_peak_strain
// Unknown keys, wrong types and out-of-range values throw common::InputError "file:line: key
// 'tension.x' = v violates rule", like the other tables.
#include "experiments/cube_config.hpp"
#include "experiments/tension_test.hpp"

namespace gradem::exp {

struct TensionConfig {
    TensionTestSpec spec;             ///< config.test plus the grips
    double auto_peak_strain = 3.0e-4; ///< expected tensile peak strain for strain_rate_per_s = "auto" [-]
};

/// The tension test of a loaded config: config.test plus the [tension] table of config.file.
TensionConfig load_tension_config(const CubeConfig& config);

/// The strain rate [1/s] to pull at: the configured one, or for "auto" the compression test's
/// rule (quasi_static_strain_rate: 200 wave transits) to the expected tensile peak strain.
double tension_strain_rate(const CubeConfig& config, const TensionConfig& tension, const Packing& packing);

}  // namespace gradem::exp
