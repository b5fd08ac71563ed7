// One function per study kind. Each runs its cases through the StudyRunner, then fills the
// result's tables (what study.md shows), data (what study.json and the figures read) and
// verdict (plain sentences). Stresses and moduli are shown in MPa, strains as ratios.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>

#include "calibrate/study/study_kinds.hpp"
#include "common/input_error.hpp"
#include "common/json_number.hpp"
#include "common/number_format.hpp"

namespace gradem::cal {
namespace {

using nlohmann::json;
constexpr auto number = common::json_number<json>;  // a number, or null when it is not finite
using common::InputError;

double display(Quantity q) { return q == Quantity::strain ? 1.0 : 1e-6; }
const char* label(Quantity q) {
    return q == Quantity::modulus ? "chord modulus" : q == Quantity::peak ? "peak stress" : "strain at peak";
}
const char* unit(Quantity q) { return q == Quantity::strain ? "-" : "MPa"; }

std::string interval_text(const Interval& i, double scale) {
    if (!std::isfinite(i.low)) return fmt_num(i.estimate * scale) + " [n < 2]";
    return fmt_num(i.estimate * scale) + " [" + fmt_num(i.low * scale) + ", " + fmt_num(i.high * scale) + "]";
}

json interval_json(const Interval& i, double scale) {
    return {{"estimate", number(i.estimate * scale)}, {"low", number(i.low * scale)}, {"high", number(i.high * scale)}};
}

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

StudyTable case_table(const std::string& title, const std::string& x_name, const std::vector<StudyCase>& cases) {
    StudyTable t{title, {x_name, "sand", "particles", "chord modulus MPa", "peak MPa", "strain at peak", "wall s/run", "failed"}, {}};
    for (const StudyCase& c : cases)
        for (std::size_t s = 0; s < c.sands.size(); ++s) {
            StudyRow row{{c.label, c.sands[s], fmt_num(c.mean_particles(s), 6)}};
            for (Quantity q : kQuantities) {
                const Sample m = c.sample(s, q);
                row.cells.push_back(mean_pm(m.mean * display(q), m.std * display(q)));
            }
            row.cells.push_back(fmt_num(c.mean_wall_seconds(s), 3));
            int failed = 0;
            for (const RunOutcome& r : c.runs[s]) failed += r.ok() ? 0 : 1;
            row.cells.push_back(std::to_string(failed));
            t.rows.push_back(row);
        }
    return t;
}

json case_samples_json(const StudyCase& c) {
    json sands = json::array();
    for (std::size_t s = 0; s < c.sands.size(); ++s) {
        json j = {{"sand", c.sands[s]}, {"particles", c.mean_particles(s)}, {"wall_seconds_per_run", number(c.mean_wall_seconds(s))}};
        for (Quantity q : kQuantities) {
            const Sample m = c.sample(s, q);
            j[to_string(q)] = {{"mean", number(m.mean * display(q))}, {"std", number(m.std * display(q))}, {"n", m.n}, {"unit", unit(q)}};
        }
        sands.push_back(j);
    }
    return {{"label", c.label}, {"x", c.x}, {"sands", sands}};
}

}  // namespace

std::string fmt_num(double v, int digits) { return common::format_significant(v, digits); }

std::string mean_pm(double mean, double std, int digits) {
    if (!std::isfinite(mean)) return "-";
    return fmt_num(mean, digits) + (std::isfinite(std) ? " ± " + fmt_num(std, 2) : "");
}

// gradation_effect: the study's question 1. One parameter set, every sand, n seeds each; the
// difference of the sand means with its Welch 95 % interval against the lab's.
void run_gradation_effect(const CalibratedPoint& point, StudyRunner& runner, StudyResult& result) {
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
                const double k = display(q);
                table.rows.push_back({{std::string(label(q)) + " [" + unit(q) + "]", p.sands[a] + " - " + p.sands[b],
                                       mean_pm(sa.mean * k, sa.std * k), mean_pm(sb.mean * k, sb.std * k),
                                       interval_text(sim, k), interval_text(lab, k), verdict}});
                pairs.push_back({{"quantity", to_string(q)}, {"unit", unit(q)}, {"sand_a", p.sands[a]}, {"sand_b", p.sands[b]},
                                 {"simulated", interval_json(sim, k)}, {"lab", interval_json(lab, k)},
                                 {"simulated_a", {{"mean", number(sa.mean * k)}, {"std", number(sa.std * k)}, {"n", sa.n}}},
                                 {"simulated_b", {{"mean", number(sb.mean * k)}, {"std", number(sb.std * k)}, {"n", sb.n}}},
                                 {"lab_a", {{"mean", ta.mean * k}, {"std", ta.std * k}, {"n", ta.n}}},
                                 {"lab_b", {{"mean", tb.mean * k}, {"std", tb.std * k}, {"n", tb.n}}},
                                 {"verdict", verdict}});
                result.verdict.push_back(std::string(label(q)) + ", " + p.sands[a] + " - " + p.sands[b] + ": simulated " +
                                         interval_text(sim, k) + " " + unit(q) + " vs lab " + interval_text(lab, k) + " " +
                                         unit(q) + " -> " + verdict);
            }
    result.tables.push_back(table);
    result.tables.push_back(case_table("Per sand at the calibrated parameters (mean ± seed std)", "case", result.cases));
    result.data = {{"pairs", pairs}, {"seeds", result.config.seeds}, {"bond_model", point.bond_model}};
}

