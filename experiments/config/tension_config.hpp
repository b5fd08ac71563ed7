#pragma once
// The direct-tension test reads the same config file as the compression test (cube_config.hpp:
// the same specimen, material, loading, gauges and output), plus an optional [tension] table
// for what only tension has (experiments/README.md lists the keys):
//   [tension]   grip_depth_fraction, auto_peak_strain, auto_transits
// Unknown keys, wrong types and out-of-range values throw common::InputError "file:line: key
// 'tension.x' = v violates rule", like the other tables.
#include "experiments/config/cube_config.hpp"
#include "experiments/virtual_tests/tension_test.hpp"

namespace gradem::exp {

struct TensionConfig {
    TensionTestSpec spec;             ///< config.test plus the grips
    /// Expected tensile peak strain for strain_rate_per_s = "auto" [-]; 0 (the default): from
    /// the material, expected_tensile_peak_strain().
    double auto_peak_strain = 0.0;
    /// Wave transits of the specimen before the expected peak for "auto" [-]: fewer than
    /// compression's 200, as a tension test is run for its strength alone. Measured on the main
    /// job's flat-joint cubes at its calibrated parameters (experiments/README.md "Direct tension"):
    /// σt at 100 transits is 0.3-1.1 % above σt at 200, and 200 is within 0.5 % of 400.
    double auto_transits = 100.0;
};

/// The tensile peak strain a bonded specimen of this material is expected to reach [-]: the
/// law's PlatenTestCost::tension_peak_over_bond_strain × σ̄_c/Ē (the bonds' mean tensile
/// strength over their modulus; core/law_parameters.hpp). Measured: parallel-bond cubes at the
/// parallel-bond main job's parameters peak at 0.62 σ̄_c/Ē (its row: 0.5), flat-joint cubes at
/// the main job's at 0.75-1.06 σ̄_c/Ē (its row: 0.75).
double expected_tensile_peak_strain(const MaterialParams& material);

/// The tension test of a loaded config: config.test plus the [tension] table of config.file.
TensionConfig load_tension_config(const CubeConfig& config);

/// The strain rate [1/s] to pull at: the configured one, or for "auto" the compression test's
/// rule (quasi_static_strain_rate) with tension.auto_transits wave transits to the expected
/// tensile peak strain (tension.auto_peak_strain if set, else
/// expected_tensile_peak_strain(config.material)).
double tension_strain_rate(const CubeConfig& config, const TensionConfig& tension, const Packing& packing);

}  // namespace gradem::exp
