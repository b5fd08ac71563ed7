#pragma once
// A parameter study, read from a TOML file (experiments/studies/*.toml; every key is documented
// in experiments/README.md):
//
//   [study]   kind, calibration (a calibration's summary.json: the parameters studied and,
//             through its config, the base cube, sands and lab targets), seeds, and the kind's
//             own keys: edges_mm + tolerance (resolution), min_diameters_mm (fines_truncation),
//             parameters + step (sensitivity), calibrations (model_form)
//   [run]     workers, timeout_s
//   [output]  dir, ledger
//
// Kinds:
//   gradation_effect  the calibrated parameters on every sand over the seeds: does the
//                     simulated difference between the sands match the lab's (95 % intervals)?
//   resolution        cube edge sweep: mean and spread per size, the size beyond which the
//                     properties change less than their seed spread (or than `tolerance`)
//   fines_truncation  smallest kept grain sweep: cost (particles, wall time) against the
//                     change from the finest case
//   sensitivity       one-at-a-time elasticities d ln(property) / d ln(parameter), with seeds
//   model_form        calibrations of different bond models side by side (reads summaries)
// Every error is a common::InputError naming the file, line and key.
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include "common/named_enum.hpp"

namespace gradem::cal {

enum class StudyKind { gradation_effect, resolution, fines_truncation, sensitivity, model_form };
constexpr EnumNameTable<StudyKind, 5> enum_name_table(StudyKind) {
    return {{{StudyKind::gradation_effect, "gradation_effect"},
             {StudyKind::resolution, "resolution"},
             {StudyKind::fines_truncation, "fines_truncation"},
             {StudyKind::sensitivity, "sensitivity"},
             {StudyKind::model_form, "model_form"}}};
}

struct StudyConfig {
    std::filesystem::path file;
    StudyKind kind = StudyKind::gradation_effect;
    std::filesystem::path calibration;                 ///< summary.json of the calibration studied
    std::vector<std::filesystem::path> calibrations;   ///< model_form: one summary per model
    std::vector<std::uint64_t> seeds = {1, 2, 3, 4, 5};
    std::vector<std::string> sands;                    ///< a subset of the calibration's sands (empty: all)
    int sands_line = 0;                                ///< where `sands` was given, for errors
    std::vector<double> sweep_mm;                      ///< edges (resolution) or min diameters (fines) [mm]
    std::vector<std::string> parameters;               ///< sensitivity: names (empty: every free one)
    double step = 0.10;                                ///< sensitivity: relative step of each parameter
    double tolerance = 0.0;                            ///< resolution: a change below this relative size counts
                                                       ///< as converged even where the seed spread is smaller
    int workers = 2;
    double timeout_s = 600.0;
    std::filesystem::path out_dir, ledger;

    /// Canonical text of everything that defines the study's answer (its ledger identity).
    [[nodiscard]] std::string describe() const;
};

StudyConfig load_study_config(const std::filesystem::path& toml_file);

}  // namespace gradem::cal