// resolution / fines_truncation: the same parameters on specimens of another edge or another
// smallest kept grain; cases in increasing order of the swept size.
// Every swept specimen is checked before anything runs.
std::vector<CalibrationProblem> sweep_problems(const CalibratedPoint& point, const StudyConfig& cfg, SweepKind kind) {
    const char* key = kind == SweepKind::edge ? "study.edges_mm" : "study.min_diameters_mm";
    std::vector<CalibrationProblem> problems;
    for (double x : cfg.sweep_mm) {
        CalibrationProblem p = point.problem;
        exp::SpecimenSpec& spec = p.base.specimen;
        if (kind == SweepKind::edge) spec.genesis.edge = x * 1e-3;
        else spec.size_rule.min_diameter = x * 1e-3;
        const std::string value = std::string(key) + " value " + fmt_num(x) + " mm";
        if (auto why = spec.invalid_reason()) throw InputError(cfg.file.string(), 0, value + " gives an invalid specimen: " + *why);
        if (spec.size_rule.max_diameter > 0.0 && spec.genesis.edge < 3.0 * spec.size_rule.max_diameter)
            throw InputError(cfg.file.string(), 0, value + ": the cube edge " + fmt_num(spec.genesis.edge * 1e3) +
                                                       " mm is under 3 x the largest grain (" +
                                                       fmt_num(spec.size_rule.max_diameter * 1e3) + " mm)");
        if (spec.size_rule.max_diameter > 0.0 && spec.size_rule.min_diameter >= spec.size_rule.max_diameter)
            throw InputError(cfg.file.string(), 0, value + " is not below the largest kept grain (" +
                                                       fmt_num(spec.size_rule.max_diameter * 1e3) + " mm)");
        problems.push_back(std::move(p));
    }
    return problems;
}

void run_size_sweep(const CalibratedPoint& point, StudyRunner& runner, StudyResult& result, SweepKind kind) {
    const StudyConfig& cfg = result.config;
    const std::vector<CalibrationProblem> problems = sweep_problems(point, cfg, kind);
    for (std::size_t k = 0; k < problems.size(); ++k) {
        const double x = cfg.sweep_mm[k];
        const std::string name = (kind == SweepKind::edge ? "edge " : "d_min ") + fmt_num(x) + " mm";
        runner.say("case " + name);
        for (StudyCase& c : runner.run(problems[k], {point.values}, {name}, {x})) result.cases.push_back(std::move(c));
    }
    result.tables.push_back(case_table(kind == SweepKind::edge ? "Macro properties against the cube edge (mean ± seed std)"
                                                               : "Macro properties against the smallest kept grain (mean ± seed std)",
                                       kind == SweepKind::edge ? "edge" : "smallest grain", result.cases));
    json cases = json::array();
    for (const StudyCase& c : result.cases) cases.push_back(case_samples_json(c));
    result.data = {{"x_name", kind == SweepKind::edge ? "edge_mm" : "min_diameter_mm"}, {"cases", cases}};
    if (kind == SweepKind::edge) summarise_convergence(result);
    else summarise_truncation(result);
}

}  // namespace gradem::cal
