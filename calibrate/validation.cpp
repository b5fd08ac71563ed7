#include "calibrate/validation.hpp"

#include <stdexcept>

#include "calibrate/parameters.hpp"
#include "calibrate/study/study_models.hpp"
#include "common/number_format.hpp"

namespace gradem::cal {

ValidatedModel::ValidatedModel(std::unique_ptr<CubeModel> fit, std::size_t sands) : fit_(std::move(fit)), sands_(sands) {}

ValidatedModel::ValidatedModel(std::unique_ptr<CubeModel> fit, std::unique_ptr<CubeModel> validation, std::size_t sands,
                               std::vector<std::uint64_t> validation_seeds)
    : ValidatedModel(std::move(fit), sands) {
    add(SpecimenSet::validation, std::move(validation), std::move(validation_seeds));
}

void ValidatedModel::add(SpecimenSet set, std::unique_ptr<CubeModel> model, std::vector<std::uint64_t> seeds) {
    if (has(set)) throw std::logic_error("ValidatedModel::add: the specimen set is there already");
    extras_.push_back({set, std::move(model), std::move(seeds), sands_ * (extras_.size() + 1)});
}

const ValidatedModel::Extra* ValidatedModel::find(SpecimenSet set) const {
    for (const Extra& e : extras_)
        if (e.set == set) return &e;
    return nullptr;
}

const CubeModel& ValidatedModel::model(SpecimenSet set) const {
    const Extra* e = find(set);
    if (!e) throw std::logic_error("ValidatedModel: no such specimen set");
    return *e->model;
}

std::size_t ValidatedModel::offset(SpecimenSet set) const {
    const Extra* e = find(set);
    if (!e) throw std::logic_error("ValidatedModel: no such specimen set");
    return e->offset;
}

namespace {

const char* set_name(SpecimenSet set) { return set == SpecimenSet::scale_up ? "scale-up " : "validation "; }

}  // namespace

void ValidatedModel::prepare(const PackingSeeds& seeds, int workers,
                             const std::function<void(const std::string&)>& log) {
    fit_->prepare(seeds, workers, log);
    for (Extra& e : extras_)
        e.model->prepare(e.seeds, workers, log ? [&log, &e](const std::string& s) { log(set_name(e.set) + s); }
                                               : std::function<void(const std::string&)>{});
}

void ValidatedModel::load_prepared(const PackingSeeds& seeds) {
    fit_->load_prepared(seeds);
    for (Extra& e : extras_) e.model->load_prepared(e.seeds);
}

RunOutcome ValidatedModel::run(const RunRequest& request, double timeout_s) const {
    if (request.sand < sands_) return fit_->run(request, timeout_s);
    for (const Extra& e : extras_)
        if (request.sand >= e.offset && request.sand < e.offset + sands_) {
            RunRequest local = request;
            local.sand -= e.offset;
            return e.model->run(local, timeout_s);
        }
    throw std::logic_error("ValidatedModel::run: sand " + std::to_string(request.sand) + " is in no specimen set");
}

SetEvaluator::SetEvaluator(const CalibrationProblem& on_set, const ValidatedModel& model, SpecimenSet set,
                           RunExecutor& executor, Ledger& ledger)
    : problem(on_set), space(problem.parameters, problem.base.material), offset(model.offset(set)),
      shifted(executor, offset), evaluator(problem, space, shifted, ledger, model.model(set)) {}

Evaluation evaluate_on_set(const CalibrationProblem& on_set, const ValidatedModel& model, SpecimenSet set, RunExecutor& executor,
                           Ledger& ledger, const std::vector<double>& point, const std::vector<std::size_t>& sands,
                           const std::string& label, int& runs, int& from_ledger, StageCost& cost) {
    SetEvaluator on(on_set, model, set, executor, ledger);
    Evaluation e = on.evaluator.evaluate(point, sands, label);
    runs = on.evaluator.runs_used();
    from_ledger = on.evaluator.runs_from_ledger();
    cost = on.evaluator.cost();
    return e;
}

StageValidation validate_point(const CalibrationProblem& problem, const ValidatedModel& model, RunExecutor& executor,
                               Ledger& ledger, const std::vector<double>& point, const std::vector<std::size_t>& sands,
                               const std::function<void(const std::string&)>& log) {
    PointValidation validation(problem, model, executor, ledger);
    const QueuedRuns runs = validation.queue(point, sands);
    run_together(executor, {runs}, problem.timeout_s);
    return validation.collect(log);
}

PointValidation::PointValidation(const CalibrationProblem& problem, const ValidatedModel& model, RunExecutor& executor,
                                 Ledger& ledger)
    : set_(validation_problem(problem), model, SpecimenSet::validation, executor, ledger) {}

QueuedRuns PointValidation::queue(const std::vector<double>& point, const std::vector<std::size_t>& sands) {
    if (point.empty()) return {};
    queued_ = true;
    return {&set_.evaluator, set_.evaluator.queue({point}, sands, "validation"), set_.offset, {}};
}

StageValidation PointValidation::collect(const std::function<void(const std::string&)>& log) {
    StageValidation v;
    if (!queued_) {
        v.note = "not run: the fit has no result";
        return v;
    }
    queued_ = false;
    v.evaluation = set_.evaluator.collect().front();
    v.runs = set_.evaluator.runs_used();
    v.from_ledger = set_.evaluator.runs_from_ledger();
    v.cost = set_.evaluator.cost();
    if (log)
        log("validation on " + std::to_string(set_.problem.seeds.size()) + (set_.problem.seeds.size() == 1 ? " unseen seed" : " unseen seeds") +
            ", edge " + common::format_significant(set_.problem.base.specimen.genesis.edge * 1e3, 4) + " mm: " + std::to_string(v.runs) +
            " runs (" + std::to_string(v.from_ledger) + " from the ledger)" +
            (v.evaluation.failed ? ", failed: " + v.evaluation.failure : ""));
    return v;
}

}  // namespace gradem::cal
