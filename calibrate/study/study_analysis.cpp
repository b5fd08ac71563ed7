// The analysis half of the sweep studies, sensitivity and model_form (see study_kinds.hpp).
#include <algorithm>
#include <cmath>
#include <fstream>

#include "calibrate/study/study_kinds.hpp"
#include "calibrate/target_tolerance.hpp"
#include "common/input_error.hpp"
#include "common/json_number.hpp"

namespace gradem::cal {
namespace {

using nlohmann::json;
constexpr auto number = common::json_number<json>;  // a number, or null when it is not finite
using common::InputError;

const char* label(Quantity q) {
    return q == Quantity::modulus ? "chord modulus" : q == Quantity::peak ? "peak stress" : "strain at peak";
}

double output_of(const RunOutcome& r, Quantity q) {
    return q == Quantity::modulus ? r.modulus_pa : q == Quantity::peak ? r.peak_pa : r.strain_at_peak;
}

}  // namespace

// A property has converged at case k when every later step changes its mean by less than the
// seed standard deviation of the two cases it joins (the noise a user sees at one size), or by
// less than study.tolerance × the mean (a change the user has said does not matter: as the
// cubes grow the seed spread shrinks below any change worth a bigger cube).
void summarise_convergence(StudyResult& result) {
    const auto& cases = result.cases;
    const double tolerance = result.config.tolerance;
    const std::string criterion = tolerance > 0.0 ? "the seed spread or " + fmt_num(100.0 * tolerance) + " %" : "the seed spread";
    StudyTable t{"Convergence with the cube edge", {"sand", "property", "converged from", "last change", "seed std there"}, {}};
    json conv = json::array();
    for (std::size_t s = 0; s < cases.front().sands.size(); ++s)
        for (Quantity q : kQuantities) {
            std::size_t from = cases.size();  // none yet
            double last_change = std::nan(""), last_std = std::nan("");
            for (std::size_t k = cases.size(); k-- > 1;) {
                const Sample a = cases[k - 1].sample(s, q), b = cases[k].sample(s, q);
                const double change = std::fabs(b.mean - a.mean);
                const double seed_std = std::max(a.std, b.std);
                const double noise = std::max(seed_std, tolerance * std::fabs(b.mean));
                if (k == cases.size() - 1) last_change = change / std::fabs(b.mean), last_std = seed_std / std::fabs(b.mean);
                if (!(change < noise)) break;
                from = k - 1;
            }
            const bool converged = from < cases.size();
            const std::string at = converged ? cases[from].label : "not within the sweep";
            t.rows.push_back({{cases.front().sands[s], label(q), at, fmt_num(100.0 * last_change, 3) + " %",
                               fmt_num(100.0 * last_std, 3) + " %"}});
            conv.push_back({{"sand", cases.front().sands[s]}, {"quantity", to_string(q)}, {"converged", converged},
                            {"from_x", converged ? json(cases[from].x) : json(nullptr)}, {"last_relative_change", number(last_change)},
                            {"relative_seed_std", number(last_std)}, {"tolerance", tolerance}});
            if (q != Quantity::strain)
                result.verdict.push_back(cases.front().sands[s] + ", " + label(q) + ": " +
                                         (converged ? "changes less than " + criterion + " from " + at + " on"
                                                    : "still changes more than " + criterion + " at the largest edge"));
        }
    result.tables.push_back(t);
    result.data["convergence"] = conv;
}

// Error of each cut against the finest (smallest d_min) case, and whether it is within the
// 95 % noise of the two means; cost as particles and wall time per run relative to the finest.
void summarise_truncation(StudyResult& result) {
    const auto& cases = result.cases;
    const StudyCase& finest = cases.front();
    StudyTable t{"Cost against error, relative to the finest cut (" + finest.label + ")",
                 {"smallest grain", "sand", "particles x", "wall time x", "modulus error", "peak error", "strain error", "within noise"}, {}};
    json rows = json::array();
    for (const StudyCase& c : cases)
        for (std::size_t s = 0; s < c.sands.size(); ++s) {
            StudyRow row{{c.label, c.sands[s], fmt_num(c.mean_particles(s) / finest.mean_particles(s), 3),
                          fmt_num(c.mean_wall_seconds(s) / finest.mean_wall_seconds(s), 3)}};
            bool within = true;
            json errors;
            for (Quantity q : kQuantities) {
                const Sample a = c.sample(s, q), f = finest.sample(s, q);
                const double err = a.mean / f.mean - 1.0;
                const double noise = 1.96 * std::sqrt(a.std * a.std / std::max(1, a.n) + f.std * f.std / std::max(1, f.n));
                within = within && std::fabs(a.mean - f.mean) <= noise;
                row.cells.push_back(fmt_num(100.0 * err, 3) + " %");
                errors[to_string(q)] = number(err);
            }
            row.cells.push_back(within ? "yes" : "no");
            t.rows.push_back(row);
            rows.push_back({{"x", c.x}, {"sand", c.sands[s]}, {"particles_ratio", number(c.mean_particles(s) / finest.mean_particles(s))},
                            {"wall_ratio", number(c.mean_wall_seconds(s) / finest.mean_wall_seconds(s))},
                            {"relative_error", errors}, {"within_noise", within}});
        }
    result.tables.push_back(t);
    result.data["truncation"] = rows;
    const StudyCase* coarsest_ok = &finest;
    for (const StudyCase& c : cases) {
        bool ok = true;
        for (const json& r : rows)
            if (r["x"] == c.x && !r["within_noise"].get<bool>()) ok = false;
        if (ok) coarsest_ok = &c;
        else break;
    }
    result.verdict.push_back("the coarsest cut whose modulus, peak and strain stay within the 95 % seed noise of the finest: " +
                             coarsest_ok->label + " (" + fmt_num(coarsest_ok->mean_particles(0) / finest.mean_particles(0), 3) +
                             " x the particles of the finest, first sand)");
}

// One-at-a-time elasticities with common random numbers: each seed's run at the perturbed point
// is paired with the same seed at the calibrated point, so the seed noise largely cancels.
//   log parameter:    e = Δ ln y / Δ ln p      linear parameter:  e = Δ ln y / Δp
void run_sensitivity(const CalibratedPoint& point, StudyRunner& runner, StudyResult& result) {
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
                        e.push_back(std::log(output_of(pert.runs[s][r], q) / output_of(base.runs[s][r], q)) / pert.x);
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
            result.verdict.push_back(std::string(label(q)) + " moves most with " + best + " (|elasticity| " + fmt_num(best_e, 3) + ")");
    }
}

