#include "calibrate/study/study_plan.hpp"

#include <algorithm>
#include <sstream>
#include <thread>

#include "calibrate/parameters.hpp"
#include "calibrate/study/study.hpp"
#include "calibrate/study/study_kind.hpp"
#include "calibrate/study/study_runner.hpp"

namespace gradem::cal {
namespace {

/// Every case the kind asks for, answered on the analytic stand-in (study_plan.hpp, step 1).
std::vector<PlannedCase> planned_cases(const StudyConfig& config) {
    StudyResult result;
    result.config = config;
    const std::vector<CalibratedPoint> calibrations = load_studied(config, result);
    std::vector<PlannedCase> planned;
    StudyRunner runner(config, planned);
    study_kind(config.kind).run(calibrations, runner, result);
    return planned;
}

/// Step 2 for one case: one RunCostPlan per sand, at the case's first point.
void plan_case(const PlannedCase& c, double probe_seconds, StudyPlan& plan) {
    const CalibrationProblem& problem = c.problem;
    const ParameterSpace space(problem.parameters, problem.base.material);
    const exp::MaterialParams material = space.material(c.points.front());
    const PlannedSpecimens set{c.label, problem.base, problem.packing_seeds()};
    for (std::size_t s = 0; s < problem.sands.size(); ++s) {
        const int runs = static_cast<int>(c.points.size() * problem.seeds_of(s).size());
        const RunCounts counts = c.test == CubeTest::tension ? RunCounts{0, runs} : RunCounts{runs, 0};
        plan.runs.push_back(plan_runs(problem, set, s, material, counts, probe_seconds, plan.specimens));
        (c.test == CubeTest::tension ? plan.tension_runs : plan.compression_runs) += runs;
    }
}

}  // namespace

StudyPlan plan_study(const StudyConfig& config, double probe_seconds) {
    StudyPlan plan;
    plan.kind = to_string(config.kind);
    plan.workers = config.workers;
    plan.cores = static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
    const std::vector<PlannedCase> cases = planned_cases(config);
    for (const PlannedCase& c : cases) {
        plan.cases += static_cast<int>(c.points.size());
        if (c.problem.model == RunModel::analytic) continue;
        plan_case(c, probe_seconds, plan);
    }
    if (!cases.empty() && cases.front().problem.model == RunModel::analytic)
        plan.assumptions.push_back("model = \"analytic\": the stand-in runs in milliseconds; nothing to estimate");
    add_totals(plan);
    plan.assumptions.push_back("the cases are those the kind asks for when the stand-in answers the earlier ones; "
                               "runs already in the study's ledger are served from it and cost nothing");
    std::vector<BondModel> models;
    for (const PlannedCase& c : cases)
        if (std::find(models.begin(), models.end(), c.problem.bond_model()) == models.end()) models.push_back(c.problem.bond_model());
    for (BondModel m : models) plan.assumptions.push_back(test_cost_assumption(m));
    plan.assumptions.push_back("every run of a case costs what its first point costs");
    return plan;
}

std::string study_plan_text(const StudyPlan& plan) {
    std::ostringstream o;
    o << "study " << plan.kind << ": " << plan.cases << (plan.cases == 1 ? " case, " : " cases, ") << plan.compression_runs
      << " compression runs";
    if (plan.tension_runs) o << " and " << plan.tension_runs << " tension runs";
    o << "\n" << cost_text(plan);
    return o.str();
}

std::string study_plan_json(const StudyPlan& plan) {
    nlohmann::ordered_json j{{"kind", plan.kind},
                             {"cases", plan.cases},
                             {"compression_runs", plan.compression_runs},
                             {"tension_runs", plan.tension_runs}};
    add_cost_json(j, plan);
    return j.dump(2);
}

}  // namespace gradem::cal
