#pragma once
// A study on the run executors (threads or MPI ranks). An MPI job holds one CubeModel per
// rank, but a study's cases may differ in specimen (the cube edge or the smallest kept grain
// of a size sweep), each with its own model. StudyModels is the
// models of every case as one CubeModel: case k's sand s is its sand offset(k) + s, so the
// executor's requests say which case they belong to, and every rank makes the same list
// from the study file (study_problems). CaseExecutor gives one case's Evaluator that
// numbering on a shared executor. Runs, ledger keys and results are those of the thread
// run: the same case model runs the same request, only elsewhere.
#include <cstddef>
#include <memory>
#include <optional>
#include <vector>

#include "calibrate/problem.hpp"
#include "calibrate/execution/run_executor.hpp"
#include "calibrate/study/study_config.hpp"

namespace gradem::cal {

/// A case's problem as the study runs it: the study's seeds, workers and per-run time limit,
/// and a budget that never stops it (a study runs what it asks for).
CalibrationProblem as_study_problem(CalibrationProblem problem, const StudyConfig& config);

/// Every distinct problem the study's compression cases run, as as_study_problem() makes them,
/// in the order the study runs them (StudyKindSpec::problems; none for a kind without). Throws
/// InputError as run_study would (missing calibration, a bad sweep value).
std::vector<CalibrationProblem> study_problems(const StudyConfig& config);

class StudyModels final : public CubeModel {
public:
    /// Makes each problem's model (make_model); nothing is prepared yet.
    explicit StudyModels(std::vector<CalibrationProblem> problems);

    [[nodiscard]] std::size_t size() const { return problems_.size(); }
    /// The case whose problem runs the same specimen and test as `problem` (nullopt: none).
    [[nodiscard]] std::optional<std::size_t> find(const CalibrationProblem& problem) const;
    [[nodiscard]] const CubeModel& model(std::size_t k) const { return *models_.at(k); }
    /// The composite sand number of case k's first sand.
    [[nodiscard]] std::size_t offset(std::size_t k) const { return offsets_.at(k); }

    /// Prepares (loads) every case's model for the seeds.
    void prepare(const PackingSeeds& seeds, int workers, const std::function<void(const std::string&)>& log) override;
    void load_prepared(const PackingSeeds& seeds) override;
    /// Runs request.sand's case model with the case's own sand number.
    [[nodiscard]] RunOutcome run(const RunRequest& request, double timeout_s) const override;
    /// Every case model's fingerprint, in order.
    [[nodiscard]] std::string fingerprint() const override;
    /// Every case model's run fingerprint of `test`, in order (the Evaluators key with the case model's own).
    [[nodiscard]] std::string run_fingerprint(CubeTest test) const override;

private:
    std::vector<CalibrationProblem> problems_;
    std::vector<std::unique_ptr<CubeModel>> models_;
    std::vector<std::size_t> offsets_;
};

/// One case's runs on an executor of StudyModels: each request's sand is shifted by the
/// case's offset. The StudyModels were prepared as a whole, so prepare() does nothing.
class CaseExecutor final : public RunExecutor {
public:
    CaseExecutor(RunExecutor& all_cases, std::size_t offset) : all_(all_cases), offset_(offset) {}
    void prepare(const PackingSeeds&, const Log&) override {}
    void run(const std::vector<RunRequest>& requests, double timeout_s, const RunDone& done) override;
    [[nodiscard]] int slots() const override { return all_.slots(); }
    [[nodiscard]] std::string describe() const override { return all_.describe(); }

private:
    RunExecutor& all_;
    std::size_t offset_;
};

/// Where run_study sends its runs instead of threads of its own: `executor` runs requests of
/// `models` (prepared for the study's seeds).
struct StudyExecution {
    StudyModels& models;
    RunExecutor& executor;
};

}  // namespace gradem::cal
