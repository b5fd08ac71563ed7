#pragma once
// A whole calibration: open (or resume) the ledger, prepare the packings, run the mode's
// solves, estimate the uncertainty, and collect what the reports need.
//   joint     one parameter set for every sand (the paste is the same): 3 targets per sand
//   per_sand  one solve per sand (3 targets each: no test of the model, only a fit)
//   study     the study's protocol: calibrate on `calibrate_on`, then predict the other
//             sands with the same parameters and report the prediction error
// With [scale_up], each stage's scales are then set on the scale-up specimens (scale_up.hpp);
// with [validation], each stage's result is then run on the validation specimens.
#include <functional>
#include <string>
#include <vector>

#include "calibrate/cube_model.hpp"
#include "calibrate/evaluator.hpp"
#include "calibrate/problem.hpp"
#include "calibrate/stage_cost.hpp"
#include "calibrate/execution/run_executor.hpp"
#include "calibrate/scale_up.hpp"
#include "calibrate/solvers/solver.hpp"
#include "calibrate/uncertainty.hpp"
#include "calibrate/validation.hpp"

namespace gradem::cal {

struct CalibrationStage {
    std::string label;                     ///< "joint", a sand's name, or "calibrated on <sand>"
    std::vector<std::size_t> fitted;       ///< sands whose targets were fitted
    std::vector<std::size_t> predicted;    ///< sands predicted with the fitted parameters (study)
    SolveResult solution;
    Uncertainty uncertainty;
    Evaluation prediction;                 ///< study mode: the best point run on `predicted`
    StageScaleUp scale_up;                 ///< the scales set on the scale-up specimens ([scale_up])
    StageValidation validation;            ///< the result on the validation specimens ([validation])
    double noise_floor[kQuantityCount] = {0, 0, 0, 0};  ///< max relative standard error of the seed mean, by quantity (measure_noise)
    /// The outcome of sand s (fitted or predicted) at the calibrated parameters; nullptr if none.
    [[nodiscard]] const SandOutcome* outcome(std::size_t sand) const;
    /// The stage's result: the fit's best point, with its scales set on the scale-up specimens
    /// when that was done (empty: no result).
    [[nodiscard]] const std::vector<double>& result() const { return scale_up.point.empty() ? solution.best : scale_up.point; }
    /// Sand s on the scale-up specimens at the result (predicted by the rescaling); nullptr if none.
    [[nodiscard]] const SandOutcome* scaled_outcome(std::size_t sand) const;
    /// Sand s on the validation specimens; nullptr if not validated.
    [[nodiscard]] const SandOutcome* validation_outcome(std::size_t sand) const;
    /// The sands a stage's result holds for: fitted, then predicted.
    [[nodiscard]] std::vector<std::size_t> sands() const;
    [[nodiscard]] const Evaluation* evaluation_of(std::size_t sand) const;
};

struct CalibrationResult {
    std::string fingerprint;
    std::vector<CalibrationStage> stages;
    std::vector<Evaluation> history;
    int runs_used = 0, runs_executed = 0, runs_from_ledger = 0, runs_failed = 0;
    int scale_up_runs = 0;                 ///< runs of the scale-up specimens (apart from the budget)
    int validation_runs = 0;               ///< runs of the validation specimens (apart from the budget)
    /// What each part cost: the fit's runs (with the tension tests at its result), the
    /// scale-up's and the validation's.
    StageCost fit_cost, scale_up_cost, validation_cost;
    double wall_seconds = 0.0;
    std::vector<std::string> log;          ///< the milestone lines
};

/// The calibration with the runs on `problem.workers` threads of this process.
CalibrationResult run_calibration(const CalibrationProblem& problem, CubeModel& model,
                                  const std::function<void(const std::string&)>& log = {},
                                  const std::function<void(const Progress&)>& progress = {});

/// The calibration with the runs on `executor` (threads or MPI ranks): the same answer.
/// `model` gives the fingerprint of the runs (the ledger's identity).
CalibrationResult run_calibration(const CalibrationProblem& problem, const CubeModel& model, RunExecutor& executor,
                                  const std::function<void(const std::string&)>& log = {},
                                  const std::function<void(const Progress&)>& progress = {});

/// The model for a problem: DEM (model = "dem") or the analytic stand-in; it runs the
/// direct-tension test too when `tension` or the problem fits the tensile strength, and is a
/// ValidatedModel (fit, scale-up and validation specimens) when the problem has [scale_up] or
/// [validation].
std::unique_ptr<CubeModel> make_model(const CalibrationProblem& problem, bool tension = false);

/// FNV-1a of the problem description and the model fingerprint: the ledger's identity.
std::string problem_fingerprint(const CalibrationProblem& problem, const CubeModel& model);

}  // namespace gradem::cal
