#include "calibrate/validation.hpp"

#include <stdexcept>

#include "calibrate/parameters.hpp"
#include "calibrate/study_models.hpp"

namespace gradem::cal {

ValidatedModel::ValidatedModel(std::unique_ptr<CubeModel> fit, std::unique_ptr<CubeModel> validation, std::size_t sands,
                               std::vector<std::uint64_t> validation_seeds)
    : fit_(std::move(fit)), validation_(std::move(validation)), sands_(sands), seeds_(std::move(validation_seeds)) {}

void ValidatedModel::prepare(const std::vector<std::uint64_t>& seeds, int workers,
                             const std::function<void(const std::string&)>& log) {
    fit_->prepare(seeds, workers, log);
    validation_->prepare(seeds_, workers, log ? [&log](const std::string& s) { log("validation " + s); }
                                              : std::function<void(const std::string&)>{});
}

void ValidatedModel::load_prepared(const std::vector<std::uint64_t>& seeds) {
    fit_->load_prepared(seeds);
    validation_->load_prepared(seeds_);
}

RunOutcome ValidatedModel::run(const RunRequest& request, double timeout_s) const {
    if (request.sand < sands_) return fit_->run(request, timeout_s);
    RunRequest local = request;
    local.sand -= sands_;
    return validation_->run(local, timeout_s);
}

StageValidation validate_point(const CalibrationProblem& problem, const ValidatedModel& model, RunExecutor& executor,
                               Ledger& ledger, const std::vector<double>& point, const std::vector<std::size_t>& sands,
                               const std::function<void(const std::string&)>& log) {
    StageValidation v;
    if (point.empty()) {
        v.note = "not run: the fit has no result";
        return v;
    }
    const CalibrationProblem vp = validation_problem(problem);
    const ParameterSpace space(vp.parameters, vp.base.material);
    CaseExecutor shifted(executor, model.offset());
    Evaluator evaluator(vp, space, shifted, ledger, model.validation());
    v.evaluation = evaluator.evaluate(point, sands, "validation");
    v.runs = evaluator.runs_used();
    v.from_ledger = evaluator.runs_from_ledger();
    if (log)
        log("validation on " + std::to_string(vp.seeds.size()) + " unseen seeds, edge " + std::to_string(vp.base.specimen.genesis.edge * 1e3) +
            " mm: " + std::to_string(v.runs) + " runs (" + std::to_string(v.from_ledger) + " from the ledger)" +
            (v.evaluation.failed ? ", failed: " + v.evaluation.failure : ""));
    return v;
}

}  // namespace gradem::cal
