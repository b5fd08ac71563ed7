// The gradation_effect study (the study's question 1): does one parameter set reproduce the
// lab's difference between the sands? One calibrated parameter set, every sand on the study's
// packing seeds; per pair of sands and quantity the difference of the means with its Welch 95 %
// interval against the lab's (docs/calibration.md "Studies").
#include <algorithm>
#include <cmath>

#include "calibrate/study/study_keys.hpp"
#include "calibrate/study/study_runner.hpp"
#include "calibrate/study/study_tables.hpp"
#include "common/json_number.hpp"

namespace gradem::cal {
namespace {

using nlohmann::json;
constexpr auto number = common::json_number<json>;  // a number, or null when it is not finite

void read_keys(StudyKeys& keys) {
    if (keys.config.seeds.size() < 2)
        study_keys::refuse(keys, "seeds", "key 'study.seeds': a 95 % interval needs at least two seeds per sand");
}

std::vector<CalibrationProblem> problems(const CalibratedPoint& point, const StudyConfig&) { return {point.problem}; }

bool excludes_zero(const Interval& i) { return std::isfinite(i.low) && (i.low > 0.0 || i.high < 0.0); }

/// Half-width / 1.96: the standard error behind a 95 % interval (normal approximation).
double se_of(const Interval& i) { return std::isfinite(i.low) ? (i.high - i.low) / (2.0 * 1.959964) : std::nan(""); }

/// Does the simulated difference between two sands reproduce the lab's?
std::string gradation_verdict(const Interval& sim, const Interval& lab) {
    if (!std::isfinite(sim.low)) return "not enough successful runs for an interval";
    if (!excludes_zero(sim)) return "the model does not resolve a difference (its interval includes 0)";
    if ((sim.estimate > 0) != (lab.estimate > 0)) return "opposite sign to the lab";
    const double se = std::hypot(se_of(sim), se_of(lab));
    if (std::fabs(sim.estimate - lab.estimate) <= 1.959964 * se) return "reproduced: same sign, size consistent with the lab (95 %)";
    return std::string("same sign, but ") + (std::fabs(sim.estimate) < std::fabs(lab.estimate) ? "smaller" : "larger") +
           " than the lab's beyond the intervals (" + fmt_num(100.0 * sim.estimate / lab.estimate, 3) + " % of it)";
}

void run(const std::vector<CalibratedPoint>& calibrations, StudyRunner& runner, StudyResult& result) {
    const CalibratedPoint& point = calibrations.front();
    result.cases = runner.run(point.problem, {point.values}, {"calibrated parameters"}, {0.0});
    const StudyCase& c = result.cases.front();
    const CalibrationProblem& p = point.problem;
    StudyTable table{"Difference between the sands with one parameter set (a - b, 95 % Welch intervals)",
                     {"quantity", "a - b", "simulated a", "simulated b", "simulated a - b", "lab a - b", "verdict"},
                     {}};
    json pairs = json::array();
    for (std::size_t a = 0; a < p.sands.size(); ++a)
        for (std::size_t b = a + 1; b < p.sands.size(); ++b)
            for (Quantity q : kQuantities) {
                const Sample sa = c.sample(a, q), sb = c.sample(b, q);
                const TargetStat& ta = target_of(p.targets[a], q);
                const TargetStat& tb = target_of(p.targets[b], q);
                const Interval sim = welch_interval(sa, sb);
                const Interval lab = welch_interval({ta.mean, ta.std, ta.n}, {tb.mean, tb.std, tb.n});
                const std::string verdict = gradation_verdict(sim, lab);
                const double k = display_scale(q);
                table.rows.push_back({{std::string(quantity_label(q)) + " [" + display_unit(q) + "]", p.sands[a] + " - " + p.sands[b],
                                       mean_pm(sa.mean * k, sa.std * k), mean_pm(sb.mean * k, sb.std * k),
                                       interval_text(sim, k), interval_text(lab, k), verdict}});
                pairs.push_back({{"quantity", to_string(q)}, {"unit", display_unit(q)}, {"sand_a", p.sands[a]}, {"sand_b", p.sands[b]},
                                 {"simulated", interval_json(sim, k)}, {"lab", interval_json(lab, k)},
                                 {"simulated_a", {{"mean", number(sa.mean * k)}, {"std", number(sa.std * k)}, {"n", sa.n}}},
                                 {"simulated_b", {{"mean", number(sb.mean * k)}, {"std", number(sb.std * k)}, {"n", sb.n}}},
                                 {"lab_a", {{"mean", ta.mean * k}, {"std", ta.std * k}, {"n", ta.n}}},
                                 {"lab_b", {{"mean", tb.mean * k}, {"std", tb.std * k}, {"n", tb.n}}},
                                 {"verdict", verdict}});
                result.verdict.push_back(std::string(quantity_label(q)) + ", " + p.sands[a] + " - " + p.sands[b] + ": simulated " +
                                         interval_text(sim, k) + " " + display_unit(q) + " vs lab " + interval_text(lab, k) + " " +
                                         display_unit(q) + " -> " + verdict);
            }
    result.tables.push_back(table);
    result.tables.push_back(case_table("Per sand at the calibrated parameters (mean ± seed std)", "case", result.cases));
    result.data = {{"pairs", pairs}, {"seeds", result.config.seeds}, {"bond_model", point.bond_model}};
}

}  // namespace

const StudyKindSpec gradation_effect_study = {
    .keys = {},
    .read_keys = read_keys,
    .one_calibration = true,
    .problems = problems,
    .run = run,
};

}  // namespace gradem::cal
