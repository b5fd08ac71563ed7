#pragma once
// Evaluations: a parameter point run on every packing seed of the requested sands (common random
// numbers: the same packings for every point), served from the ledger when the identical run is
// there, otherwise handed to the run executor (threads or MPI ranks) and recorded at once. The budget counts distinct
// runs of this calibration, from the ledger or not, so a resumed calibration takes the same path.
// A problem that fits the direct-tension strength adds, per compression run, the tension test of
// the same packing and material (its own ledger key): both go to the executor in one batch.
#include <chrono>
#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <set>
#include <stdexcept>
#include <string>
#include <vector>

#include "calibrate/cube_model.hpp"
#include "calibrate/execution/ledger.hpp"
#include "calibrate/parameters.hpp"
#include "calibrate/problem.hpp"
#include "calibrate/stage_cost.hpp"
#include "calibrate/execution/run_executor.hpp"

namespace gradem::cal {

/// A run's value of a target quantity: chord modulus [Pa], peak stress [Pa] (for a tension run
/// the tensile strength), strain at peak [-].
double outcome_value(const RunOutcome& r, Quantity q);

/// A sand's outputs over the seeds: mean and sample standard deviation, by Quantity (the
/// tension slot holds the tension tests' peak σt [Pa], NaN when none was run).
struct SandOutcome {
    std::size_t sand = 0;
    double mean[kQuantityCount] = {0, 0, 0, 0}, std[kQuantityCount] = {0, 0, 0, 0};
    double poisson = 0.0;
    int ok = 0, failed = 0;
    int tension_ok = 0;   ///< successful tension tests (their failures count in `failed`)
    std::string failure;  ///< the first failing run's status and reason
    [[nodiscard]] double value(Quantity q) const { return mean[static_cast<int>(q)]; }
    /// Runs behind the mean of q (for standard errors).
    [[nodiscard]] int count(Quantity q) const { return q == Quantity::tension ? tension_ok : ok; }
};

struct Evaluation {
    int index = 0;                     ///< 1, 2, ... in the order requested
    std::vector<double> values;        ///< free parameters, config units
    std::vector<SandOutcome> sands;    ///< one per evaluated sand
    std::vector<RunOutcome> runs;      ///< the primary test's, sand-major, then seed
    std::vector<RunOutcome> tension_runs;  ///< the companion tension tests, same order, of the seeds that run one
                                           ///< (CalibrationProblem::runs_tension_on; empty: none)
    bool failed = false;
    std::string failure;
    std::string label;                 ///< what the solver asked for ("start", "rescaled", "fd", ...)
    int runs_used = 0;                 ///< budget used once this evaluation was done
    double seconds = 0.0;              ///< wall time of the calibration when it was done [s]
};

class BudgetExhausted : public std::runtime_error {
public:
    using std::runtime_error::runtime_error;
};

/// What the progress line shows after each run.
struct Progress {
    int runs_used = 0, max_runs = 0, from_ledger = 0, evaluations = 0;
    double elapsed_s = 0.0, mean_run_s = 0.0, best_objective = 0.0;
    std::vector<double> sand_mean_run_s;  ///< per problem sand: the mean of its runs so far [s] (0: none yet)
    int workers = 1;
};

class Evaluator {
public:
    /// The runs on `executor`; `model` is the one it runs (its run fingerprints key the ledger).
    /// `primary`: the test whose outcomes fill an Evaluation's runs and the three compression
    /// quantities' slots (the study runs tension alone so); with compression and a problem that
    /// fits tension, every run has its tension companion.
    Evaluator(const CalibrationProblem& problem, const ParameterSpace& space, RunExecutor& executor, Ledger& ledger,
              const CubeModel& model, std::function<void(const Progress&)> progress = {},
              CubeTest primary = CubeTest::compression);
    /// The runs on problem.workers threads of this process (`model` already prepared).
    Evaluator(const CalibrationProblem& problem, const ParameterSpace& space, const CubeModel& model, Ledger& ledger,
              std::function<void(const Progress&)> progress = {}, CubeTest primary = CubeTest::compression);

    /// Evaluates every point on `sands` (indices into problem.sands); all their runs go to the
    /// executor together (a batch of 20 finite-difference points fills 20 workers). Throws BudgetExhausted (before running anything) when the new
    /// distinct runs would exceed solver.max_runs.
    std::vector<Evaluation> evaluate(const std::vector<std::vector<double>>& points, const std::vector<std::size_t>& sands,
                                     const std::string& label);
    Evaluation evaluate(const std::vector<double>& point, const std::vector<std::size_t>& sands, const std::string& label) {
        return evaluate(std::vector<std::vector<double>>{point}, sands, label).front();
    }

    /// evaluate() in three steps, so that the runs of several evaluators share one executor
    /// batch (run_together): queue() checks the budget (BudgetExhausted before anything runs),
    /// serves what the ledger has and returns the runs left to make, in order; record() takes
    /// the k-th's outcome when it ends; collect() makes the evaluations. One queue at a time.
    std::vector<RunRequest> queue(const std::vector<std::vector<double>>& points, const std::vector<std::size_t>& sands,
                                  const std::string& label);
    void record(std::size_t k, const RunOutcome& outcome, const RunPlace& place);
    std::vector<Evaluation> collect();

