#pragma once
// The calibration's result files (each written whole or not at all), in the output folder:
//   summary.json     parameters with standard errors, runs, wall time, and per sand and target
//                    the lab mean ± std, the simulated mean ± seed spread, relative error, z
//   summary.md       the same for people, with plain statements on unmet targets
//   convergence.csv  every evaluation in order: budget used, objective, parameters, outputs
//   curves.csv       simulated stress-strain curves at the calibrated parameters (each seed)
//                    and the lab's mean curve (Popovics through the lab means)
//   calibrated-<sand>.toml  the base cube config at the calibrated parameters (calibrated_config.hpp)
// and the one-line brief report for the terminal.
#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>

#include "calibrate/calibration.hpp"

namespace gradem::report {

nlohmann::json summary_json(const cal::CalibrationProblem& problem, const cal::CalibrationResult& result);
std::string summary_markdown(const cal::CalibrationProblem& problem, const cal::CalibrationResult& result);
std::string convergence_csv(const cal::CalibrationProblem& problem, const cal::CalibrationResult& result);
std::string curves_csv(const cal::CalibrationProblem& problem, const cal::CalibrationResult& result);
std::string brief_report(const cal::CalibrationProblem& problem, const cal::CalibrationResult& result);

/// Writes the files above into problem.out_dir.
void write_calibration_outputs(const cal::CalibrationProblem& problem, const cal::CalibrationResult& result);

}  // namespace gradem::report
