#pragma once
// Result files of one direct-tension test (`gradem tension`), each written atomically into
// `dir` (the command uses <output dir>/tension, next to the compression test's files):
//   load_curve.csv  the columns of the compression test's (cube_output.hpp), tension positive:
//                   platen_strain = grip opening / height, gauge_strain = extensometer
//                   extension, stress_* = grip load / initial area; lateral_strain stays
//                   expansion positive (negative in tension)
//   cracks.csv      as in compression (platen_strain = grip opening strain at the break)
//   macro.json      tensile strength σt, strain at peak (gauge, grips), tensile chord and
//                   tangent moduli, Poisson's ratio, the reduction, the grips, the run, breaks
//                   by mode, material, specimen, the rate check if run, and with a compression
//                   macro.json of the same config: σc, its chord modulus and σc/σt.
#include <filesystem>
#include <optional>
#include <string>

#include "experiments/config/cube_config.hpp"
#include "experiments/virtual_tests/tension_test.hpp"
#include "reports/cube_output.hpp"

namespace gradem::report {

/// The compression result a tension run is compared with.
struct CompressionReference {
    std::filesystem::path file;    ///< its macro.json
    double peak_stress = 0.0;      ///< σc [Pa]
    double chord_modulus = 0.0;    ///< [Pa] (NaN if it was not reduced)
};

/// Reads a compression macro.json and checks what can be checked before a packing exists: the
/// file is readable JSON and the macro.json of a compression test (a numeric peak_stress_mpa,
/// no tensile_strength_mpa). Throws common::InputError naming the file. The tension command
/// calls it before genesis, read_compression_reference() once the packing is there.
void check_compression_file(const std::filesystem::path& macro_json_file);

/// Reads a compression macro.json and checks that it is of the same material and specimen as
/// the tension run (its "material" and "specimen" blocks equal the ones this run writes).
/// Throws common::InputError naming the file and what differs or is missing.
CompressionReference read_compression_reference(const std::filesystem::path& macro_json_file, const exp::CubeConfig& config,
                                                const exp::Packing& packing);

/// The macro.json text (exposed for tests); the CSVs are cube_output's load_curve_csv and
/// cracks_csv of result.cube.
std::string tension_macro_json(const exp::TensionTestResult& result, const exp::CubeConfig& config, const exp::TensionTestSpec& spec,
                               const exp::Packing& packing, double strain_rate, const std::optional<RateCheck>& rate_check = {},
                               const std::optional<CompressionReference>& compression = {});

/// Writes load_curve.csv, cracks.csv and macro.json into `dir` (created), each atomically, macro.json last.
void write_tension_outputs(const std::filesystem::path& dir, const exp::TensionTestResult& result, const exp::CubeConfig& config,
                           const exp::TensionTestSpec& spec, const exp::Packing& packing, double strain_rate,
                           const std::optional<RateCheck>& rate_check = {},
                           const std::optional<CompressionReference>& compression = {});

}  // namespace gradem::report
