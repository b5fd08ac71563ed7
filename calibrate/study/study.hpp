#pragma once
// `gradem study`: parameter studies run through the calibration's machinery - the same
// CubeModel (cached packings), Evaluator and SQLite ledger - so a study is resumable after
// `kill -9`, identical runs are served from the ledger and failed runs are recorded and shown.
// Each kind is one file in calibrate/study/kinds/ (study_kind.hpp lists them); run_study loads
// the calibration(s) studied, opens the study's ledger and runs the kind.
#include <functional>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "calibrate/cube_model.hpp"
#include "calibrate/problem.hpp"
#include "calibrate/study/study_config.hpp"
#include "calibrate/study/study_statistics.hpp"

namespace gradem::cal {

/// A calibration's result as a study needs it: its problem (from the summary's config) and
/// the calibrated free parameters (config units, in the problem's ParameterSpace order).
struct CalibratedPoint {
    std::filesystem::path summary;
    CalibrationProblem problem;
    std::vector<double> values;
    std::string bond_model;  ///< the material's bond model name (", explicit_paste" appended for paste specimens)
    nlohmann::json document;  ///< summary.json as read
};

/// Reads summary.json and its calibration problem; InputError naming the summary when it
/// does not exist, is not a calibration summary, or no longer matches its config (other
/// sands, other lab results, a parameter outside the config's bounds). When the calibration set
/// its scales on scale-up specimens, the problem's specimen edge is theirs (the result's size).
CalibratedPoint load_calibrated_point(const std::filesystem::path& summary_json);

/// One simulated configuration of a study: a label, the swept value (if any), and every run.
struct StudyCase {
    std::string label;
    double x = 0.0;                                ///< swept value (edge or min diameter [mm], step)
    std::vector<std::string> sands;
    std::vector<std::uint64_t> seeds;              ///< the packing seeds of runs[sand][k] (a calibration's sand with
                                                   ///< seeds of its own, run on them: its sand_seeds list)
    std::vector<std::vector<RunOutcome>> runs;     ///< per sand, per seed
    [[nodiscard]] Sample sample(std::size_t sand, Quantity q) const;
    [[nodiscard]] double mean_particles(std::size_t sand) const;
    [[nodiscard]] double mean_wall_seconds(std::size_t sand) const;
    [[nodiscard]] int failed() const;
};

/// A line of a result table, kept generic so one writer serves every kind.
struct StudyRow {
    std::vector<std::string> cells;
};
struct StudyTable {
    std::string title;
    std::vector<std::string> header;
    std::vector<StudyRow> rows;
};

struct StudyResult {
    StudyConfig config;
    std::vector<std::string> calibration_summaries;
    bool representative = false;          ///< the lab data behind it are representative
    std::vector<StudyCase> cases;
    std::vector<StudyTable> tables;
    std::vector<std::string> verdict;     ///< plain-language answers, one per line
    nlohmann::json data;                  ///< the kind's numbers (intervals, convergence, ...)
    int runs_executed = 0, runs_from_ledger = 0, runs_failed = 0;
    double wall_seconds = 0.0;
};

struct StudyExecution;

/// The calibration(s) the study's kind studies, each checked (and the study's sands against
/// it): InputError as load_calibrated_point. Their summaries go to result.calibration_summaries.
std::vector<CalibratedPoint> load_studied(const StudyConfig& config, StudyResult& result);

/// Runs the study; its runs go to threads of this process, or to `execution`'s executor (the
/// worker ranks of an MPI job: calibrate/study/study_models.hpp), with the same results.
StudyResult run_study(const StudyConfig& config, const std::function<void(const std::string&)>& log = {},
                      const StudyExecution* execution = nullptr);

}  // namespace gradem::cal
