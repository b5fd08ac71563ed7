#include "calibrate/study/study_models.hpp"

#include <algorithm>
#include <stdexcept>

#include "calibrate/calibration.hpp"
#include "calibrate/study/study.hpp"
#include "common/input_error.hpp"

namespace gradem::cal {
namespace {

/// The same specimen and test: what the study kinds vary (the cube edge, the kept grain sizes)
/// and everything the problem's answer depends on (its canonical text).
bool same_case(const CalibrationProblem& a, const CalibrationProblem& b) {
    const exp::SpecimenSpec &x = a.base.specimen, &y = b.base.specimen;
    return a.model == b.model && x.genesis.edge == y.genesis.edge && x.size_rule.min_diameter == y.size_rule.min_diameter &&
           x.size_rule.max_diameter == y.size_rule.max_diameter && x.size_rule.scale == y.size_rule.scale &&
           a.describe() == b.describe();
}

/// Keeps the study's `sands` (in its order) of the calibration's, with their lab targets.
void select_sands(CalibrationProblem& problem, const StudyConfig& config) {
    std::vector<std::string> sands;
    std::vector<SandTargets> targets;
    for (const std::string& name : config.sands) {
        const auto it = std::find(problem.sands.begin(), problem.sands.end(), name);
        if (it == problem.sands.end()) {
            std::string known;
            for (const auto& s : problem.sands) known += (known.empty() ? "" : ", ") + s;
            throw common::InputError(config.file.string(), config.sands_line,
                                     "key 'study.sands': '" + name + "' is not a sand of the calibration (" + known + ")");
        }
        sands.push_back(name);
        targets.push_back(problem.targets.at(static_cast<std::size_t>(it - problem.sands.begin())));
    }
    problem.sands = std::move(sands);
    problem.targets = std::move(targets);
}

}  // namespace

CalibrationProblem as_study_problem(CalibrationProblem problem, const StudyConfig& config) {
    problem.seeds = config.seeds;
    problem.sand_seeds.clear();  // the study's seeds for every sand
    if (!config.sands.empty()) select_sands(problem, config);
    problem.workers = config.workers;
    problem.timeout_s = config.timeout_s;
    problem.solver.max_runs = 1 << 30;  // a study runs what it asks for
    problem.tension = {};               // and fits nothing: its tension runs are cases of their own
    return problem;
}

std::vector<CalibrationProblem> study_problems(const StudyConfig& config) {
    const StudyKindSpec& kind = study_kind(config.kind);
    if (kind.problems == nullptr) return {};
    std::vector<CalibrationProblem> problems = kind.problems(load_calibrated_point(config.calibration), config);
    for (CalibrationProblem& p : problems) p = as_study_problem(std::move(p), config);
    return problems;
}

StudyModels::StudyModels(std::vector<CalibrationProblem> problems) : problems_(std::move(problems)) {
    std::size_t sands = 0;
    for (const CalibrationProblem& p : problems_) {
        models_.push_back(make_model(p));
        offsets_.push_back(sands);
        sands += p.sands.size();
    }
}

std::optional<std::size_t> StudyModels::find(const CalibrationProblem& problem) const {
    for (std::size_t k = 0; k < problems_.size(); ++k)
        if (same_case(problems_[k], problem)) return k;
    return std::nullopt;
}

void StudyModels::prepare(const PackingSeeds& seeds, int workers, const std::function<void(const std::string&)>& log) {
    for (auto& m : models_) m->prepare(seeds, workers, log);
}

void StudyModels::load_prepared(const PackingSeeds& seeds) {
    for (auto& m : models_) m->load_prepared(seeds);
}

RunOutcome StudyModels::run(const RunRequest& request, double timeout_s) const {
    for (std::size_t k = problems_.size(); k-- > 0;)
        if (request.sand >= offsets_[k]) {
            if (request.sand - offsets_[k] >= problems_[k].sands.size()) break;
            RunRequest local = request;
            local.sand -= offsets_[k];
            return models_[k]->run(local, timeout_s);
        }
    throw std::out_of_range("study: sand " + std::to_string(request.sand) + " is no case's sand");
}

std::string StudyModels::fingerprint() const {
    std::string f = "study cases " + std::to_string(models_.size());
    for (const auto& m : models_) f += "\n--\n" + m->fingerprint();
    return f;
}

std::string StudyModels::run_fingerprint(CubeTest test) const {
    std::string f = "study cases " + std::to_string(models_.size());
    for (const auto& m : models_) f += "\n--\n" + m->run_fingerprint(test);
    return f;
}

void CaseExecutor::run(const std::vector<RunRequest>& requests, double timeout_s, const RunDone& done) {
    std::vector<RunRequest> shifted = requests;
    for (RunRequest& r : shifted) r.sand += offset_;
    all_.run(shifted, timeout_s, done);
}

}  // namespace gradem::cal