RunCostSummary summarise_costs(const std::vector<RunCost>& runs, const std::string& sand) {
    RunCostSummary c;
    double wall = 0.0, particle_steps = 0.0;
    for (const RunCost& r : runs)
        if (r.sand == sand && r.wall_seconds > 0.0) {
            ++c.runs;
            wall += r.wall_seconds;
            particle_steps += static_cast<double>(r.particles) * static_cast<double>(r.steps);
        }
    c.mean_wall_seconds = c.runs ? wall / c.runs : std::nan("");
    c.particle_steps_per_second = c.runs ? particle_steps / wall : std::nan("");
    return c;
}

double compressive_to_tensile_ratio(double peak_compression_pa, const Sample& tensile_strength_pa) {
    if (!(peak_compression_pa > 0.0) || tensile_strength_pa.n < 1 || !(tensile_strength_pa.mean > 0.0)) return std::nan("");
    return peak_compression_pa / tensile_strength_pa.mean;
}

namespace {

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
    double err[3] = {NAN, NAN, NAN}, sim[3] = {NAN, NAN, NAN}, lab[3] = {NAN, NAN, NAN};
    for (const json& r : j.at("targets")) {
        if (r.value("sand", "") != sand) continue;
        for (Quantity q : kQuantities)
            if (r.value("quantity", "") == to_string(q)) {
                const int k = static_cast<int>(q);
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
                       std::to_string(met) + " of 3", fmt_num(d_sim, 3), fmt_num(d_lab, 3),
                       mean_pm(sigma_t.mean * 1e-6, sigma_t.std * 1e-6, 3) + " (n " + std::to_string(sigma_t.n) + ")",
                       fmt_num(ratio, 3), fmt_num(cost.mean_wall_seconds, 3), fmt_num(cost.particle_steps_per_second, 3)}});
    model["sands"].push_back({{"sand", sand}, {"modulus_error", number(err[0])}, {"peak_error", number(err[1])},
                          {"strain_error", number(err[2])}, {"targets_met", met},
                          {"shape_index_sim", number(d_sim)}, {"shape_index_lab", number(d_lab)},
                          {"peak_compression_mpa", number(sim[1])},
                          {"tensile_strength_mpa", {{"mean", number(sigma_t.mean * 1e-6)}, {"std", number(sigma_t.std * 1e-6)},
                                                    {"n", sigma_t.n}, {"failed", static_cast<int>(tension.runs[s].size()) - sigma_t.n}}},
                          {"compressive_to_tensile_ratio", number(ratio)},
                          {"cost", {{"runs", cost.runs}, {"wall_seconds_per_run", number(cost.mean_wall_seconds)},
                                    {"particle_steps_per_second", number(cost.particle_steps_per_second)}}}});
}

}  // namespace

// model_form: the calibrations of several bond models (or representations) side by side: per
// model and sand the error against the lab on the three targets (met within
// target_tolerance.hpp's tolerances or not), the shape index D = E ε_peak / σ_peak,
// σc/σt from the direct-tension test at the calibrated parameters (the calibration's sands,
// seeds and base cube; through the study's ledger, so a rerun repeats no test), and the cost
// per cube test from the calibration's ledger.
void run_model_form(const std::vector<CalibratedPoint>& calibrations, StudyRunner& runner, StudyResult& result) {
    StudyTable t{"Calibrated models side by side (errors: simulated / lab - 1; cost: the calibration's compression runs, "
                 "wall time with its other runs in flight)",
                 {"model", "summary", "DEM runs", "wall s", "sand", "modulus error", "peak error", "strain error", "targets met",
                  "D sim", "D lab", "sigma_t MPa", "sigma_c/sigma_t", "wall s/run", "particle-steps/s"},
                 {}};
    json models = json::array();
    double best_score = 1e300;
    std::string best;
    std::vector<std::string> all_met, ratios;
    for (const CalibratedPoint& cp : calibrations) {
        const std::filesystem::path& file = cp.summary;
        result.calibration_summaries.push_back(file.string());
        result.representative = result.representative || cp.problem.representative;
        std::ifstream in(file);
        const json j = json::parse(in);
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

}  // namespace gradem::cal
