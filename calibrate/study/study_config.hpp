#pragma once
// A parameter study, read from a TOML file (experiments/studies/*.toml; every key is documented
// in experiments/README.md):
//
//   [study]   kind (one of calibrate/study/study_kind.hpp's rows), calibration (a calibration's
//             summary.json: the parameters studied and, through its config, the base cube,
//             sands and lab targets) or calibrations (kinds that compare several), seeds, and
//             the kind's own keys (read by its file in calibrate/study/kinds/)
//   [run]     workers, timeout_s
//   [output]  dir, ledger
//
// Every error is a common::InputError naming the file, line and key.
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include "calibrate/study/study_kind.hpp"

namespace gradem::cal {

/// A study file's settings. The kinds' own keys are fields here, each read and checked by the
/// kinds it belongs to (StudyKindSpec::keys).
struct StudyConfig {
    std::filesystem::path file;
    StudyKind kind{};  ///< required in the file
    std::filesystem::path calibration;                 ///< summary.json of the calibration studied
    std::vector<std::filesystem::path> calibrations;   ///< kinds comparing several: one summary each
    std::vector<std::uint64_t> seeds = {1, 2, 3, 4, 5};
    std::vector<std::string> sands;                    ///< a subset of the calibration's sands (empty: all)
    int sands_line = 0;                                ///< where `sands` was given, for errors
    std::vector<double> sweep_mm;                      ///< the swept sizes (cube edges or min diameters) [mm]
    std::vector<std::string> parameters;               ///< the parameters varied (empty: every free one)
    double step = 0.10;                                ///< relative step of each varied parameter
    double tolerance = 0.0;                            ///< a change below this relative size counts as
                                                       ///< converged even where the seed spread is smaller
    int workers = 2;
    double timeout_s = 600.0;
    std::filesystem::path out_dir, ledger;

    /// Canonical text of everything that defines the study's answer (its ledger identity).
    [[nodiscard]] std::string describe() const;
};

StudyConfig load_study_config(const std::filesystem::path& toml_file);

}  // namespace gradem::cal
