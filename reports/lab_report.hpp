#pragma once
// Writers for LabStats: the JSON calibration reads, CSV tables, and the printed Table 2 /
// Table 4-style report. Display units: MPa for stresses and moduli, mm for sizes, strain as a
// plain number; keys carry the unit (_mpa, _mm).

#include <filesystem>
#include <iosfwd>
#include <nlohmann/json.hpp>
#include <string>

#include "lab_data/lab_stats.hpp"

namespace gradem::report {

/// The JSON contract (see lab_data/README.md): representative_data, note, sands[], cubes[],
/// comparisons[]. NaN values are written as null.
nlohmann::json lab_stats_to_json(const lab::LabStats& lab);

std::string cubes_csv(const lab::LabStats& lab);
std::string sand_stats_csv(const lab::LabStats& lab);
std::string gradation_csv(const lab::LabStats& lab);
std::string comparisons_csv(const lab::LabStats& lab);
/// One row per tension specimen: test, peak load, geometry (mm), strength, MC2010 factor, direct equivalent.
std::string tensile_tests_csv(const lab::LabStats& lab);
/// Each cube's stress-strain curve for plots: every k-th sample (at most kCurvePointsPerCube per
/// cube) plus the peak sample, so a curve's largest stress is the cube's peak stress.
inline constexpr std::size_t kCurvePointsPerCube = 200;
std::string curves_csv(const lab::LabStats& lab);

/// Writes lab_results.json, cubes.csv, tensile_tests.csv, sand_stats.csv, gradation.csv, comparisons.csv, curves.csv into
/// `dir` (created if needed). Each file is written to a temporary name first and renamed only
/// once all are complete, so a failure leaves no partial result behind.
void write_lab_outputs(const std::filesystem::path& dir, const lab::LabStats& lab);

/// Table 2 (gradation), gradation indices and C144 verdicts, Table 4 (strength) and the other
/// per-sand statistics, the tensile strengths, Welch tests, C109 range flags; `per_cube` adds one
/// row per cube and per tension specimen.
void print_lab_report(std::ostream& out, const lab::LabStats& lab, bool per_cube);

}  // namespace gradem::report
