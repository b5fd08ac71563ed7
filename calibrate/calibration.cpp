#include "calibrate/calibration.hpp"

#include <chrono>
#include <cmath>
#include <stdexcept>

#include "calibrate/execution/ledger.hpp"
#include "calibrate/plan.hpp"
#include "common/hash.hpp"

namespace gradem::cal {
namespace {

/// Whether the tension tests at each stage's result wait for its validation, to run in one batch
/// with it: a worker that the result's few tension tests leave idle runs validation runs. Not
/// in study mode, whose prediction runs between the fit and the validation.
bool tension_joins_validation(const CalibrationProblem& problem) {
    return problem.tension_at_result_only() && problem.validation.enabled() && problem.mode != Mode::study;
}

/// The solver's path; with a tension target that is reported only, the path runs compression
/// alone (σt cannot move it) with the result's tension runs held back from the budget, and the
/// tension tests run once, at the best point (its compression runs come from the ledger): here,
/// or with the validation (`tension_later`: the runs stay held back until then).
SolveResult solve_then_tension(const CalibrationProblem& problem, SolveContext& ctx, Evaluator& evaluator,
                               const std::vector<double>& start, bool tension_later) {
    if (!problem.tension_at_result_only()) return solve(ctx, start);
    const int tension_runs = problem.tension_runs_per_test(ctx.sands);
    const int reserved = evaluator.reserve();
    evaluator.set_tension_companion(false);
    evaluator.set_reserve(reserved + tension_runs);
    SolveResult solution = solve(ctx, start);
    evaluator.set_tension_companion(true);
    if (tension_later && !solution.best.empty()) return solution;
    evaluator.set_reserve(reserved);
    if (solution.best.empty()) return solution;
    if (ctx.log) ctx.log("tension tests at the result");
    solution.best_eval = evaluator.evaluate(solution.best, ctx.sands, "tension at the result");
    return solution;
}

/// Once the result's evaluation is complete (its tension tests too): its noise floor and the
/// parameters' uncertainty.
void finish_stage(CalibrationStage& stage, const CalibrationProblem& problem, const ParameterSpace& space,
                  Evaluator& evaluator, const std::function<void(const std::string&)>& log) {
    if (stage.solution.best.empty()) {
        stage.uncertainty.note = "not computed: no evaluation";
        return;
    }
    measure_noise(stage.solution.best_eval, stage.noise_floor);
    SolveContext ctx{problem, space, evaluator, stage.fitted, log};
    // σt of weight 0 is no residual, so the difference points run compression alone too.
    evaluator.set_tension_companion(!problem.tension_at_result_only());
    stage.uncertainty = estimate_uncertainty(ctx, stage.solution);
    evaluator.set_tension_companion(true);
}

CalibrationStage solve_stage(const CalibrationProblem& problem, const ParameterSpace& space, Evaluator& evaluator,
                             std::string label, std::vector<std::size_t> fitted,
                             const std::function<void(const std::string&)>& log) {
    CalibrationStage stage;
    stage.label = std::move(label);
    stage.fitted = fitted;
    SolveContext ctx{problem, space, evaluator, fitted, log};
    if (log) log(stage.label + ": solving with " + to_string(problem.solver.method));
    const bool tension_later = tension_joins_validation(problem);
    stage.solution = solve_then_tension(problem, ctx, evaluator, space.start(), tension_later);
    if (!tension_later || stage.solution.best.empty()) finish_stage(stage, problem, space, evaluator, log);
    return stage;
}

/// The stage's validation, its longest runs first; when its tension tests at the result waited
/// for it (tension_joins_validation), they join its batch, and the stage is finished once they
/// are in.
void validate_stage(CalibrationStage& st, const CalibrationProblem& problem, const ParameterSpace& space,
                    const ValidatedModel& sets, RunExecutor& executor, Ledger& ledger, Evaluator& evaluator,
                    const std::function<void(const std::string&)>& log) {
    const bool with_tension = tension_joins_validation(problem) && !st.solution.best.empty();
    PointValidation validation(problem, sets, executor, ledger);
    std::vector<QueuedRuns> batch{validation.queue(st.result(), st.sands())};
    if (with_tension) {
        evaluator.set_reserve(evaluator.reserve() - problem.tension_runs_per_test(st.fitted));
        if (log) log("tension tests at the result, with the validation");
        batch.push_back({&evaluator, evaluator.queue({st.solution.best}, st.fitted, "tension at the result"), 0, {}});
    }
    // The runs' expected times, to start the longest first: a sand's mean fitted run so far ×
    // the set's grains × steps, a tension test about half a compression test (its automatic rate
    // puts 100 wave transits before its peak, compression's 200).
    constexpr double kTensionRunShare = 0.5;
    const double validation_weight = run_weight_at_edge(problem, problem.validation.edge);
    for (QueuedRuns& runs : batch)
        for (const RunRequest& r : runs.requests)
            runs.expected_seconds.push_back(evaluator.sand_mean_run_seconds(r.sand) *
                                            (runs.evaluator == &evaluator ? 1.0 : validation_weight) *
                                            (r.test == CubeTest::tension ? kTensionRunShare : 1.0));
    run_together(executor, batch, problem.timeout_s);
    st.validation = validation.collect(log);
    if (!with_tension) return;
    st.solution.best_eval = evaluator.collect().front();
    finish_stage(st, problem, space, evaluator, log);
}

}  // namespace

const SandOutcome* CalibrationStage::outcome(std::size_t sand) const {
    for (const auto* e : {&solution.best_eval, &prediction})
        for (const SandOutcome& s : e->sands)
            if (s.sand == sand) return &s;
    return nullptr;
}

const SandOutcome* CalibrationStage::scaled_outcome(std::size_t sand) const {
    for (const SandOutcome& s : scale_up.prediction.sands)
        if (s.sand == sand) return &s;
    return nullptr;
}

const SandOutcome* CalibrationStage::validation_outcome(std::size_t sand) const {
    for (const SandOutcome& s : validation.evaluation.sands)
        if (s.sand == sand) return &s;
    return nullptr;
}

std::vector<std::size_t> CalibrationStage::sands() const {
    std::vector<std::size_t> all = fitted;
    all.insert(all.end(), predicted.begin(), predicted.end());
    return all;
}

const Evaluation* CalibrationStage::evaluation_of(std::size_t sand) const {
    for (const auto* e : {&solution.best_eval, &prediction})
        for (const SandOutcome& s : e->sands)
            if (s.sand == sand) return e;
    return nullptr;
}

namespace {

std::unique_ptr<CubeModel> make_specimen_model(const CalibrationProblem& problem, bool tension) {
    if (problem.model == RunModel::analytic) return make_analytic_model(problem.sands.size(), 0.003, 0.0);
    return make_dem_model(problem.base, problem.sands, tension || problem.tension.fitted());
}

}  // namespace

std::unique_ptr<CubeModel> make_model(const CalibrationProblem& problem, bool tension) {
    if (!problem.scale_up.enabled() && !problem.validation.enabled()) return make_specimen_model(problem, tension);
    auto model = std::make_unique<ValidatedModel>(make_specimen_model(problem, tension), problem.sands.size());
    if (problem.scale_up.enabled())
        model->add(SpecimenSet::scale_up, make_specimen_model(scale_up_problem(problem), tension), problem.scale_up.seeds);
    if (problem.validation.enabled())
        model->add(SpecimenSet::validation, make_specimen_model(validation_problem(problem), tension), problem.validation.seeds);
    return model;
}

std::string problem_fingerprint(const CalibrationProblem& problem, const CubeModel& model) {
    return common::fnv1a_hex(problem.describe() + "\n" + model.fingerprint());
}

CalibrationResult run_calibration(const CalibrationProblem& problem, CubeModel& model,
                                  const std::function<void(const std::string&)>& log_line,
                                  const std::function<void(const Progress&)>& progress) {
    ThreadExecutor threads(model, problem.workers);
    return run_calibration(problem, model, threads, log_line, progress);
}

CalibrationResult run_calibration(const CalibrationProblem& problem, const CubeModel& model, RunExecutor& executor,
                                  const std::function<void(const std::string&)>& log_line,
                                  const std::function<void(const Progress&)>& progress) {
    const auto start = std::chrono::steady_clock::now();
    CalibrationResult result;
    auto log = [&](const std::string& s) {
        result.log.push_back(s);
        if (log_line) log_line(s);
    };
    // 1. The ledger first: a mismatch must stop us before any work.
    result.fingerprint = problem_fingerprint(problem, model);
    Ledger ledger(problem.ledger, result.fingerprint, problem.describe() + model.fingerprint() + "\n");
    if (const auto rows = ledger.size()) log("ledger " + problem.ledger.string() + ": " + std::to_string(rows) + " runs recorded, resuming");
    // 2. Packings (made once, cached), all sands and seeds, wherever the runs will go.
    log("runs on " + executor.describe());
    executor.prepare(problem.packing_seeds(), log);
    const ParameterSpace space(problem.parameters, problem.base.material);
    Evaluator evaluator(problem, space, executor, ledger, model, progress);
    // 3. The mode's solves.
    const std::vector<std::size_t> all = problem.sand_indices();
    if (problem.mode == Mode::joint) {
        result.stages.push_back(solve_stage(problem, space, evaluator, "joint", all, log));
    } else if (problem.mode == Mode::per_sand) {
        for (std::size_t s : all) result.stages.push_back(solve_stage(problem, space, evaluator, problem.sands[s], {s}, log));
    } else {
        std::size_t on = 0;
        while (problem.sands[on] != problem.calibrate_on) ++on;
        std::vector<std::size_t> others;
        for (std::size_t s : all)
            if (s != on) others.push_back(s);
        evaluator.set_reserve(problem.runs_per_test(others));
        CalibrationStage stage = solve_stage(problem, space, evaluator, "calibrated on " + problem.calibrate_on, {on}, log);
        evaluator.set_reserve(0);
        for (std::size_t s : all)
            if (s != on) stage.predicted.push_back(s);
        if (!stage.solution.best.empty()) {
            try {
                stage.prediction = evaluator.evaluate(stage.solution.best, stage.predicted, "prediction");
            } catch (const BudgetExhausted& e) {
                log(std::string("prediction not run: ") + e.what());
            }
        }
        result.stages.push_back(std::move(stage));
    }
    // 4. The scale-up specimens: each stage's scales set where the specimen is larger; then the
    //    validation specimens: each stage's result where the fit never looked.
    if (problem.scale_up.enabled() || problem.validation.enabled()) {
        const auto* sets = dynamic_cast<const ValidatedModel*>(&model);
        if (!sets) throw std::logic_error("run_calibration: a problem with [scale_up] or [validation] needs make_model()'s ValidatedModel");
        for (CalibrationStage& st : result.stages) {
            if (problem.scale_up.enabled()) {
                st.scale_up = scale_up_point(problem, *sets, executor, ledger, st.solution.best, st.fitted, log);
                result.scale_up_runs += st.scale_up.runs;
                result.scale_up_cost += st.scale_up.cost;
            }
            if (problem.validation.enabled()) {
                validate_stage(st, problem, space, *sets, executor, ledger, evaluator, log);
                result.validation_runs += st.validation.runs;
                result.validation_cost += st.validation.cost;
            }
        }
    }
    result.history = evaluator.history();
    result.runs_used = evaluator.runs_used();
    result.runs_executed = evaluator.runs_executed();
    result.runs_from_ledger = evaluator.runs_from_ledger();
    result.runs_failed = evaluator.runs_failed();
    result.fit_cost = evaluator.cost();
    result.wall_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    return result;
}

}  // namespace gradem::cal
