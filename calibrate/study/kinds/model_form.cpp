// The model_form study: which bond model fits the lab best? The calibrations of several bond
// models (or representations) of study.calibrations side by side: per model and sand the error
// against the lab on the three targets on the fitted specimens (met within target_tolerance.hpp's
// tolerances or not) and, where the calibration has [validation], on its validation specimens,
// the shape index D = E ε_peak / σ_peak, σc/σt from the direct-tension test at the calibrated
// parameters (the calibration's sands, each sand's own seeds and base cube; through the study's
// ledger, so a rerun repeats no test), and the cost per cube test from the calibration's ledger
// (docs/calibration.md "Studies").
#include <algorithm>
#include <cmath>

#include "calibrate/study/study_keys.hpp"
#include "calibrate/study/study_runner.hpp"
#include "calibrate/study/study_tables.hpp"
#include "calibrate/target_tolerance.hpp"
#include "common/json_number.hpp"

namespace gradem::cal {
namespace {

using nlohmann::json;
constexpr auto number = common::json_number<json>;  // a number, or null when it is not finite

void read_keys(StudyKeys&) {}  // study.calibrations: read with the calibration(s) studied

/// The calibration's ledger: as its summary names it, else ledger.sqlite beside the summary
/// (the default place, for a summary read from another folder).
std::vector<RunCost> calibration_run_costs(const CalibratedPoint& cp, const json& summary, std::string& note) {
    const std::filesystem::path named = summary.value("ledger", "");
    const std::filesystem::path beside = cp.summary.parent_path() / "ledger.sqlite";
    for (const auto& path : {named, beside}) {
        std::error_code ec;
        if (path.empty() || !std::filesystem::exists(path, ec)) continue;
        try {
            return read_run_costs(path);
        } catch (const LedgerError& e) {
            note = e.what();
            return {};
        }
    }
    note = "ledger of " + cp.summary.string() + " not found (" + named.string() + ")";
    return {};
}

std::string pct_text(double v) { return std::isfinite(v) ? fmt_num(100 * v, 3) + " %" : "-"; }

/// The errors on the calibration's validation specimens, "-" without them.
std::string validation_text(const double (&err)[3]) {
    if (!std::isfinite(err[0]) && !std::isfinite(err[1]) && !std::isfinite(err[2])) return "-";
    return pct_text(err[0]) + " / " + pct_text(err[1]) + " / " + pct_text(err[2]);
}

/// What a model's sands add up to: its worst target error, whether every target is met, and
/// its σc/σt per sand as text.
struct ModelTally {
    double worst = 0.0;
    bool every_met = true;
    std::string ratio_text;
};

/// Sand s of a calibrated model: its table row and JSON entry (errors, D, σt and σc/σt, cost).
void add_model_sand(const CalibratedPoint& cp, const json& j, std::size_t s, const StudyCase& tension,
                    const std::vector<RunCost>& costs, StudyTable& table, json& model, ModelTally& tally) {
    const std::filesystem::path& file = cp.summary;
    const std::string& sand = cp.problem.sands[s];
    // The fitted specimens' rows (σt runs on them); a summary with [validation] also has rows
    // of its validation specimens, kept apart.
    double err[3] = {NAN, NAN, NAN}, sim[3] = {NAN, NAN, NAN}, lab[3] = {NAN, NAN, NAN}, validation[3] = {NAN, NAN, NAN};
    for (const json& r : j.at("targets")) {
        if (r.value("sand", "") != sand) continue;
        const bool validation_row = r.value("role", "fitted") == "validation";
        for (Quantity q : kQuantities)
            if (r.value("quantity", "") == to_string(q)) {
                const int k = static_cast<int>(q);
                if (validation_row) {
                    validation[k] = common::number_or_nan(r, "rel_error");
                    continue;
                }
                err[k] = common::number_or_nan(r, "rel_error");
                sim[k] = common::number_or_nan(r, "sim_mean");
                lab[k] = common::number_or_nan(r, "lab_mean");
            }
    }
    const double d_sim = sim[0] * sim[2] / sim[1], d_lab = lab[0] * lab[2] / lab[1];
    int met = 0;
    for (Quantity q : kQuantities) met += target_met(q, err[static_cast<int>(q)]) ? 1 : 0;
    tally.every_met = tally.every_met && met == 3;
    for (double e : err) tally.worst = std::max(tally.worst, std::isfinite(e) ? std::fabs(e) : 1e300);
    const Sample sigma_t = tension.sample(s, Quantity::peak);             // [Pa]
    const double ratio = compressive_to_tensile_ratio(sim[1] * 1e6, sigma_t);  // summary peaks are in MPa
    const RunCostSummary cost = summarise_costs(costs, sand);
    tally.ratio_text += (tally.ratio_text.empty() ? "" : ", ") + sand + " " + fmt_num(ratio, 3);
    table.rows.push_back({{cp.bond_model, file.parent_path().filename().string(), std::to_string(j.value("dem_test_runs", 0)),
                       fmt_num(j.value("wall_seconds", 0.0), 4), sand, pct_text(err[0]), pct_text(err[1]), pct_text(err[2]),
                       std::to_string(met) + " of 3", validation_text(validation), fmt_num(d_sim, 3), fmt_num(d_lab, 3),
                       mean_pm(sigma_t.mean * 1e-6, sigma_t.std * 1e-6, 3) + " (n " + std::to_string(sigma_t.n) + ")",
                       fmt_num(ratio, 3), fmt_num(cost.mean_wall_seconds, 3), fmt_num(cost.particle_steps_per_second, 3)}});
    model["sands"].push_back({{"sand", sand}, {"modulus_error", number(err[0])}, {"peak_error", number(err[1])},
                          {"strain_error", number(err[2])}, {"targets_met", met},
                          {"validation", {{"modulus_error", number(validation[0])}, {"peak_error", number(validation[1])},
                                          {"strain_error", number(validation[2])}}},
                          {"shape_index_sim", number(d_sim)}, {"shape_index_lab", number(d_lab)},
                          {"peak_compression_mpa", number(sim[1])},
                          {"tensile_strength_mpa", {{"mean", number(sigma_t.mean * 1e-6)}, {"std", number(sigma_t.std * 1e-6)},
                                                    {"n", sigma_t.n}, {"failed", static_cast<int>(tension.runs[s].size()) - sigma_t.n}}},
                          {"compressive_to_tensile_ratio", number(ratio)},
                          {"cost", {{"runs", cost.runs}, {"wall_seconds_per_run", number(cost.mean_wall_seconds)},
                                    {"particle_steps_per_second", number(cost.particle_steps_per_second)}}}});
}

void run(const std::vector<CalibratedPoint>& calibrations, StudyRunner& runner, StudyResult& result) {
    StudyTable t{"Calibrated models side by side (errors: simulated / lab - 1; cost: the calibration's compression runs, "
                 "wall time with its other runs in flight)",
                 {"model", "summary", "DEM runs", "wall s", "sand", "modulus error", "peak error", "strain error", "targets met",
                  "validation: modulus / peak / strain error", "D sim", "D lab", "sigma_t MPa", "sigma_c/sigma_t", "wall s/run", "particle-steps/s"},
                 {}};
    json models = json::array();
    double best_score = 1e300;
    std::string best;
    std::vector<std::string> all_met, ratios;
    for (const CalibratedPoint& cp : calibrations) {
        const std::filesystem::path& file = cp.summary;
        const json& j = cp.document;
        const std::string name = cp.bond_model + " (" + file.parent_path().filename().string() + ")";
        runner.say("direct tension at the calibrated parameters of " + name);
        StudyCase tension = std::move(runner.run(cp.problem, {cp.values}, {"direct tension, " + name}, {0.0},
                                                 {CubeTest::tension, true}).front());
        std::string cost_note;
        const std::vector<RunCost> costs = calibration_run_costs(cp, j, cost_note);
        if (!cost_note.empty()) result.verdict.push_back("cost per cube test of " + name + " unknown: " + cost_note);
        json m = {{"model", cp.bond_model}, {"summary", file.string()}, {"runs", j.value("dem_test_runs", 0)},
                  {"wall_seconds", j.value("wall_seconds", 0.0)}, {"seeds", cp.problem.seeds}, {"sands", json::array()}};
        ModelTally tally;
        for (std::size_t s = 0; s < cp.problem.sands.size(); ++s) add_model_sand(cp, j, s, tension, costs, t, m, tally);
        const double worst = tally.worst;
        const bool every_met = tally.every_met;
        const std::string& ratio_text = tally.ratio_text;
        m["worst_error"] = number(worst);
        m["all_targets_met"] = every_met;
        models.push_back(m);
        result.cases.push_back(std::move(tension));
        if (every_met) all_met.push_back(name);
        ratios.push_back(name + ": " + ratio_text);
        if (worst < best_score) best_score = worst, best = cp.bond_model + " (" + file.string() + ")";
    }
    result.tables.push_back(t);
    const TargetTolerances& tol = kTargetTolerances;
    result.data = {{"models", models},
                   {"target_tolerances", {{"modulus", tol.modulus}, {"peak_stress", tol.peak}, {"strain_at_peak", tol.strain}}}};
    result.verdict.push_back("smallest worst-target error: " + best + ", " + fmt_num(100 * best_score, 3) + " %");
    std::string met_text;
    for (const std::string& n : all_met) met_text += (met_text.empty() ? "" : ", ") + n;
    result.verdict.push_back("every target met (modulus within " + fmt_num(100 * tol.modulus, 3) + " %, peak within " +
                             fmt_num(100 * tol.peak, 3) + " %, strain at peak within " + fmt_num(100 * tol.strain, 3) +
                             " %) on every sand: " + (met_text.empty() ? std::string("no model") : met_text));
    for (const std::string& r : ratios)
        result.verdict.push_back("sigma_c/sigma_t at the calibrated parameters, " + r + " (mortar: about 8-12)");
}

}  // namespace

const StudyKindSpec model_form_study = {
    .keys = {"calibrations"},
    .read_keys = read_keys,
    .one_calibration = false,
    .problems = nullptr,
    .run = run,
    .runs_note = " (direct-tension tests for sigma_c/sigma_t, each calibration's seeds)",
};

}  // namespace gradem::cal