    /// Distinct runs that evaluating `points` would add to the budget.
    [[nodiscard]] int runs_needed(const std::vector<std::vector<double>>& points, const std::vector<std::size_t>& sands) const;
    [[nodiscard]] int runs_used() const { return static_cast<int>(used_.size()); }
    [[nodiscard]] int runs_remaining() const { return problem_.solver.max_runs - reserve_ - runs_used(); }
    /// Whether compression runs have their tension companion (a problem that fits tension:
    /// on by default; off while the solver runs when the tension target is reported only).
    void set_tension_companion(bool on);
    /// Runs kept back from the solvers (e.g. for the study's prediction); 0 releases them.
    void set_reserve(int runs) { reserve_ = runs; }
    [[nodiscard]] int reserve() const { return reserve_; }
    [[nodiscard]] int runs_executed() const { return executed_; }
    [[nodiscard]] int runs_from_ledger() const { return served_; }
    [[nodiscard]] int runs_failed() const { return failed_; }
    /// What the runs made here cost, and what the ledger served (StageCost).
    [[nodiscard]] const StageCost& cost() const { return cost_; }
    [[nodiscard]] const std::vector<Evaluation>& history() const { return history_; }
    void note_best(double objective) { best_objective_ = objective; }
    /// The mean wall time of the runs of problem sand `sand` made here so far [s] (0: none yet).
    [[nodiscard]] double sand_mean_run_seconds(std::size_t sand) const;
    [[nodiscard]] double seconds() const;

private:
    /// Whether `seed` runs `test`: the primary test always, the tension companion on the
    /// problem's tension seeds (CalibrationProblem::runs_tension_on).
    [[nodiscard]] bool runs_test(CubeTest test, std::uint64_t seed) const;
    /// The tests each (point, sand, seed) runs: the primary one, then its tension companion.
    [[nodiscard]] const std::vector<CubeTest>& tests() const { return tests_; }
    std::string run_key(const exp::MaterialParams& m, std::size_t sand, std::uint64_t seed, CubeTest test) const;
    /// The ledger's outcome of `key`, unless it is a timeout shorter than problem.timeout_s.
    std::optional<RunOutcome> served_outcome(const std::string& key) const;
    std::string parameters_json(const std::vector<double>& values) const;
    SandOutcome summarise(std::size_t sand, const std::vector<RunOutcome>& runs, const std::vector<RunOutcome>& tension_runs) const;
    void report(int evaluations);
    // The steps of evaluate().
    /// One run of one point: (point, sand, seed, test), its key and outcome.
    struct Job {
        std::size_t point, sand;
        std::uint64_t seed;
        CubeTest test;
        exp::MaterialParams material;
        std::string key;
        RunOutcome outcome;
        bool done = false;
    };
    /// A queue()'s evaluation until collect(): its jobs, and the ones the executor runs (each
    /// distinct key once, in the order of the requests).
    struct Pending {
        std::vector<std::vector<double>> points;
        std::vector<std::size_t> sands;
        std::string label;
        std::vector<Job> jobs;
        std::vector<std::size_t> queue;
    };
    std::vector<Job> jobs_of(const std::vector<std::vector<double>>& points, const std::vector<std::size_t>& sands) const;
    std::vector<std::size_t> serve_from_ledger(std::vector<Job>& jobs);
    Evaluation evaluation_of(const std::vector<Job>& jobs, std::size_t point, const std::vector<double>& values,
                             const std::vector<std::size_t>& sands, const std::string& label);

    const CalibrationProblem& problem_;
    const ParameterSpace& space_;
    std::unique_ptr<RunExecutor> own_executor_;  ///< the thread executor of the second constructor
    RunExecutor& executor_;
    Ledger& ledger_;
    CubeTest primary_;
    std::vector<CubeTest> tests_;  ///< see tests()
    std::string fingerprint_[2];  ///< run fingerprints by CubeTest (the tension one only when it runs)
    std::function<void(const Progress&)> progress_;
    std::set<std::string> used_;
    int executed_ = 0, served_ = 0, failed_ = 0, reserve_ = 0;
    StageCost cost_;
    double run_seconds_ = 0.0, best_objective_ = 0.0;
    std::vector<double> sand_run_seconds_;  ///< per problem sand: Σ wall seconds of its runs here
    std::vector<int> sand_runs_;            ///< per problem sand: its runs here
    std::vector<Evaluation> history_;
    std::optional<Pending> pending_;  ///< between queue() and collect()
    std::chrono::steady_clock::time_point start_;
};

/// The runs an evaluator has queued (Evaluator::queue), and where its specimens sit in the
/// executor's model: its requests' sands are shifted by `sand_offset` (a ValidatedModel's set).
struct QueuedRuns {
    Evaluator* evaluator = nullptr;
    std::vector<RunRequest> requests;
    std::size_t sand_offset = 0;
    /// Each request's expected wall time [s], or empty: unknown (run after the others).
    std::vector<double> expected_seconds;
};

/// The queued runs of several evaluators as one batch on `executor`, the longest expected first
/// (the executor starts runs in order: a long run started last keeps the others waiting), else
/// in the order given; each outcome recorded by the evaluator that queued it; the evaluators then
/// collect() their evaluations. A worker that would sit idle at the end of one evaluator's
/// batch runs another's instead.
void run_together(RunExecutor& executor, const std::vector<QueuedRuns>& batches, double timeout_s);

}  // namespace gradem::cal
