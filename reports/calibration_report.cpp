#include "reports/calibration_report.hpp"

#include <cmath>
#include <cstdio>
#include <sstream>

#include "calibrate/objective.hpp"
#include "calibrate/rescaling.hpp"
#include "calibrate/target_tolerance.hpp"
#include "common/atomic_file.hpp"
#include "reports/calibrated_config.hpp"
#include "common/clock_text.hpp"
#include "common/json_number.hpp"
#include "common/number_format.hpp"
#include "experiments/config/material_table.hpp"

namespace gradem::report {

using namespace gradem::cal;  // the calibration types these outputs are written from

namespace {

using nlohmann::json;
constexpr auto number = common::json_number<json>;  // a number, or null when it is not finite
using common::clock_text;

/// Display scale and unit of a quantity.
double display(Quantity q) { return q == Quantity::strain ? 1.0 : 1e-6; }
const char* unit(Quantity q) { return q == Quantity::strain ? "-" : "MPa"; }
const char* label(Quantity q) {
    switch (q) {
        case Quantity::modulus: return "chord modulus";
        case Quantity::peak: return "peak stress";
        case Quantity::strain: return "strain at peak";
        case Quantity::tension: return "tensile strength";
    }
    return "?";
}
const char* short_label(Quantity q) {
    return q == Quantity::modulus ? "E" : q == Quantity::peak ? "peak" : q == Quantity::strain ? "eps" : "sigt";
}

std::string fmt(double v, int digits = 4) { return common::format_significant(v, digits); }

/// "modulus and peak within 5 %, strain at peak within 10 %" (target_tolerance.hpp).
std::string tolerances_text() {
    const TargetTolerances& t = kTargetTolerances;
    auto p = [](double v) { return common::format_significant(100.0 * v, 3) + " %"; };
    if (t.modulus == t.peak) return "modulus and peak within " + p(t.modulus) + ", strain at peak within " + p(t.strain);
    return "modulus within " + p(t.modulus) + ", peak within " + p(t.peak) + ", strain at peak within " + p(t.strain);
}

std::string pct(double v) {
    if (!std::isfinite(v)) return "-";
    char buf[32];
    std::snprintf(buf, sizeof buf, "%+.1f %%", 100.0 * v);
    return buf;
}

/// Were the stage's scales set on the scale-up specimens ([scale_up])?
bool scaled_up(const CalibrationStage& st) { return !st.scale_up.point.empty(); }

struct TargetRow {
    std::string stage, sand, role;
    Quantity q;
    TargetStat lab;
    double sim_mean, sim_std;
    int sim_n;
    double rel_error, z;
    double ratio = std::nan("");  ///< tension rows: simulated σc/σt of the sand
    bool met = false;
};

/// Sand s's outcome on the specimens of a target row's role (fitted, predicted, scale-up, validation).
const SandOutcome* role_outcome(const CalibrationStage& st, std::size_t s, const std::string& role) {
    if (role == "validation") return st.validation_outcome(s);
    if (role == "scale-up") return st.scaled_outcome(s);
    return st.outcome(s);
}

std::vector<TargetRow> target_rows(const CalibrationProblem& p, const CalibrationStage& st) {
    std::vector<TargetRow> rows;
    auto add = [&](std::size_t s, const char* role) {
        const std::string r = role;
        const SandOutcome* o = role_outcome(st, s, r);
        for (Quantity q : p.fitted_quantities()) {
            TargetRow r{st.label, p.sands[s], role, q, target_of(p.targets[s], q), std::nan(""), std::nan(""), 0, std::nan(""), std::nan("")};
            if (o && o->count(q) > 0) {
                const int k = static_cast<int>(q);
                r.sim_mean = o->mean[k];
                r.sim_std = o->std[k];
                r.sim_n = o->count(q);
                r.rel_error = r.sim_mean / r.lab.mean - 1.0;
                r.z = z_score(r.sim_mean, r.sim_std, r.sim_n, r.lab);
            }
            if (q == Quantity::tension) {
                if (o && o->ok > 0) r.ratio = o->value(Quantity::peak) / r.sim_mean;
                r.met = tension_met(p.tension, r.rel_error, r.ratio);
            } else {
                r.met = target_met(q, r.rel_error);
            }
            rows.push_back(r);
        }
    };
    for (std::size_t s : st.fitted) add(s, "fitted");
    for (std::size_t s : st.predicted) add(s, "predicted");
    if (scaled_up(st))
        for (std::size_t s : st.fitted) add(s, "scale-up");
    if (p.validation.enabled())
        for (std::size_t s : st.sands()) add(s, "validation");
    return rows;
}

/// The role of the rows that state the stage's result on its own specimens: "scale-up" when the
/// scales were set on the scale-up specimens, else the fit's rows ("fitted", "predicted").
bool is_result_row(const CalibrationStage& st, const std::string& role) {
    return scaled_up(st) ? role == "scale-up" : role == "fitted" || role == "predicted";
}

/// "11, 12, 13".
std::string seeds_text(const std::vector<std::uint64_t>& seeds) {
    std::string text;
    for (std::uint64_t s : seeds) text += (text.empty() ? "" : ", ") + std::to_string(s);
    return text;
}

/// "3.5 mm cubes, packing seeds 11, 12, 13", and "(direct tension on 11)" when the tension tests
/// run on some of them only.
std::string specimens_text(const SpecimenSetSpec& set) {
    std::string text = fmt(set.edge * 1e3, 3) + " mm cubes, packing seeds " + seeds_text(set.seeds);
    if (set.seeds_with_tension().size() < set.seeds.size()) text += " (direct tension on " + seeds_text(set.seeds_with_tension()) + ")";
    return text;
}

std::string validation_specimens_text(const CalibrationProblem& p) { return specimens_text(p.validation); }

/// Does the stage's result hold on the validation specimens (every validation row met)?
bool validation_holds(const std::vector<TargetRow>& rows) {
    bool any = false;
    for (const TargetRow& r : rows)
        if (r.role == "validation") {
            if (!r.met) return false;
            any = true;
        }
    return any;
}

/// E ε / σ: the shape index the homogeneity leaves to the shape parameters.
double shape_index(double e, double sigma, double eps) { return e * eps / sigma; }

/// D of a sand's seed means, and of its lab means.
double outcome_shape_index(const SandOutcome& o) {
    return shape_index(o.value(Quantity::modulus), o.value(Quantity::peak), o.value(Quantity::strain));
}
double lab_shape_index(const SandTargets& t) { return shape_index(t.modulus.mean, t.peak.mean, t.strain.mean); }

/// D = E·ε_peak/σ_peak of a sand: the lab's (from its means) and the simulated one (seed means
/// at the calibrated parameters; NaN if the sand has no successful run).
struct ShapeIndexRow {
    std::string sand, role;
    double lab = 0.0, sim = 0.0;
};

std::vector<ShapeIndexRow> shape_index_rows(const CalibrationProblem& p, const CalibrationStage& st) {
    std::vector<ShapeIndexRow> rows;
    auto add = [&](std::size_t s, const char* role, const SandOutcome* o) {
        rows.push_back({p.sands[s], role, lab_shape_index(p.targets[s]), o && o->ok > 0 ? outcome_shape_index(*o) : std::nan("")});
    };
    for (std::size_t s : st.fitted) add(s, "fitted", st.outcome(s));
    for (std::size_t s : st.predicted) add(s, "predicted", st.outcome(s));
    if (scaled_up(st))
        for (std::size_t s : st.fitted) add(s, "scale-up", st.scaled_outcome(s));
    if (p.validation.enabled())
        for (std::size_t s : st.sands()) add(s, "validation", st.validation_outcome(s));
    return rows;
}

/// The bond model's own parameters (the table rows it does not share with the parallel bond)
/// in the material of the first stage's best point (or the start), config units.
json bond_model_parameters(const CalibrationProblem& p, const CalibrationResult& r) {
    const ParameterSpace space(p.parameters, p.base.material);
    const bool solved = !r.stages.empty() && !r.stages[0].result().empty();
    const exp::MaterialParams m = space.material(solved ? r.stages[0].result() : space.start());
    json out = json::object();
    for (const exp::MaterialParameter& row : exp::material_table())
        if (row.in_config && row.applies_to(p.bond_model()) && !row.applies_to(BondModel::parallel_bond))
            out[std::string(row.key)] = row.integer ? json(row.get_int(m)) : json(exp::config_value(row, m));
    return out;
}

json parameters_json(const CalibrationProblem& p, const CalibrationStage& st) {
    const ParameterSpace space(p.parameters, p.base.material);
    json out = json::array();
    for (const ParameterSpec& spec : space.all()) {
        json j = {{"name", spec.name}, {"unit", spec.unit()}, {"free", spec.free}};
        if (!spec.free) {
            j["value"] = spec.start;
        } else {
            const std::size_t k = *space.index_of(spec.name);
            const std::vector<double>& result = st.result();
            j["value"] = result.empty() ? json(nullptr) : json(result[k]);
            if (scaled_up(st)) j["fit_value"] = st.solution.best[k];  // on the fit's specimens, before the scales were set
            j["start"] = spec.start;
            j["lower"] = spec.lower;
            j["upper"] = spec.upper;
            j["scale"] = spec.log_scale ? "log" : "linear";
            const Uncertainty& u = st.uncertainty;
            if (u.computed) {
                j["std_error"] = spec.log_scale ? json{{"relative", number(u.std_error_natural[k])}}
                                                : json{{"absolute", number(u.std_error_natural[k])}};
                const double moved = scaled_up(st) ? result[k] / st.solution.best[k] : 1.0;  // the interval moves with the scale
                j["one_sigma_interval"] = {number(u.low[k] * moved), number(u.high[k] * moved)};
            }
        }
        out.push_back(j);
    }
    return out;
}

/// The lab's σc/σt of a sand (its peak-stress and tensile-strength means).
double lab_ratio(const CalibrationProblem& p, const std::string& sand) {
    for (const SandTargets& t : p.targets)
        if (t.name == sand) return t.peak.mean / t.tension.mean;
    return std::nan("");
}

/// "σc/σt 10 (assumed, band 8-12; basis ...)" or "σt from the lab's tensile tests".
std::string tension_target_text(const CalibrationProblem& p) {
    const TensionTarget& t = p.tension;
    if (!t.assumed()) return "the lab's tensile strength (tensile_strength_mpa), within " + fmt(100.0 * t.tolerance, 3) + " %";
    return "ASSUMED σc/σt = " + fmt(t.ratio, 3) + " (met within " + fmt(t.ratio_low, 3) + "-" + fmt(t.ratio_high, 3) +
           "; basis: " + t.basis + ")";
}

std::string tension_unmet_statement(const CalibrationProblem& p, const TargetRow& r) {
    std::ostringstream s;
    s << r.sand << " " << label(r.q) << " (" << r.role << "): simulated " << fmt(r.sim_mean * 1e-6) << " MPa, σc/σt = "
      << fmt(r.ratio, 3);
    if (p.tension.assumed())
        s << ", outside the assumed band " << fmt(p.tension.ratio_low, 3) << "-" << fmt(p.tension.ratio_high, 3)
          << " (the target σt = σc,lab/" << fmt(p.tension.ratio, 3) << " = " << fmt(r.lab.mean * 1e-6) << " MPa)";
    else
        s << " vs lab " << fmt(r.lab.mean * 1e-6) << " MPa (" << pct(r.rel_error) << ")";
    if (p.bond_model() == BondModel::parallel_bond)
        s << " - a parallel-bond specimen's σc/σt stays near 2-4 whatever its strengths (Potyondy & Cundall 2004): a model-form "
             "limit, which a law with unbonded (slit or gapped) interfaces addresses (docs/bond_laws.md)";
    return s.str();
}

/// Why a fitted strain at peak misses: the model's D on the fitted specimens against the lab's,
/// and what could have moved it. The scales cannot (homogeneity: E × α, peak × β, strain × β/α
/// keep D), so a law's D is what its shape parameters make it: searched when some are free,
/// as the problem fixes them otherwise; with a strain weight of 0 the strain is reported, not fitted.
std::string fitted_strain_miss(const CalibrationProblem& p, const CalibrationStage& st, std::size_t si) {
    const SandOutcome* so = st.outcome(si);
    if (!so) return "";
    const double d_sim = outcome_shape_index(*so), d_lab = lab_shape_index(p.targets[si]);
    std::ostringstream s;
    s << ". The model cannot meet it: its shape index D = E·ε/σ is " << fmt(d_sim, 3) << " against the lab's " << fmt(d_lab, 3);
    if (p.bond_model() == BondModel::parallel_bond)
        s << " - bonded-particle specimens are near-linear (brittle) to the peak, so with E and peak matched";
    else if (split_by_role(ParameterSpace(p.parameters, p.base.material)).shape.empty())
        s << " - with the " << bond_model_name(p.bond_model())
          << " law's shape parameters as the problem fixes them (none is free; the scales cannot move D) and E and peak matched,";
    else
        s << " - with the " << bond_model_name(p.bond_model()) << " law's shape parameters found and E and peak matched,";
    s << " the strain at peak is D_sim/D_lab = " << pct(d_sim / d_lab - 1.0) << " off; ";
    if (p.weights.strain > 0.0) s << "this is the best compromise the weights allow (model-form error, not an optimiser failure)";
    else s << "the strain weight is 0, so it is reported, not fitted (model-form error, not an optimiser failure)";
    return s.str();
}

/// Why a strain at peak misses on specimens the fit did not run (validation, scale-up): their
/// own D beside the fitted specimens' D and the lab's, and how much the fitted specimens' strain
/// at peak scatters between packing seeds, so a reader can tell a different curve shape on the
/// other specimens from the draw of one packing.
std::string unseen_strain_miss(const CalibrationProblem& p, const CalibrationStage& st, std::size_t si, const TargetRow& r) {
    const SandOutcome* own = role_outcome(st, si, r.role);
    const SandOutcome* fitted = st.outcome(si);
    std::ostringstream s;
    if (r.role == "validation") s << " - on the validation specimens (" << validation_specimens_text(p) << "), which the fit never saw";
    else s << " - on the scale-up specimens (" << specimens_text(p.scale_up) << "), where the scales were set";
    if (!own || !fitted) return s.str();
    s << ": their shape index D = E·ε/σ is " << fmt(outcome_shape_index(*own), 3) << " against " << fmt(outcome_shape_index(*fitted), 3)
      << " on the fitted specimens and the lab's " << fmt(lab_shape_index(p.targets[si]), 3);
    const int k = static_cast<int>(Quantity::strain);
    const int n = fitted->count(Quantity::strain);
    if (n > 1 && fitted->mean[k] > 0.0)
        s << " (the fitted specimens' strain at peak scatters " << fmt(100.0 * fitted->std[k] / fitted->mean[k], 2)
          << " % (standard deviation) between their " << n << " packing seeds; this row is the mean of " << r.sim_n << ")";
    return s.str();
}

std::vector<std::string> unmet_statements(const CalibrationProblem& p, const CalibrationStage& st) {
    std::vector<std::string> out;
    for (const TargetRow& r : target_rows(p, st)) {
        if (!std::isfinite(r.rel_error) || r.met) continue;
        std::ostringstream s;
        if (r.q == Quantity::tension) {
            out.push_back(tension_unmet_statement(p, r));
            continue;
        }
        s << r.sand << " " << label(r.q) << " (" << r.role << "): simulated " << fmt(r.sim_mean * display(r.q)) << " vs lab "
          << fmt(r.lab.mean * display(r.q)) << (r.q == Quantity::strain ? "" : " MPa") << " (" << pct(r.rel_error) << ")";
        if (r.q == Quantity::strain) {
            const auto si = static_cast<std::size_t>(std::find(p.sands.begin(), p.sands.end(), r.sand) - p.sands.begin());
            s << (r.role == "validation" || r.role == "scale-up" ? unseen_strain_miss(p, st, si, r) : fitted_strain_miss(p, st, si));
        } else if (r.role == "validation") {
            s << " - on the validation specimens (" << validation_specimens_text(p)
              << "), which the fit never saw: the calibrated parameters do not hold there";
        } else if (r.role == "scale-up") {
            s << " - at the result on the scale-up specimens (" << specimens_text(p.scale_up)
              << "), where the scales were set: the best rescaling of the fit's shape cannot meet it there";
        } else if (r.role == "predicted") {
            s << " - a prediction, not a fit";
        } else if (p.mode == Mode::joint) {
            s << " - with one parameter set for all sands the model cannot reproduce the lab's difference between the sands in this quantity";
        }
        out.push_back(s.str());
    }
    return out;
}

json noise_floor_json(const CalibrationProblem& p, const double (&floor)[kQuantityCount]) {
    json j = json::object();
    for (Quantity q : p.fitted_quantities()) j[to_string(q)] = number(floor[static_cast<int>(q)]);  // null: not measured
    return j;
}

json stage_json(const CalibrationProblem& p, const CalibrationStage& st) {
    json targets = json::array();
    for (const TargetRow& r : target_rows(p, st)) {
        json t = {{"sand", r.sand}, {"role", r.role}, {"quantity", to_string(r.q)}, {"unit", unit(r.q)},
                  {"lab_mean", number(r.lab.mean * display(r.q))}, {"lab_std", number(r.lab.std * display(r.q))},
                  {"lab_n", r.lab.n}, {"sim_mean", number(r.sim_mean * display(r.q))},
                  {"sim_std", number(r.sim_std * display(r.q))}, {"sim_n", r.sim_n}, {"rel_error", number(r.rel_error)},
                  {"z", number(r.z)}, {"tolerance", r.q == Quantity::tension ? p.tension.tolerance : kTargetTolerances.of(r.q)},
                  {"met", r.met}};
        if (r.q == Quantity::tension) {
            t["assumed"] = p.tension.assumed();
            t["compressive_to_tensile_ratio"] = number(r.ratio);
            if (p.tension.assumed()) t["ratio_band"] = {p.tension.ratio_low, p.tension.ratio_high};
        }
        targets.push_back(t);
    }
    const SolveResult& s = st.solution;
    const Uncertainty& u = st.uncertainty;
    json j = {{"label", st.label},
              {"method", s.method},
              {"stop_reason", s.stop_reason},
              {"budget_exhausted", s.budget_exhausted},
              {"objective", s.best_objective},
              {"best_evaluation", s.best_eval.index},
              {"parameters", parameters_json(p, st)},
              {"targets", targets},
              {"noise_floor_rel_se", noise_floor_json(p, st.noise_floor)},
              {"identifiability", {{"computed", u.computed}, {"note", u.note}, {"singular_values", u.singular_values},
                                   {"condition_number", number(u.condition)}, {"poorly_identified", u.poorly_identified},
                                   {"difference_runs", u.fd_runs}, {"difference_points_reused", u.reused}}},
              {"notes", s.notes},
              {"unmet_targets", unmet_statements(p, st)}};
    json d = json::array();
    for (const ShapeIndexRow& row : shape_index_rows(p, st))
        d.push_back({{"sand", row.sand}, {"role", row.role}, {"lab", number(row.lab)}, {"simulated", number(row.sim)},
                     {"rel_error", number(row.sim / row.lab - 1.0)}});
    j["shape_index_d"] = d;
    if (s.homogeneity.done)
        j["homogeneity"] = {{"holds", s.homogeneity.holds}, {"alpha", s.homogeneity.alpha}, {"beta", s.homogeneity.beta},
                            {"modulus_deviation", s.homogeneity.modulus_deviation}, {"peak_deviation", s.homogeneity.peak_deviation},
                            {"strain_deviation", s.homogeneity.strain_deviation}, {"tolerance", p.solver.homogeneity_tolerance}};
    if (s.homogeneity.done && p.tension.fitted()) j["homogeneity"]["tension_deviation"] = number(s.homogeneity.tension_deviation);
    if (!st.prediction.sands.empty() && st.prediction.failed) j["prediction_failure"] = st.prediction.failure;
    if (p.scale_up.enabled()) {
        const StageScaleUp& u = st.scale_up;
        j["scale_up"] = {{"edge_mm", p.scale_up.edge * 1e3}, {"seeds", p.scale_up.seeds}, {"runs", u.runs},
                         {"from_ledger", u.from_ledger}, {"done", scaled_up(st)}, {"alpha", number(u.scales.alpha)},
                         {"beta", number(u.scales.beta)}, {"noise_floor_rel_se", noise_floor_json(p, u.noise_floor)},
                         {"note", u.note}};
    }
    if (p.validation.enabled()) {
        const StageValidation& v = st.validation;
        j["validation"] = {{"edge_mm", p.validation.edge * 1e3}, {"seeds", p.validation.seeds}, {"runs", v.runs},
                           {"from_ledger", v.from_ledger}, {"holds", validation_holds(target_rows(p, st))},
                           {"failed", v.evaluation.failed}, {"failure", v.evaluation.failure}, {"note", v.note}};
        if (p.tension.fitted())  // the seeds whose direct-tension test ran
            j["validation"]["tension_seeds"] = p.validation.seeds_with_tension();
    }
    return j;
}

/// A part's StageCost: runs made now with their particle-steps and worker-seconds, runs served.
json stage_cost_json(const StageCost& c) {
    return {{"runs_now", c.executed},
            {"particle_steps", c.particle_steps},
            {"worker_seconds", c.worker_seconds},
            {"from_ledger", c.from_ledger},
            {"ledger_particle_steps", c.ledger_particle_steps}};
}

/// "12 runs, 1.23e+09 particle-steps, 345 worker-s (3 from the ledger, 2.1e+08 particle-steps)".
std::string stage_cost_text(const StageCost& c) {
    std::string t = std::to_string(c.executed) + (c.executed == 1 ? " run, " : " runs, ") + fmt(c.particle_steps, 3) +
                    " particle-steps, " + fmt(c.worker_seconds, 3) + " worker-s";
    if (c.from_ledger) t += " (" + std::to_string(c.from_ledger) + " from the ledger, " + fmt(c.ledger_particle_steps, 3) + " particle-steps)";
    return t;
}

json tension_target_json(const CalibrationProblem& p) {
    const TensionTarget& t = p.tension;
    json j = {{"source", to_string(t.source)}};
    if (!t.fitted()) return j;
    j["weight"] = p.weights.tension;
    if (t.assumed()) {
        j["assumed"] = true;
        j["compressive_to_tensile_ratio"] = t.ratio;
        j["ratio_band"] = {t.ratio_low, t.ratio_high};
        j["basis"] = t.basis;
    } else {
        j["assumed"] = false;
        j["tolerance"] = t.tolerance;
    }
    return j;
}

/// The stage's validation first: fitted and validation errors side by side, and a plain verdict.
void validation_markdown(std::ostringstream& md, const CalibrationProblem& p, const CalibrationStage& st) {
    const std::vector<TargetRow> rows = target_rows(p, st);
    md << "**Validation** on " << validation_specimens_text(p) << " (" << st.validation.runs << " runs, "
       << st.validation.from_ledger << " from the ledger): ";
    if (!st.validation.note.empty()) md << st.validation.note << ".\n\n";
    else if (st.validation.evaluation.failed) md << "a run failed (" << st.validation.evaluation.failure << ").\n\n";
    else if (validation_holds(rows)) md << "every target holds on specimens the fit never saw.\n\n";
    else md << "**the result does NOT hold on specimens the fit never saw** (rows marked no below).\n\n";
    md << "| sand | target | " << (scaled_up(st) ? "scale-up" : "fitted") << " rel. error | validation rel. error | validation met |\n"
       << "|---|---|---|---|---|\n";
    for (const TargetRow& v : rows) {
        if (v.role != "validation") continue;
        double fitted = std::nan("");
        for (const TargetRow& f : rows)
            if (is_result_row(st, f.role) && f.sand == v.sand && f.q == v.q) fitted = f.rel_error;
        md << "| " << v.sand << " | " << label(v.q) << " | " << pct(fitted) << " | " << pct(v.rel_error) << " | "
           << (v.met ? "yes" : "no") << " |\n";
    }
    md << "\n";
}

/// Where the stage's scales were set: the specimens, α and β, and the fit's point against the result.
void scale_up_markdown(std::ostringstream& md, const CalibrationProblem& p, const CalibrationStage& st) {
    const StageScaleUp& u = st.scale_up;
    md << "**Scales set** on " << specimens_text(p.scale_up) << " (" << u.runs << " runs, " << u.from_ledger
       << " from the ledger): ";
    if (!scaled_up(st)) {
        md << u.note << ".\n\n";
        return;
    }
    md << "the fit's point run there once, then moduli × " << fmt(u.scales.alpha) << " and strengths × " << fmt(u.scales.beta)
       << " (the closed-form rescaling: E × α, strengths × β, strain at peak × β/α). The result below is that point; its "
          "scale-up rows are the runs rescaled, its validation rows are run.\n\n";
    md << "| sand | target | fitted (fit's specimens, fit's point) | scale-up, fit's point (run) | scale-up, result |\n"
          "|---|---|---|---|---|\n";
    const std::vector<TargetRow> rows = target_rows(p, st);
    for (const TargetRow& r : rows) {
        if (r.role != "scale-up") continue;
        double fitted = std::nan(""), measured = std::nan("");
        for (const TargetRow& f : rows)
            if (f.role == "fitted" && f.sand == r.sand && f.q == r.q) fitted = f.rel_error;
        for (const SandOutcome& o : u.measured.sands)
            if (p.sands[o.sand] == r.sand && o.count(r.q) > 0) measured = o.mean[static_cast<int>(r.q)] / r.lab.mean - 1.0;
        md << "| " << r.sand << " | " << label(r.q) << " | " << pct(fitted) << " | " << pct(measured) << " | " << pct(r.rel_error)
           << " |\n";
    }
    md << "\n";
}

}  // namespace

json summary_json(const CalibrationProblem& p, const CalibrationResult& r) {
    json stages = json::array(), all_targets = json::array(), all_d = json::array();
    for (const CalibrationStage& st : r.stages) {
        stages.push_back(stage_json(p, st));
        for (auto t : stages.back()["targets"]) {
            t["stage"] = st.label;
            all_targets.push_back(t);
        }
        for (auto d : stages.back()["shape_index_d"]) {
            d["stage"] = st.label;
            all_d.push_back(d);
        }
    }
    json seeds = p.seeds, seeds_by_sand = json::object(), tension_seeds_by_sand = json::object();
    for (std::size_t s = 0; s < p.sands.size(); ++s) {
        seeds_by_sand[p.sands[s]] = p.seeds_of(s);
        if (p.tension.fitted()) tension_seeds_by_sand[p.sands[s]] = p.tension_seeds_of(s);  // the fit's tension tests
    }
    return {{"schema", "gradem-calibration/1"},
            {"config", p.file.string()},
            {"model", to_string(p.model)},
            {"bond_model", bond_model_name(p.bond_model())},
            {"bond_model_parameters", bond_model_parameters(p, r)},
            {"mode", to_string(p.mode)},
            {"solver", to_string(p.solver.method)},
            {"sands", p.sands},
            {"packing_seeds", seeds},
            {"packing_seeds_by_sand", seeds_by_sand},
            {"tension_seeds_by_sand", tension_seeds_by_sand},
            {"specimen_edge_mm", p.base.specimen.genesis.edge * 1e3},
            {"lab_results", p.lab_results.string()},
            {"representative_lab_data", p.representative},
            {"lab_note", p.lab_note},
            {"dem_test_runs", r.runs_used},
            {"runs", {{"total", r.runs_used}, {"executed_now", r.runs_executed}, {"from_ledger", r.runs_from_ledger},
                      {"failed", r.runs_failed}, {"budget", p.solver.max_runs}, {"scale_up", r.scale_up_runs},
                      {"validation", r.validation_runs},
                      {"cost", {{"fit", stage_cost_json(r.fit_cost)},
                                {"scale_up", stage_cost_json(r.scale_up_cost)},
                                {"validation", stage_cost_json(r.validation_cost)}}}}},
            {"evaluations", r.history.size()},
            {"wall_seconds", r.wall_seconds},
            {"ledger", p.ledger.string()},
            {"problem_fingerprint", r.fingerprint},
            {"code_version", code_version()},
            {"parameters", stages.empty() ? json::array() : stages[0]["parameters"]},
            {"targets", all_targets},
            {"shape_index_d", all_d},
            {"target_tolerances", {{"modulus", kTargetTolerances.modulus}, {"peak_stress", kTargetTolerances.peak},
                                   {"strain_at_peak", kTargetTolerances.strain}, {"source", "calibrate/target_tolerance.hpp: modulus and peak within 5 %, strain at peak within 10 %"}}},
            {"tension_target", tension_target_json(p)},
            {"stages", stages}};
}

namespace {

// --- summary.md, one part per function ----------------------------------------------------

void header_markdown(std::ostringstream& md, const CalibrationProblem& p, const CalibrationResult& r) {
    md << "# gradem calibration: " << p.file.filename().string() << "\n\n";
    if (p.representative)
        md << "> **The lab data are REPRESENTATIVE, not measurements.** " << p.lab_note << "\n\n";
    md << "- mode **" << to_string(p.mode) << "**, solver **" << to_string(p.solver.method) << "**, model " << to_string(p.model)
       << ", bond model **" << bond_model_name(p.bond_model()) << "**";
    std::string sep = " (";
    const json law = bond_model_parameters(p, r);
    for (const auto& [key, value] : law.items()) {
        md << sep << key << " = " << fmt(value.get<double>());
        sep = ", ";
    }
    md << (sep == ", " ? ")" : "") << "\n"
       << "- sands: ";
    for (std::size_t s = 0; s < p.sands.size(); ++s) md << (s ? ", " : "") << p.sands[s];
    md << "; packing seeds per sand: ";
    for (std::size_t s = 0; s < p.sands.size(); ++s)
        if (s == 0 || p.seeds_of(s) != p.seeds_of(0)) md << (s ? ", " + p.sands[s] + " " : "") << p.seeds_of(s).size();
    md << " (the same packings for every parameter set)";
    if (p.tension.fitted() && !p.tension_seeds.empty()) md << "; direct tension on seed" << (p.tension_seeds.size() > 1 ? "s " : " ")
                                                            << seeds_text(p.tension_seeds) << " of each sand";
    md << "; specimen edge " << fmt(p.base.specimen.genesis.edge * 1e3) << " mm\n"
       << "- DEM test runs: **" << r.runs_used << "** of a budget of " << p.solver.max_runs << " (" << r.runs_executed
       << " run now, " << r.runs_from_ledger << " from the ledger, " << r.runs_failed << " failed); " << r.history.size()
       << " evaluations; wall time " << clock_text(r.wall_seconds) << "\n"
       << "- cost: fit " << stage_cost_text(r.fit_cost);
    if (p.scale_up.enabled()) md << "; scale-up " << stage_cost_text(r.scale_up_cost);
    if (p.validation.enabled()) md << "; validation " << stage_cost_text(r.validation_cost);
    md << "\n";
    if (p.validation.enabled())
        md << "- validation specimens: " << validation_specimens_text(p) << " (" << r.validation_runs
           << " runs after the fit, apart from the budget)\n";
    md << "- targets: " << p.lab_results.string() << "; weights: modulus " << p.weights.modulus << ", peak " << p.weights.peak
       << ", strain " << p.weights.strain;
    if (p.tension.fitted()) md << ", tension " << p.weights.tension << "\n- direct-tension target: " << tension_target_text(p);
    md << "\n\n";
}

void homogeneity_markdown(std::ostringstream& md, const SolveResult& s) {
    if (s.homogeneity.done)
        md << "Homogeneity check on the actual specimens (moduli × " << fmt(s.homogeneity.alpha) << ", strengths × "
           << fmt(s.homogeneity.beta) << "): predicted vs run E " << pct(s.homogeneity.modulus_deviation) << ", peak "
           << pct(s.homogeneity.peak_deviation) << ", strain " << pct(s.homogeneity.strain_deviation)
           << (std::isfinite(s.homogeneity.tension_deviation) ? ", tension " + pct(s.homogeneity.tension_deviation) : "") << " - "
           << (s.homogeneity.holds ? "holds" : "does not hold") << ".\n\n";
}

void parameters_markdown(std::ostringstream& md, const CalibrationProblem& p, const CalibrationStage& st) {
    md << "| parameter | value | ± 1 s.e. | bounds | free |\n|---|---|---|---|---|\n";
    const ParameterSpace space(p.parameters, p.base.material);
    for (const ParameterSpec& spec : space.all()) {
        if (!spec.free) {
            md << "| " << spec.name << " | " << fmt(spec.start) << " " << spec.unit() << " | | | fixed |\n";
            continue;
        }
        const std::size_t k = *space.index_of(spec.name);
        const double v = st.result().empty() ? std::nan("") : st.result()[k];
        std::string se = "-";
        if (st.uncertainty.computed)
            se = spec.log_scale ? pct(st.uncertainty.std_error_natural[k]).substr(1) : fmt(st.uncertainty.std_error_natural[k], 3);
        md << "| " << spec.name << " | " << fmt(v) << " " << spec.unit() << " | " << se << " | [" << fmt(spec.lower) << ", "
           << fmt(spec.upper) << "] " << (spec.log_scale ? "log" : "linear") << " | free |\n";
    }
}

void targets_markdown(std::ostringstream& md, const CalibrationProblem& p, const CalibrationStage& st) {
    md << "\n| sand | target | role | lab mean ± std | simulated mean ± seed spread | rel. error | z |\n"
          "|---|---|---|---|---|---|---|\n";
    for (const TargetRow& row : target_rows(p, st))
        md << "| " << row.sand << " | " << label(row.q) << " [" << unit(row.q) << "] | " << row.role << " | "
           << fmt(row.lab.mean * display(row.q))
           << (row.q == Quantity::tension && p.tension.assumed() ? " (assumed: σc,lab/" + fmt(p.tension.ratio, 3) + ")"
                                                                 : " ± " + fmt(row.lab.std * display(row.q), 2))
           << " | "
           << fmt(row.sim_mean * display(row.q)) << " ± " << fmt(row.sim_std * display(row.q), 2) << " | " << pct(row.rel_error)
           << " | " << fmt(row.z, 2) << " |\n";
}

void shape_index_markdown(std::ostringstream& md, const CalibrationProblem& p, const CalibrationStage& st) {
    md << "\n| sand | role | D = E·ε_peak/σ_peak lab | D simulated | rel. error |\n|---|---|---|---|---|\n";
    for (const ShapeIndexRow& row : shape_index_rows(p, st))
        md << "| " << row.sand << " | " << row.role << " | " << fmt(row.lab, 3) << " | " << fmt(row.sim, 3) << " | "
           << pct(row.sim / row.lab - 1.0) << " |\n";
}

/// A noise floor as a percentage, or why there is none (measure_noise: one seed per sand).
std::string noise_text(double floor) { return std::isfinite(floor) ? pct(floor).substr(1) : "not measured (one seed)"; }

void noise_floor_line(std::ostringstream& md, const CalibrationProblem& p, const double (&floor)[kQuantityCount]) {
    md << "modulus " << noise_text(floor[0]) << ", peak " << noise_text(floor[1]) << ", strain " << noise_text(floor[2]);
    if (p.tension.fitted()) md << ", tension " << noise_text(floor[static_cast<int>(Quantity::tension)]);
}

void noise_floor_markdown(std::ostringstream& md, const CalibrationProblem& p, const CalibrationStage& st) {
    md << "\nNoise floor (relative standard error of the seed mean): ";
    noise_floor_line(md, p, st.noise_floor);
    if (scaled_up(st)) {
        md << " on the fit's specimens; ";
        noise_floor_line(md, p, st.scale_up.noise_floor);
        md << " on the scale-up specimens, where the scales were set";
    }
    md << ".\n\n";
}

void tension_ratio_markdown(std::ostringstream& md, const CalibrationProblem& p, const CalibrationStage& st) {
    if (p.tension.fitted()) {
        md << "| sand | role | σc/σt simulated | " << (p.tension.assumed() ? "assumed band" : "lab") << " | met |\n|---|---|---|---|---|\n";
        for (const TargetRow& row : target_rows(p, st))
            if (row.q == Quantity::tension)
                md << "| " << row.sand << " | " << row.role << " | " << fmt(row.ratio, 3) << " | "
                   << (p.tension.assumed() ? fmt(p.tension.ratio_low, 3) + "-" + fmt(p.tension.ratio_high, 3)
                                           : fmt(lab_ratio(p, row.sand), 3))
                   << " | " << (row.met ? "yes" : "no") << " |\n";
        md << "\n";
    }
}

void identifiability_markdown(std::ostringstream& md, const CalibrationStage& st) {
    const Uncertainty& u = st.uncertainty;
    if (u.computed) {
        md << "Identifiability: singular values of the lab-normalised Jacobian (unit-box columns) ";
        for (std::size_t k = 0; k < u.singular_values.size(); ++k) md << (k ? ", " : "") << fmt(u.singular_values[k], 3);
        md << "; condition number " << (std::isfinite(u.condition) ? fmt(u.condition, 3) : "infinite (rank-deficient)") << ".";
        if (u.poorly_identified.empty()) md << " Every free parameter is pinned down by the targets.\n\n";
        else {
            md << " **The data cannot pin down:**\n\n";
            for (const auto& w : u.poorly_identified) md << "- " << w << "\n";
            md << "\n";
        }
        for (const auto& r : u.reused) md << "- standard error of " << r << "\n";
        if (!u.reused.empty()) md << "\n";
    } else {
        md << "Uncertainty: " << u.note << "\n\n";
    }
}

void unmet_markdown(std::ostringstream& md, const CalibrationProblem& p, const CalibrationStage& st) {
    const auto unmet = unmet_statements(p, st);
    const std::string rules = tolerances_text() + (p.tension.fitted() ? "; tension: " + tension_target_text(p) : "");
    if (unmet.empty()) md << "Every target is met (" << rules << " of the lab mean).\n\n";
    else {
        md << "**Targets not met (" << rules << "):**\n\n";
        for (const auto& w : unmet) md << "- " << w << "\n";
        md << "\n";
    }
}

}  // namespace

std::string summary_markdown(const CalibrationProblem& p, const CalibrationResult& r) {
    std::ostringstream md;
    header_markdown(md, p, r);
    for (const CalibrationStage& st : r.stages) {
        const SolveResult& s = st.solution;
        md << "## " << st.label << "\n\n";
        if (p.validation.enabled()) validation_markdown(md, p, st);
        if (p.scale_up.enabled()) scale_up_markdown(md, p, st);
        md << "Solver path: " << s.method << "; stop: " << s.stop_reason << "; objective Σr² = " << fmt(s.best_objective) << "\n\n";
        homogeneity_markdown(md, s);
        parameters_markdown(md, p, st);
        targets_markdown(md, p, st);
        shape_index_markdown(md, p, st);
        noise_floor_markdown(md, p, st);
        tension_ratio_markdown(md, p, st);
        identifiability_markdown(md, st);
        unmet_markdown(md, p, st);
        for (const auto& n : s.notes) md << "- note: " << n << "\n";
    }
    return md.str();
}

std::string convergence_csv(const CalibrationProblem& p, const CalibrationResult& r) {
    const ParameterSpace space(p.parameters, p.base.material);
    std::ostringstream c;
    c.precision(10);
    c << "evaluation,label,runs_used,wall_seconds,objective,failed";
    for (std::size_t k = 0; k < space.size(); ++k) c << "," << space.free(k).name;
    for (const auto& sand : p.sands)
        for (Quantity q : p.fitted_quantities()) c << ",\"" << sand << " " << to_string(q) << (q == Quantity::strain ? "" : "_mpa") << "\"";
    c << "\n";
    for (const Evaluation& e : r.history) {
        c << e.index << "," << e.label << "," << e.runs_used << "," << e.seconds << "," << objective(e, p) << ","
          << (e.failed ? 1 : 0);
        for (double v : e.values) c << "," << v;
        for (std::size_t s = 0; s < p.sands.size(); ++s)
            for (Quantity q : p.fitted_quantities()) {
                c << ",";
                for (const SandOutcome& o : e.sands)
                    if (o.sand == s && std::isfinite(o.value(q))) c << o.value(q) * display(q);
            }
        c << "\n";
    }
    return c.str();
}

std::string curves_csv(const CalibrationProblem& p, const CalibrationResult& r) {
    std::ostringstream c;
    c.precision(8);
    c << "stage,sand,source,seed,strain,stress_mpa\n";
    for (const CalibrationStage& st : r.stages) {
        std::vector<std::size_t> sands = st.fitted;
        sands.insert(sands.end(), st.predicted.begin(), st.predicted.end());
        for (std::size_t s : sands) {
            // The result's curves: on the scale-up specimens (rescaled) when the scales were set there.
            const bool up = scaled_up(st) && st.scaled_outcome(s);
            if (const Evaluation* e = up ? &st.scale_up.prediction : st.evaluation_of(s)) {
                std::size_t run = 0;
                for (std::size_t k = 0; k < e->sands.size(); ++k) {
                    for (std::uint64_t seed : up ? p.scale_up.seeds : p.seeds_of(e->sands[k].sand)) {
                        const RunOutcome& o = e->runs[run++];
                        if (e->sands[k].sand != s) continue;
                        for (std::size_t i = 0; i < o.curve_strain.size(); ++i)
                            c << "\"" << st.label << "\",\"" << p.sands[s] << "\",simulated," << seed << "," << o.curve_strain[i]
                              << "," << o.curve_stress_pa[i] * 1e-6 << "\n";
                    }
                }
            }
            // The lab's mean curve: Popovics (1973) through the lab means,
            // σ = σp (ε/εp) n / (n − 1 + (ε/εp)^n), n = E / (E − σp/εp).
            const SandTargets& t = p.targets[s];
            const double secant = t.peak.mean / t.strain.mean;
            if (t.modulus.mean > secant) {
                const double n = t.modulus.mean / (t.modulus.mean - secant);
                for (int i = 1; i <= 75; ++i) {
                    const double x = 1.5 * i / 75.0;
                    c << "\"" << st.label << "\",\"" << p.sands[s] << "\",lab_mean_popovics,," << x * t.strain.mean << ","
                      << t.peak.mean * x * n / (n - 1.0 + std::pow(x, n)) * 1e-6 << "\n";
                }
            }
        }
    }
    return c.str();
}

namespace {
/// The one-line result marks each target outside its tolerance, so a reader sees which miss.
const char* miss_mark(const TargetRow& row) { return row.met ? "" : " (miss)"; }
}  // namespace

std::string brief_report(const CalibrationProblem& p, const CalibrationResult& r) {
    std::ostringstream b;
    b << "calibrate: " << to_string(p.mode) << "/" << to_string(p.solver.method) << ", " << r.runs_used << " DEM runs ("
      << r.runs_from_ledger << " from ledger), " << clock_text(r.wall_seconds);
    for (const CalibrationStage& st : r.stages) {
        b << " | " << st.label << ":";
        if (p.validation.enabled()) {
            const std::vector<TargetRow> rows = target_rows(p, st);
            b << " validation " << (validation_holds(rows) ? "holds" : "MISSES");
            for (const TargetRow& row : rows)
                if (row.role == "validation" && std::isfinite(row.rel_error))
                    b << " " << row.sand << " " << short_label(row.q) << " " << pct(row.rel_error) << miss_mark(row);
            b << ";";
        }
        const ParameterSpace space(p.parameters, p.base.material);
        for (std::size_t k = 0; k < space.size() && !st.result().empty(); ++k)
            b << " " << space.free(k).name << "=" << fmt(st.result()[k], 3);
        if (scaled_up(st)) b << " (scales set on " << fmt(p.scale_up.edge * 1e3, 3) << " mm cubes)";
        for (const TargetRow& row : target_rows(p, st))
            if (std::isfinite(row.rel_error) && is_result_row(st, row.role))
                b << "; " << row.sand << " " << short_label(row.q) << " " << pct(row.rel_error)
                  << (row.q == Quantity::tension ? " (sigc/sigt " + fmt(row.ratio, 3) + ")" : "") << miss_mark(row);
    }
    return b.str();
}

void write_calibration_outputs(const CalibrationProblem& p, const CalibrationResult& r) {
    common::write_file_atomically(p.out_dir / "summary.json", summary_json(p, r).dump(2) + "\n");
    common::write_file_atomically(p.out_dir / "summary.md", summary_markdown(p, r));
    common::write_file_atomically(p.out_dir / "convergence.csv", convergence_csv(p, r));
    common::write_file_atomically(p.out_dir / "curves.csv", curves_csv(p, r));
    if (p.base_file.empty()) return;  // a problem built in code (tests) has no base file to copy
    common::write_files_atomically(calibrated_cube_configs(p, r));
}

}  // namespace gradem::report
