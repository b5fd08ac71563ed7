// The study kinds (study_kind.hpp) on top of the calibration's Evaluator: every simulated
// configuration ("case") is a set of parameter points run on every sand and seed, through the
// study's own ledger.
#include "calibrate/study/study.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <fstream>
#include <memory>
#include <optional>
#include <stdexcept>

#include "calibrate/calibration.hpp"
#include "calibrate/evaluator.hpp"
#include "calibrate/execution/ledger.hpp"
#include "calibrate/study/study_runner.hpp"
#include "calibrate/study/study_models.hpp"
#include "common/hash.hpp"
#include "common/input_error.hpp"
#include "common/json_file.hpp"
#include "common/number_format.hpp"

namespace gradem::cal {
namespace {

namespace fs = std::filesystem;
using common::InputError;
using nlohmann::json;

}  // namespace

// --- cases ------------------------------------------------------------------------------

Sample StudyCase::sample(std::size_t sand, Quantity q) const {
    std::vector<double> v;
    for (const RunOutcome& r : runs[sand])
        if (r.ok()) v.push_back(outcome_value(r, q));
    return sample_of(v);
}

double StudyCase::mean_particles(std::size_t sand) const {
    double sum = 0.0;
    for (const RunOutcome& r : runs[sand]) sum += static_cast<double>(r.particles);
    return runs[sand].empty() ? 0.0 : sum / static_cast<double>(runs[sand].size());
}

double StudyCase::mean_wall_seconds(std::size_t sand) const {
    double sum = 0.0;
    int n = 0;
    for (const RunOutcome& r : runs[sand])
        if (r.wall_seconds > 0.0) sum += r.wall_seconds, ++n;
    return n ? sum / n : std::nan("");
}

int StudyCase::failed() const {
    int n = 0;
    for (const auto& sand : runs)
        for (const RunOutcome& r : sand) n += r.ok() ? 0 : 1;
    return n;
}

// --- the calibration studied ---------------------------------------------------------------

CalibratedPoint load_calibrated_point(const fs::path& summary_json) {
    const std::string where = summary_json.string();
    if (!fs::exists(summary_json)) throw InputError(where, 0, "calibration summary not found; run `gradem calibrate <config>` first");
    const json j = common::read_json_file(summary_json, "the calibration summary");
    if (j.value("schema", "") != "gradem-calibration/1")
        throw InputError(where, 0, "not a gradem calibration summary (schema \"gradem-calibration/1\" expected)");
    CalibratedPoint cp;
    cp.summary = summary_json;
    cp.document = j;
    const fs::path config = j.value("config", "");
    if (config.empty() || !fs::exists(config))
        throw InputError(where, 0, "the calibration's config '" + config.string() +
                                       "' is not reachable from here (run the study from the folder the calibration ran in)");
    cp.problem = load_calibration_problem(config);
    if (j.value("sands", std::vector<std::string>{}) != cp.problem.sands)
        throw InputError(where, 0, "belongs to another problem: its sands differ from those of " + config.string());
    if (j.value("lab_results", "") != cp.problem.lab_results.string())
        throw InputError(where, 0, "belongs to another dataset: lab results " + j.value("lab_results", "") + " vs " +
                                       cp.problem.lab_results.string() + " in " + config.string());
    for (ParameterSpec& spec : cp.problem.parameters) {
        const json* found = nullptr;
        for (const json& p : j.at("parameters"))
            if (p.value("name", "") == spec.name) found = &p;
        if (!found || !found->contains("value") || !(*found)["value"].is_number())
            throw InputError(where, 0, "has no calibrated value for parameter '" + spec.name + "'");
        const double v = (*found)["value"].get<double>();
        if (spec.free && !(v >= spec.lower && v <= spec.upper))
            throw InputError(where, 0, "parameter '" + spec.name + "' = " + common::format_significant(v, 6) +
                                           " is outside the config's bounds: the config changed since the calibration");
        spec.start = v;
    }
    // With [scale_up] the values are the result set on the scale-up specimens: studies run that size.
    const bool scaled_up = j.contains("stages") && !j["stages"].empty() && j["stages"][0].contains("scale_up") &&
                           j["stages"][0]["scale_up"].value("done", false);
    if (scaled_up) cp.problem.base.specimen.genesis.edge = cp.problem.scale_up.edge;
    cp.values = ParameterSpace(cp.problem.parameters, cp.problem.base.material).start();
    cp.bond_model = bond_model_name(cp.problem.base.material.bond.model);
    if (cp.problem.base.representation != exp::Representation::parallel_bonds)  // the paste as particles
        cp.bond_model += std::string(", ") + to_string(cp.problem.base.representation);
    return cp;
}

// --- running cases -------------------------------------------------------------------------

StudyRunner::StudyRunner(const StudyConfig& config, std::function<void(const std::string&)> log, const StudyExecution* execution)
    : config_(config), log_(std::move(log)),
      ledger_(std::make_unique<Ledger>(config.ledger, common::fnv1a_hex(config.describe()), config.describe())),
      execution_(execution) {
    if (const auto rows = ledger_->size()) say("ledger " + config.ledger.string() + ": " + std::to_string(rows) + " runs recorded, resuming");
}

StudyRunner::StudyRunner(const StudyConfig& config, std::vector<PlannedCase>& planned)
    : config_(config), ledger_(std::make_unique<Ledger>(":memory:", common::fnv1a_hex(config.describe()), config.describe())),
      execution_(nullptr), planned_(&planned) {}

StudyRunner::~StudyRunner() = default;

void StudyRunner::say(const std::string& line) const {
    if (log_) log_(line);
}

namespace {

/// One case's evaluations and how its runs went.
struct CaseRuns {
    std::vector<Evaluation> evals;
    int executed = 0, from_ledger = 0, failed = 0;
};

/// The runs of one case through an Evaluator: on threads with a model of its own, or on the
/// shared executor with the case's model among the StudyModels (the same model, the same
/// ledger keys, the same outcomes).
CaseRuns evaluate_case(const CalibrationProblem& problem, const std::vector<std::vector<double>>& points, const std::string& label,
                       Ledger& ledger, const StudyExecution* execution, CubeTest test,
                       const std::function<void(const std::string&)>& say) {
    const ParameterSpace space(problem.parameters, problem.base.material);
    std::vector<std::size_t> sands;
    for (std::size_t s = 0; s < problem.sands.size(); ++s) sands.push_back(s);
    auto evaluate = [&](Evaluator& evaluator) {
        CaseRuns r;
        r.evals = evaluator.evaluate(points, sands, label);
        r.executed = evaluator.runs_executed(), r.from_ledger = evaluator.runs_from_ledger(), r.failed = evaluator.runs_failed();
        return r;
    };
    if (execution && test == CubeTest::compression) {
        const std::optional<std::size_t> k = execution->models.find(problem);
        if (!k) throw std::logic_error("study: a case that study_problems() did not list");
        CaseExecutor executor(execution->executor, execution->models.offset(*k));
        Evaluator evaluator(problem, space, executor, ledger, execution->models.model(*k));
        return evaluate(evaluator);
    }
    auto model = make_model(problem, test == CubeTest::tension);
    model->prepare(problem.packing_seeds(), problem.workers, say);
    Evaluator evaluator(problem, space, *model, ledger, {}, test);
    return evaluate(evaluator);
}

/// The calibration's own packing seeds on a study problem made from it: its common list and
/// each sand's own list ([calibration] sand_seeds), matched by sand name (the study may keep
/// only some of the sands).
void use_calibration_seeds(const CalibrationProblem& calibration, CalibrationProblem& problem) {
    problem.seeds = calibration.seeds;
    problem.sand_seeds.clear();
    for (const std::string& sand : problem.sands) {
        const auto it = std::find(calibration.sands.begin(), calibration.sands.end(), sand);
        problem.sand_seeds.push_back(it == calibration.sands.end()
                                         ? calibration.seeds
                                         : calibration.seeds_of(static_cast<std::size_t>(it - calibration.sands.begin())));
    }
}

/// An evaluation's runs split per sand: the evaluator runs each sand on its seeds in turn.
std::vector<std::vector<RunOutcome>> runs_by_sand(const CalibrationProblem& problem, const std::vector<RunOutcome>& runs) {
    std::vector<std::vector<RunOutcome>> out(problem.sands.size());
    std::size_t r = 0;
    for (std::size_t s = 0; s < problem.sands.size(); ++s)
        for (std::size_t k = 0; k < problem.seeds_of(s).size() && r < runs.size(); ++k) out[s].push_back(runs[r++]);
    return out;
}

}  // namespace

std::vector<StudyCase> StudyRunner::run(CalibrationProblem problem, const std::vector<std::vector<double>>& points,
                                        const std::vector<std::string>& labels, const std::vector<double>& xs,
                                        const CaseOptions& options) {
    const CalibrationProblem own = problem;
    problem = as_study_problem(std::move(problem), config_);
    if (options.calibration_seeds) use_calibration_seeds(own, problem);
    if (planned_) {
        planned_->push_back({problem, points, labels.empty() ? "study" : labels.front(), options.test});
        problem.model = RunModel::analytic;
    }
    const CaseRuns runs = evaluate_case(problem, points, labels.empty() ? "study" : labels.front(), *ledger_, execution_,
                                        options.test, [this](const std::string& s) { say(s); });
    const std::vector<Evaluation>& evals = runs.evals;
    executed_ += runs.executed;
    from_ledger_ += runs.from_ledger;
    failed_ += runs.failed;
    std::vector<StudyCase> cases;
    for (std::size_t k = 0; k < evals.size(); ++k) {
        StudyCase c;
        c.label = k < labels.size() ? labels[k] : "case " + std::to_string(k + 1);
        c.x = k < xs.size() ? xs[k] : 0.0;
        c.sands = problem.sands;
        c.seeds = problem.seeds;
        c.runs = runs_by_sand(problem, evals[k].runs);
        say(c.label + ": " + std::to_string(evals[k].runs.size()) + " runs, " + std::to_string(c.failed()) + " failed");
        cases.push_back(std::move(c));
    }
    return cases;
}

// --- the whole study -----------------------------------------------------------------------

std::vector<CalibratedPoint> load_studied(const StudyConfig& config, StudyResult& result) {
    std::vector<CalibratedPoint> points;
    const std::vector<fs::path> files = study_kind(config.kind).one_calibration ? std::vector<fs::path>{config.calibration}
                                                                                : config.calibrations;
    for (const fs::path& file : files) {
        points.push_back(load_calibrated_point(file));
        (void)as_study_problem(points.back().problem, config);
        result.calibration_summaries.push_back(file.string());
        result.representative = result.representative || points.back().problem.representative;
    }
    return points;
}

StudyResult run_study(const StudyConfig& config, const std::function<void(const std::string&)>& log, const StudyExecution* execution) {
    const auto start = std::chrono::steady_clock::now();
    StudyResult result;
    result.config = config;
    const std::vector<CalibratedPoint> calibrations = load_studied(config, result);
    StudyRunner runner(config, log, execution);
    study_kind(config.kind).run(calibrations, runner, result);
    result.runs_executed = runner.executed();
    result.runs_from_ledger = runner.from_ledger();
    result.runs_failed = runner.failed();
    result.wall_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    return result;
}

}  // namespace gradem::cal
