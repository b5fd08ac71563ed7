#pragma once
// The calibrated material as cube configs: for every calibrated sand, the calibration's base
// cube config with its [material] set to the stage's best point (every row of the material table
// the bond model uses, config units), its specimen set to that sand and to the calibration's
// edge and paste size, its paths made absolute and its output folder inside the calibration's.
// `gradem compress out/calibration-joint/calibrated-pre-blended.toml` then runs one cube test at
// the calibrated parameters (another seed, a larger edge, the tension test: edit the copy).
#include <filesystem>
#include <string>
#include <utility>
#include <vector>

#include "calibrate/calibration.hpp"

namespace gradem::report {

/// (path, text) of calibrated-<sand>.toml for every sand a stage with a solution fitted or predicted.
std::vector<std::pair<std::filesystem::path, std::string>> calibrated_cube_configs(const cal::CalibrationProblem& problem,
                                                                                    const cal::CalibrationResult& result);

}  // namespace gradem::report
