#pragma once
// The validation of a calibration ([validation] edge_mm, seeds; docs/calibration.md
// "Validation"): each stage's result run on specimens the fit never saw - cubes of another edge
// and other packing seeds - with the same tests (compression, and direct tension when the
// problem fits it). A calibration that holds only on its own specimens is overfitted to their
// packing noise or to their size; the summary leads with these errors.
//
// ValidatedModel is the fit's model and those of its other specimen sets (scale-up,
// validation) as one CubeModel, as StudyModels is for a study's cases: set k's sand s is the
// composite's sand (k + 1) x (fitted sands) + s, so an MPI job's worker ranks, which build
// make_model(problem), run those requests too.
#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "calibrate/cube_model.hpp"
#include "calibrate/evaluator.hpp"
#include "calibrate/execution/ledger.hpp"
#include "calibrate/parameters.hpp"
#include "calibrate/problem.hpp"
#include "calibrate/stage_cost.hpp"
#include "calibrate/execution/run_executor.hpp"
#include "calibrate/study/study_models.hpp"

namespace gradem::cal {

/// The specimen sets besides the fitted ones.
enum class SpecimenSet { scale_up, validation };

class ValidatedModel final : public CubeModel {
public:
    /// The fit's model for `sands` sands; add() the other sets.
    ValidatedModel(std::unique_ptr<CubeModel> fit, std::size_t sands);
    /// The fit and its validation set.
    ValidatedModel(std::unique_ptr<CubeModel> fit, std::unique_ptr<CubeModel> validation, std::size_t sands,
                   std::vector<std::uint64_t> validation_seeds);
    void add(SpecimenSet set, std::unique_ptr<CubeModel> model, std::vector<std::uint64_t> seeds);

    [[nodiscard]] const CubeModel& fit() const { return *fit_; }
    [[nodiscard]] bool has(SpecimenSet set) const { return find(set) != nullptr; }
    [[nodiscard]] const CubeModel& model(SpecimenSet set) const;
    /// The composite sand number of the set's first sand.
    [[nodiscard]] std::size_t offset(SpecimenSet set) const;
    [[nodiscard]] const CubeModel& validation() const { return model(SpecimenSet::validation); }

    /// The fit's packings for `seeds`, each set's for its own seeds.
    void prepare(const PackingSeeds& seeds, int workers, const std::function<void(const std::string&)>& log) override;
    void load_prepared(const PackingSeeds& seeds) override;
    [[nodiscard]] RunOutcome run(const RunRequest& request, double timeout_s) const override;
    /// The fit's: the other specimen sets are not part of the problem's identity.
    [[nodiscard]] std::string fingerprint() const override { return fit_->fingerprint(); }
    [[nodiscard]] std::string run_fingerprint(CubeTest test) const override { return fit_->run_fingerprint(test); }

private:
    struct Extra {
        SpecimenSet set;
        std::unique_ptr<CubeModel> model;
        std::vector<std::uint64_t> seeds;
        std::size_t offset;
    };
    [[nodiscard]] const Extra* find(SpecimenSet set) const;
    std::unique_ptr<CubeModel> fit_;
    std::size_t sands_;
    std::vector<Extra> extras_;
};

/// The evaluator of `on_set` (the problem on set `set`'s specimens) over that set of `model`,
/// its runs through `executor` (which runs `model`'s requests, so the sands are shifted into the
/// set), recording into `ledger`. Not copyable: the evaluator refers to the members before it.
struct SetEvaluator {
    SetEvaluator(const CalibrationProblem& on_set, const ValidatedModel& model, SpecimenSet set, RunExecutor& executor,
                 Ledger& ledger);
    SetEvaluator(const SetEvaluator&) = delete;
    SetEvaluator& operator=(const SetEvaluator&) = delete;
    CalibrationProblem problem;
    ParameterSpace space;
    std::size_t offset;     ///< the composite sand number of the set's first sand
    CaseExecutor shifted;   ///< `executor` with the set's sands
    Evaluator evaluator;
};

/// `point` on set `set` of `model` for `sands` through `executor` (which runs `model`'s
/// requests), recording into `ledger`, as `on_set` (the problem on that set's specimens) defines
/// its runs; `runs`, `from_ledger` and `cost` receive its counts and cost.
Evaluation evaluate_on_set(const CalibrationProblem& on_set, const ValidatedModel& model, SpecimenSet set, RunExecutor& executor,
                           Ledger& ledger, const std::vector<double>& point, const std::vector<std::size_t>& sands,
                           const std::string& label, int& runs, int& from_ledger, StageCost& cost);

/// One stage's validation: its result on the validation specimens of `sands`.
struct StageValidation {
    Evaluation evaluation;            ///< empty sands: not run (no result, or it failed to run)
    int runs = 0, from_ledger = 0;    ///< runs it took, and how many the ledger served
    StageCost cost;                   ///< what its runs cost
    std::string note;                 ///< why it was not run, if it was not
};

/// Runs `point` on the validation specimens of `sands` through `executor` (which runs `model`'s
/// requests), recording into `ledger`; `log` gets one milestone line.
StageValidation validate_point(const CalibrationProblem& problem, const ValidatedModel& model, RunExecutor& executor,
                               Ledger& ledger, const std::vector<double>& point, const std::vector<std::size_t>& sands,
                               const std::function<void(const std::string&)>& log);

/// validate_point in two halves around a batch it may share with other runs (run_together):
/// queue() its runs, run them, collect() the StageValidation.
class PointValidation {
public:
    /// The validation of `problem` on `model`'s validation set; `executor` runs `model`'s requests.
    PointValidation(const CalibrationProblem& problem, const ValidatedModel& model, RunExecutor& executor, Ledger& ledger);
    PointValidation(const PointValidation&) = delete;
    PointValidation& operator=(const PointValidation&) = delete;
    /// The runs of `point` on the validation specimens of `sands` (none for an empty point: the
    /// fit has no result), their sands placed in `model`'s validation set.
    QueuedRuns queue(const std::vector<double>& point, const std::vector<std::size_t>& sands);
    /// The validation once the queued runs have run; `log` gets one milestone line.
    StageValidation collect(const std::function<void(const std::string&)>& log);

private:
    SetEvaluator set_;  ///< the validation set's (run_together shifts the sands itself)
    bool queued_ = false;
};

}  // namespace gradem::cal
