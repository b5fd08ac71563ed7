// The sensitivity study: which parameter moves which property? One-at-a-time elasticities
// d ln(property) / d ln(parameter) of the parameters study.parameters (every free one by
// default) at the relative step study.step, with seeds (docs/calibration.md "Studies").
#include <algorithm>
#include <cmath>

#include "calibrate/evaluator.hpp"
#include "calibrate/study/study_keys.hpp"
#include "calibrate/study/study_runner.hpp"
#include "calibrate/study/study_tables.hpp"
#include "common/input_error.hpp"
#include "common/json_number.hpp"

namespace gradem::cal {
namespace {

using nlohmann::json;
constexpr auto number = common::json_number<json>;  // a number, or null when it is not finite
using common::InputError;

void read_keys(StudyKeys& keys) {
    StudyConfig& c = keys.config;
    c.parameters = study_keys::read_list<std::string>(keys.section, "parameters", "an array of parameter names", study_keys::text_item);
    keys.section.real("step", c.step);
    if (!(c.step > 0.0 && c.step <= 0.5)) study_keys::refuse(keys, "step", "key 'study.step' must be in (0, 0.5]");
}

std::vector<CalibrationProblem> problems(const CalibratedPoint& point, const StudyConfig&) { return {point.problem}; }

// One-at-a-time elasticities with common random numbers: each seed's run at the perturbed point
// is paired with the same seed at the calibrated point, so the seed noise largely cancels.
//   log parameter:    e = Δ ln y / Δ ln p      linear parameter:  e = Δ ln y / Δp
void run(const std::vector<CalibratedPoint>& calibrations, StudyRunner& runner, StudyResult& result) {
    const CalibratedPoint& point = calibrations.front();
    const StudyConfig& cfg = result.config;
    const ParameterSpace space(point.problem.parameters, point.problem.base.material);
    std::vector<std::size_t> chosen;
    if (cfg.parameters.empty()) {
        for (std::size_t k = 0; k < space.size(); ++k) chosen.push_back(k);
    } else {
        for (const std::string& name : cfg.parameters) {
            const auto k = space.index_of(name);
            if (!k) throw InputError(cfg.file.string(), 0, "study.parameters: '" + name + "' is not a free parameter of the calibration");
            chosen.push_back(*k);
        }
    }
    std::vector<std::vector<double>> points{point.values};
    std::vector<std::string> labels{"calibrated"};
    std::vector<double> steps{0.0};
    for (std::size_t k : chosen) {
        const ParameterSpec& spec = space.free(k);
        std::vector<double> v = point.values;
        const double up = spec.log_scale ? v[k] * (1.0 + cfg.step) : v[k] + cfg.step * (spec.upper - spec.lower);
        const double down = spec.log_scale ? v[k] / (1.0 + cfg.step) : v[k] - cfg.step * (spec.upper - spec.lower);
        v[k] = up <= spec.upper ? up : down;  // stay inside the bounds
        points.push_back(v);
        labels.push_back(spec.name);
        steps.push_back(spec.log_scale ? std::log(v[k] / point.values[k]) : v[k] - point.values[k]);
    }
    result.cases = runner.run(point.problem, points, labels, steps);
    const StudyCase& base = result.cases.front();
    StudyTable t{"Elasticities d ln(property) / d ln(parameter) (per unit for linear parameters), mean ± standard error over seeds",
                 {"parameter", "sand", "chord modulus", "peak stress", "strain at peak"}, {}};
    json rows = json::array();
    for (std::size_t c = 1; c < result.cases.size(); ++c) {
        const StudyCase& pert = result.cases[c];
        const ParameterSpec& spec = space.free(chosen[c - 1]);
        for (std::size_t s = 0; s < base.sands.size(); ++s) {
            StudyRow row{{spec.name + (spec.log_scale ? "" : " (per unit)"), base.sands[s]}};
            json j = {{"parameter", spec.name}, {"scale", spec.log_scale ? "log" : "linear"}, {"sand", base.sands[s]}};
            for (Quantity q : kQuantities) {
                std::vector<double> e;
                for (std::size_t r = 0; r < base.runs[s].size() && r < pert.runs[s].size(); ++r)
                    if (base.runs[s][r].ok() && pert.runs[s][r].ok())
                        e.push_back(std::log(outcome_value(pert.runs[s][r], q) / outcome_value(base.runs[s][r], q)) / pert.x);
                const Sample m = sample_of(e);
                const double se = m.n > 1 ? m.std / std::sqrt(static_cast<double>(m.n)) : std::nan("");
                row.cells.push_back(mean_pm(m.mean, se, 3));
                j[to_string(q)] = {{"elasticity", number(m.mean)}, {"std_error", number(se)}, {"n", m.n}};
            }
            t.rows.push_back(row);
            rows.push_back(j);
        }
    }
    result.tables.push_back(t);
    result.data = {{"elasticities", rows}, {"step", cfg.step}};
    for (Quantity q : kQuantities) {
        std::string best;
        double best_e = -1.0;
        for (const json& r : rows)
            if (r[to_string(q)]["elasticity"].is_number() && r["scale"] == "log" &&
                std::fabs(r[to_string(q)]["elasticity"].get<double>()) > best_e)
                best_e = std::fabs(r[to_string(q)]["elasticity"].get<double>()), best = r["parameter"];
        if (!best.empty())
            result.verdict.push_back(std::string(quantity_label(q)) + " moves most with " + best + " (|elasticity| " + fmt_num(best_e, 3) + ")");
    }
}

}  // namespace

const StudyKindSpec sensitivity_study = {
    .keys = {"parameters", "step"},
    .read_keys = read_keys,
    .one_calibration = true,
    .problems = problems,
    .run = run,
};

}  // namespace gradem::cal
