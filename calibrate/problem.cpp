#include "calibrate/problem.hpp"

#include "calibrate/cube_model.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numeric>
#include <fstream>
#include <nlohmann/json.hpp>
#include <optional>
#include <set>
#include <sstream>

#include "common/input_error.hpp"
#include "common/json_file.hpp"
#include "common/json_number.hpp"
#include "common/toml_section.hpp"
#include "experiments/config/material_table.hpp"

namespace gradem::cal {
namespace {

namespace fs = std::filesystem;
using common::InputError;
using namespace common::toml_io;

const std::vector<std::string> kTables = {"calibration", "targets", "parameters", "solver", "run", "scale_up", "validation", "output"};
const std::vector<std::string> kDefaultFree = {"effective_modulus_gpa", "tensile_strength_mpa", "cohesion_ratio", "strength_cv"};

std::vector<std::string> read_strings(Section& s, const char* key, std::vector<std::string> fallback) {
    const toml::node* n = s.node(key);
    if (!n) return fallback;
    if (!n->is_array()) s.type_error(key, *n, "an array of strings");
    std::vector<std::string> out;
    for (const toml::node& item : *n->as_array()) {
        if (!item.is_string()) s.type_error(key, *n, "an array of strings");
        out.push_back(item.as_string()->get());
    }
    s.record(key, *n, false);
    return out;
}

/// A seed list as written: into `out`, or what it should have been ("a non-empty array of
/// positive integers", "distinct seeds").
std::optional<std::string> parse_seed_list(const toml::node& n, std::vector<std::uint64_t>& out) {
    const char* not_a_list = "a non-empty array of positive integers";
    if (!n.is_array() || n.as_array()->empty()) return not_a_list;
    for (const toml::node& item : *n.as_array()) {
        if (!item.is_integer() || item.as_integer()->get() < 1) return not_a_list;
        const auto v = static_cast<std::uint64_t>(item.as_integer()->get());
        if (std::find(out.begin(), out.end(), v) != out.end()) return "distinct seeds";
        out.push_back(v);
    }
    return std::nullopt;
}

std::vector<std::uint64_t> read_seeds(Section& s, const char* key, std::vector<std::uint64_t> fallback) {
    const toml::node* n = s.node(key);
    if (!n) return fallback;
    std::vector<std::uint64_t> out;
    if (const auto expected = parse_seed_list(*n, out)) s.type_error(key, *n, *expected);
    s.record(key, *n, false);
    return out;
}

// [calibration] sand_seeds = { "Van Buren" = [1, 2, 3, 5, 6] }: a sand's own packing seeds,
// replacing calibration.seeds for it (a sand whose small cubes scatter more gets more seeds;
// docs/calibration.md "The noise floor").
void read_sand_seeds(Context& ctx, const toml::node& node, CalibrationProblem& p) {
    const int line = line_of(node);
    if (!node.is_table())
        throw InputError(ctx.file, line, "key 'calibration.sand_seeds' = " + show(node) +
                                             ": expected a table of sand names to seed lists, e.g. { \"Van Buren\" = [1, 2, 3, 5, 6] }");
    p.sand_seeds.assign(p.sands.size(), {});
    for (auto&& [key, value] : *node.as_table()) {
        const std::string sand(key.str());
        const auto at = std::find(p.sands.begin(), p.sands.end(), sand);
        const std::string where = "key 'calibration.sand_seeds.\"" + sand + "\"'";
        if (at == p.sands.end()) throw InputError(ctx.file, line_of(value), where + ": \"" + sand + "\" is not one of calibration.sands");
        std::vector<std::uint64_t>& list = p.sand_seeds[static_cast<std::size_t>(at - p.sands.begin())];
        if (const auto expected = parse_seed_list(value, list))
            throw InputError(ctx.file, line_of(value), where + " = " + show(value) + ": expected " + *expected);
    }
}

// [calibration] edge_mm: the specimen edge of every run, replacing the base config's
// genesis.edge_mm (the same base serves calibrations at several specimen sizes).
void apply_edge(Context& ctx, double edge, exp::CubeConfig& base) {
    const int line = ctx.keys["calibration.edge_mm"].line;
    if (!(edge > 0.0) || !std::isfinite(edge))
        throw InputError(ctx.file, line, "key 'calibration.edge_mm' must be a positive cube edge [mm]");
    base.specimen.genesis.edge = edge;
    if (const auto why = base.specimen.invalid_reason())
        throw InputError(ctx.file, line, "key 'calibration.edge_mm': " + *why);
}

// [calibration] stop_fraction and stop_strain_ratio: where every platen test of the calibration
// stops after its peak (stress under stop_fraction × the peak; gauge strain past
// stop_strain_ratio × its value at the peak), replacing the base config's test keys of the same
// names: the targets are at or before the peak, so a calibration need not follow the softening
// as far as a study.
void apply_stop_rule(Context& ctx, const std::string& key, double exp::PlatenTestSpec::*field, double value,
                     exp::CubeConfig& base) {
    base.test.loading.*field = value;
    if (auto why = base.test.loading.invalid_reason())
        throw InputError(ctx.file, ctx.keys["calibration." + key].line, "key 'calibration." + key + "' = " + show(value) + ": " + *why);
}

// [calibration] paste_diameter_mm: one coarse-grained paste size for every run, replacing the
// base config's paste.min/max_diameter_mm (explicit-paste bases only; the same base serves
// calibrations at several paste sizes).
void apply_paste_diameter(Context& ctx, double diameter, exp::CubeConfig& base) {
    const int line = ctx.keys["calibration.paste_diameter_mm"].line;
    if (!base.specimen.paste)
        throw InputError(ctx.file, line,
                         std::string("key 'calibration.paste_diameter_mm' needs a base config with specimen.representation = "
                                     "\"explicit_paste\" (it is \"") + to_string(base.representation) + "\")");
    if (!(diameter > 0.0) || !std::isfinite(diameter))
        throw InputError(ctx.file, line, "key 'calibration.paste_diameter_mm' must be a positive paste particle diameter [mm]");
    exp::PasteSpec& paste = base.specimen.paste->paste;
    paste.min_diameter = paste.max_diameter = diameter;
    if (const auto why = paste.invalid_reason())
        throw InputError(ctx.file, line, "key 'calibration.paste_diameter_mm': " + *why);
}

void read_calibration(Context& ctx, const toml::table& root, CalibrationProblem& p) {
    Section s(ctx, root, "calibration");
    fs::path base;
    s.path("base", base);
    s.choice("model", p.model);
    s.choice("mode", p.mode);
    p.sands = read_strings(s, "sands", {"pre-blended", "Van Buren"});
    s.text("calibrate_on", p.calibrate_on);
    p.seeds = read_seeds(s, "seeds", p.seeds);
    const toml::node* sand_seeds = s.node("sand_seeds");
    p.tension_seeds = read_seeds(s, "tension_seeds", {});
    std::string bond_model;
    s.text("bond_model", bond_model);
    double edge = 0.0;  // [m] 0: the base config's genesis.edge_mm
    s.real("edge_mm", edge, 1e-3);
    double paste_diameter = 0.0;  // [m] 0: the base config's paste size
    s.real("paste_diameter_mm", paste_diameter, 1e-3);
    double stop_fraction = 0.0;  // [-] 0: the base config's test.stop_fraction
    s.real("stop_fraction", stop_fraction);
    double stop_strain_ratio = 0.0;  // [-] absent: the base config's test.stop_strain_ratio
    s.real("stop_strain_ratio", stop_strain_ratio);
    s.finish();
    if (base.empty()) throw InputError(ctx.file, 0, "key 'calibration.base' is required: the cube config (specimen, start material, test)");
    if (!fs::exists(base))
        throw InputError(ctx.file, ctx.keys["calibration.base"].line, "key 'calibration.base': file " + base.string() + " not found");
    p.base = exp::load_cube_config(base);
    p.base_file = base;
    if (!bond_model.empty()) {  // overrides the base config's [material] model
        const auto model = parse_bond_model(bond_model);
        if (!model)
            throw InputError(ctx.file, ctx.keys["calibration.bond_model"].line,
                             "key 'calibration.bond_model' = \"" + bond_model + "\": unknown bond model (known: " +
                                 exp::bond_model_names() + ")");
        p.base.material.bond.model = *model;
    }
    if (ctx.keys["calibration.edge_mm"].line > 0) apply_edge(ctx, edge, p.base);
    if (ctx.keys["calibration.paste_diameter_mm"].line > 0) apply_paste_diameter(ctx, paste_diameter, p.base);
    if (ctx.keys["calibration.stop_fraction"].line > 0)
        apply_stop_rule(ctx, "stop_fraction", &exp::PlatenTestSpec::stop_fraction, stop_fraction, p.base);
    if (ctx.keys["calibration.stop_strain_ratio"].line > 0)
        apply_stop_rule(ctx, "stop_strain_ratio", &exp::PlatenTestSpec::stop_strain_ratio, stop_strain_ratio, p.base);
    if (p.sands.empty()) throw InputError(ctx.file, ctx.keys["calibration.sands"].line, "key 'calibration.sands' is empty");
    const std::set<std::string> unique(p.sands.begin(), p.sands.end());
    if (unique.size() != p.sands.size())
        throw InputError(ctx.file, ctx.keys["calibration.sands"].line, "key 'calibration.sands' names a sand twice");
    if (sand_seeds) read_sand_seeds(ctx, *sand_seeds, p);
    if (p.mode == Mode::study) {
        if (p.calibrate_on.empty()) p.calibrate_on = p.sands.front();
        if (!unique.count(p.calibrate_on))
            throw InputError(ctx.file, ctx.keys["calibration.calibrate_on"].line,
                             "key 'calibration.calibrate_on' = \"" + p.calibrate_on + "\" is not one of calibration.sands");
        if (p.sands.size() < 2)
            throw InputError(ctx.file, ctx.keys["calibration.mode"].line, "mode \"study\" needs a second sand to predict");
    }
}

// Where the problem's bond model comes from, for messages.
std::string bond_model_origin(Context& ctx) {
    const int line = ctx.keys["calibration.bond_model"].line;
    return line > 0 ? "calibration.bond_model (line " + std::to_string(line) + ")" : "the base config's material.model";
}

// A parameter of another bond model than the problem's is an error naming the model it belongs to.
void check_model_of(Context& ctx, const exp::MaterialParameter& row, BondModel model, int line) {
    if (row.applies_to(model)) return;
    throw InputError(ctx.file, line,
                     "parameter '" + std::string(row.key) + "' belongs to bond model " + exp::model_names(row.models) +
                         ", but this problem's bond model is " + bond_model_name(model) + " (from " + bond_model_origin(ctx) +
                         "): set calibration.bond_model or remove [parameters." + std::string(row.key) + "]");
}

// A paste-only row (the interfacial-zone factors) needs an explicit-paste base: a parallel-bond
// specimen has no paste-sand bonds, so the parameter would be a direction the targets cannot see.
void check_representation_of(Context& ctx, const exp::MaterialParameter& row, const exp::CubeConfig& base, int line) {
    if (!row.paste_only || base.specimen.paste) return;
    const std::string name(row.key);
    throw InputError(ctx.file, line,
                     "parameter '" + name + "' applies to explicit-paste specimens only, but the base config's "
                     "specimen.representation is \"" + to_string(base.representation) + "\": remove [parameters." + name + "]");
}

// Integer parameters (element counts) are never free, and their value is a whole number.
void check_integer(Context& ctx, const exp::MaterialParameter& row, const ParameterSpec& spec) {
    if (row.calibration != exp::Calibration::fixed_only) return;
    const std::string where = "parameters." + spec.name;
    if (spec.free)
        throw InputError(ctx.file, ctx.keys[spec.name + ".free"].line,
                         "key '" + where + ".free' = true: " + spec.name + " is an integer (" + std::string(row.description) +
                             ") and cannot be calibrated; set free = false and start = the count");
    if (spec.start != std::round(spec.start))
        throw InputError(ctx.file, ctx.keys[spec.name + ".start"].line,
                         "key '" + where + ".start' = " + show(spec.start) + ": " + spec.name + " is an integer (an element count)");
}

void read_parameters(Context& ctx, const toml::table& root, CalibrationProblem& p) {
    std::map<std::string, ParameterSpec> specs;
    for (const std::string& name : kDefaultFree) {
        specs[name] = default_parameter(name, p.base.material);
        specs[name].free = true;
    }
    if (const toml::node* n = root.get("parameters")) {
        if (!n->is_table()) throw InputError(ctx.file, line_of(*n), "'parameters' must be a table of [parameters.<name>] tables");
        for (auto&& [key, node] : *n->as_table()) {
            const std::string name(key.str());
            if (!is_known_parameter(name)) {
                std::string known;
                for (const auto& k : parameter_names()) known += (known.empty() ? "" : ", ") + k;
                throw InputError(ctx.file, line_of(node), "unknown parameter '" + name + "' (known: " + known + ")");
            }
            if (!node.is_table()) throw InputError(ctx.file, line_of(node), "'parameters." + name + "' must be a table");
            const exp::MaterialParameter& row = *exp::find_material_parameter(name);
            check_model_of(ctx, row, p.base.material.bond.model, line_of(node));
            check_representation_of(ctx, row, p.base, line_of(node));
            ParameterSpec spec = specs.count(name) ? specs[name] : default_parameter(name, p.base.material);
            Section s(ctx, *n->as_table(), name);
            s.boolean("free", spec.free);
            s.real("start", spec.start);
            s.real("lower", spec.lower);
            s.real("upper", spec.upper);
            std::string scale = spec.log_scale ? "log" : "linear";
            s.text("scale", scale);
            s.finish();
            spec.line = line_of(node);
            const std::string where = "parameters." + name;
            if (scale != "log" && scale != "linear")
                throw InputError(ctx.file, ctx.keys[name + ".scale"].line, "key '" + where + ".scale' = \"" + scale + "\": expected \"log\" or \"linear\"");
            spec.log_scale = scale == "log";
            if (!(spec.lower < spec.upper))
                throw InputError(ctx.file, spec.line, "[" + where + "] lower = " + show(spec.lower) + " must be < upper = " + show(spec.upper));
            if (spec.log_scale && !(spec.lower > 0.0))
                throw InputError(ctx.file, spec.line, "[" + where + "] scale = \"log\" needs lower > 0 (got " + show(spec.lower) + ")");
            check_integer(ctx, *exp::find_material_parameter(name), spec);
            if (spec.free && !(spec.start >= spec.lower && spec.start <= spec.upper))
                throw InputError(ctx.file, spec.line, "[" + where + "] start = " + show(spec.start) + " is outside [lower, upper] = [" +
                                                          show(spec.lower) + ", " + show(spec.upper) + "]");
            specs[name] = spec;
        }
    }
    if (specs.count("cohesion_mpa") && specs.count("cohesion_ratio") && specs["cohesion_mpa"].free && specs["cohesion_ratio"].free)
        throw InputError(ctx.file, specs["cohesion_mpa"].line, "free parameters cohesion_mpa and cohesion_ratio exclude each other: set one free = false");
    if (specs.count("cohesion_mpa") && specs["cohesion_mpa"].free) specs.erase("cohesion_ratio");
    if (specs.count("bond_gap_um") && specs.count("bond_gap_fraction") && specs["bond_gap_um"].free && specs["bond_gap_fraction"].free)
        throw InputError(ctx.file, specs["bond_gap_um"].line, "free parameters bond_gap_um and bond_gap_fraction exclude each other");
    for (auto& [name, spec] : specs) p.parameters.push_back(spec);
    // Every parameter must give a valid material at its bounds' corners that matter: check the start.
    const ParameterSpace space(p.parameters, p.base.material);
    if (space.size() == 0) throw InputError(ctx.file, 0, "no free parameter: set free = true in a [parameters.<name>] table");
    if (auto why = space.material(space.start()).invalid_reason())
        throw InputError(ctx.file, 0, "the start parameters give an invalid material: " + *why);
}

/// [targets] tension*: the direct-tension target's keys (read into p.tension, checked here).
void read_tension_target(Context& ctx, Section& s, CalibrationProblem& p) {
    TensionTarget& t = p.tension;
    s.choice("tension", t.source);
    s.real("tension_ratio", t.ratio);
    s.real("tension_ratio_low", t.ratio_low);
    s.real("tension_ratio_high", t.ratio_high);
    s.real("tension_tolerance", t.tolerance);
    s.real("tension_weight", p.weights.tension);
    s.text("tension_basis", t.basis);
    auto line = [&](const char* key) { return ctx.keys[std::string("targets.") + key].line; };
    if (!t.fitted()) return;
    if (!(t.ratio > 1.0))
        throw InputError(ctx.file, line("tension_ratio"), "key 'targets.tension_ratio' = " + show(t.ratio) + " violates > 1 (σc/σt)");
    if (!(t.ratio_low > 1.0 && t.ratio_low <= t.ratio && t.ratio <= t.ratio_high))
        throw InputError(ctx.file, line(t.ratio_low > 1.0 && t.ratio_low <= t.ratio ? "tension_ratio_high" : "tension_ratio_low"),
                         "keys 'targets.tension_ratio_low' = " + show(t.ratio_low) + ", 'tension_ratio' = " + show(t.ratio) +
                             ", 'tension_ratio_high' = " + show(t.ratio_high) + " violate 1 < low <= ratio <= high");
    if (!(t.tolerance > 0.0 && t.tolerance < 1.0))
        throw InputError(ctx.file, line("tension_tolerance"), "key 'targets.tension_tolerance' = " + show(t.tolerance) + " violates in (0, 1)");
    if (t.assumed() && t.basis.empty())
        throw InputError(ctx.file, line("tension"),
                         "key 'targets.tension_basis' is required with tension = \"assumed_ratio\": say where the assumed σc/σt comes from");
}

/// The tension targets of every sand, once the lab's compression targets are read.
void set_tension_targets(Context& ctx, CalibrationProblem& p) {
    if (p.tension.assumed())
        for (SandTargets& t : p.targets) t.tension = {t.peak.mean / p.tension.ratio, std::nan(""), 0};
    if (p.tension.source != TensionSource::lab) return;
    const auto tensile = read_lab_tensile_targets(p.lab_results, p.sands);
    for (std::size_t s = 0; s < p.targets.size(); ++s) {
        if (!tensile[s])
            throw InputError(ctx.file, ctx.keys["targets.tension"].line,
                             "key 'targets.tension' = \"lab\": sand '" + p.sands[s] + "' has no tensile_strength_mpa in " +
                                 p.lab_results.string() +
                                 " (add its splitting or flexural tests to the dataset, or use tension = \"assumed_ratio\")");
        p.targets[s].tension = *tensile[s];
    }
}

void read_targets(Context& ctx, const toml::table& root, CalibrationProblem& p) {
    Section s(ctx, root, "targets");
    s.path("lab_results", p.lab_results);
    s.real("modulus_weight", p.weights.modulus);
    s.real("peak_weight", p.weights.peak);
    s.real("strain_weight", p.weights.strain);
    read_tension_target(ctx, s, p);
    s.finish();
    for (const auto& [key, w] : {std::pair<const char*, double>{"modulus_weight", p.weights.modulus},
                                 {"peak_weight", p.weights.peak}, {"strain_weight", p.weights.strain},
                                 {"tension_weight", p.weights.tension}})
        if (!(w >= 0.0 && std::isfinite(w)))
            throw InputError(ctx.file, ctx.keys[std::string("targets.") + key].line, std::string("key 'targets.") + key + "' must be >= 0");
    if (p.weights.modulus + p.weights.peak + p.weights.strain <= 0.0)
        throw InputError(ctx.file, ctx.keys["targets.modulus_weight"].line, "all target weights are zero");
    if (p.lab_results.empty())
        throw InputError(ctx.file, 0, "key 'targets.lab_results' is required: the lab_results.json written by `gradem lab <dataset> --out DIR`");
    if (!fs::exists(p.lab_results))
        throw InputError(ctx.file, ctx.keys["targets.lab_results"].line,
                         "key 'targets.lab_results': " + p.lab_results.string() + " not found; run `gradem lab <dataset> --out DIR` first");
    p.targets = read_lab_targets(p.lab_results, p.sands, &p.representative, &p.lab_note);
    set_tension_targets(ctx, p);
}

/// The largest grain a specimen of the problem can hold [m]: the size rule's cut-off, or the
/// coarsest sieve of the sands' gradations when there is none (after the rule's scale).
double largest_grain(const CalibrationProblem& p) {
    const exp::SizeRule& rule = p.base.specimen.size_rule;
    if (rule.max_diameter > 0.0) return rule.max_diameter * rule.scale;
    double largest = 0.0;
    for (const std::string& sand : p.sands) {
        exp::CubeConfig c = p.base;
        c.sand = sand;
        const lab::GradationCurve curve = exp::load_gradation(c);
        if (!curve.size_m.empty()) largest = std::max(largest, curve.size_m.back());
    }
    return largest * rule.scale;
}

/// [scale_up] or [validation] (`table`): the edge (default: the fit's) and the seeds, checked
/// against the size rule; `what` names the specimens in the messages.
SpecimenSetSpec read_specimen_set(Context& ctx, const toml::table& root, const CalibrationProblem& p, const std::string& table,
                                  const std::string& what) {
    Section s(ctx, root, table);
    SpecimenSetSpec v;
    v.edge = p.base.specimen.genesis.edge;
    s.real("edge_mm", v.edge, 1e-3);
    v.seeds = read_seeds(s, "seeds", {});
    if (table == "validation") v.tension_seeds = read_seeds(s, "tension_seeds", {});
    s.finish();
    const int edge_line = ctx.keys[table + ".edge_mm"].line, seeds_line = ctx.keys[table + ".seeds"].line;
    if (v.seeds.empty())
        throw InputError(ctx.file, seeds_line, "key '" + table + ".seeds' is required and not empty: the packing seeds of the " + what);
    const double grain = largest_grain(p);
    if (!(v.edge >= 3.0 * grain))
        throw InputError(ctx.file, edge_line, "key '" + table + ".edge_mm' = " + show(v.edge * 1e3) + " violates >= 3 x the largest grain (" +
                                                  show(grain * 1e3) + " mm), i.e. >= " + show(3e3 * grain) + " mm");
    exp::SpecimenSpec spec = p.base.specimen;
    spec.genesis.edge = v.edge;
    if (const auto why = spec.invalid_reason()) throw InputError(ctx.file, edge_line, "key '" + table + ".edge_mm': " + *why);
    return v;
}

bool contains(const std::vector<std::uint64_t>& seeds, std::uint64_t seed) {
    return std::find(seeds.begin(), seeds.end(), seed) != seeds.end();
}

/// [scale_up]: needs a free scale parameter to set, and one stage per fitted set of sands.
void read_scale_up(Context& ctx, const toml::table& root, CalibrationProblem& p) {
    if (!root.get("scale_up")) return;
    p.scale_up = read_specimen_set(ctx, root, p, "scale_up", "specimens on which the scales are set");
    const int line = ctx.keys["scale_up.seeds"].line;
    if (p.mode == Mode::study)
        throw InputError(ctx.file, line, "table [scale_up] is not available with calibration.mode = \"study\" (its prediction runs "
                                         "on the fitted specimens): use mode \"joint\" or \"per_sand\"");
    bool scale_free = false;
    for (const ParameterSpec& spec : p.parameters)
        scale_free = scale_free || (spec.free && spec.role() != Role::shape);
    if (!scale_free)
        throw InputError(ctx.file, line, "table [scale_up] needs a free stiffness or strength parameter (e.g. effective_modulus_gpa, "
                                         "tensile_strength_mpa) to set on its specimens; every one is fixed");
}

void read_validation(Context& ctx, const toml::table& root, CalibrationProblem& p) {
    if (!root.get("validation")) return;
    ValidationSpec& v = p.validation;
    v = read_specimen_set(ctx, root, p, "validation", "validation specimens");
    const int seeds_line = ctx.keys["validation.seeds"].line;
    for (std::uint64_t seed : v.seeds) {
        for (std::size_t sand = 0; sand < p.sands.size(); ++sand)
            if (contains(p.seeds_of(sand), seed))
                throw InputError(ctx.file, seeds_line, "key 'validation.seeds': seed " + std::to_string(seed) + " is also a fitted seed of " +
                                                           p.sands[sand] + " (calibration." +
                                                           (&p.seeds_of(sand) == &p.seeds ? std::string("seeds") : "sand_seeds") +
                                                           "): validation specimens must be unseen");
        if (contains(p.scale_up.seeds, seed))
            throw InputError(ctx.file, seeds_line, "key 'validation.seeds': seed " + std::to_string(seed) +
                                                       " is also a scale-up seed (scale_up.seeds): validation specimens must be unseen");
    }
    const int tension_line = ctx.keys["validation.tension_seeds"].line;
    for (std::uint64_t seed : v.tension_seeds)
        if (!contains(v.seeds, seed))
            throw InputError(ctx.file, tension_line, "key 'validation.tension_seeds': seed " + std::to_string(seed) +
                                                         " is not a validation seed (validation.seeds): the tension test runs on a "
                                                         "validation cube beside its compression test");
    if (!v.tension_seeds.empty() && !p.tension.fitted())
        throw InputError(ctx.file, tension_line, "key 'validation.tension_seeds' needs a direct-tension target ([targets] tension): "
                                                 "without one no tension test runs");
}

/// [calibration] tension_seeds, once the sands' seeds and the tension target are read: each a
/// packing seed of every sand (so every sand has its σt), and only with a tension target.
void check_tension_seeds(Context& ctx, const CalibrationProblem& p) {
    if (p.tension_seeds.empty()) return;
    const int line = ctx.keys["calibration.tension_seeds"].line;
    for (std::uint64_t seed : p.tension_seeds)
        for (std::size_t sand = 0; sand < p.sands.size(); ++sand)
            if (!contains(p.seeds_of(sand), seed))
                throw InputError(ctx.file, line, "key 'calibration.tension_seeds': seed " + std::to_string(seed) + " is not a seed of " +
                                                     p.sands[sand] + " (calibration." +
                                                     (&p.seeds_of(sand) == &p.seeds ? std::string("seeds") : "sand_seeds") +
                                                     "): the tension test runs on a fitted cube of every sand, beside its compression test");
    if (!p.tension.fitted())
        throw InputError(ctx.file, line, "key 'calibration.tension_seeds' needs a direct-tension target ([targets] tension): "
                                         "without one no tension test runs");
}

void read_solver(Context& ctx, const toml::table& root, CalibrationProblem& p) {
    Section s(ctx, root, "solver");
    SolverSettings& v = p.solver;
    s.choice("method", v.method);
    s.integer("max_runs", v.max_runs, 1);
    s.real("tolerance", v.tolerance);
    s.real("fd_step", v.fd_step);
    s.real("homogeneity_tolerance", v.homogeneity_tolerance);
    s.real("penalty", v.penalty);
    s.integer("seed", v.seed, 0);
    s.finish();
    auto bad = [&](const char* key, const std::string& rule) {
        throw InputError(ctx.file, ctx.keys[std::string("solver.") + key].line, std::string("key 'solver.") + key + "' " + rule);
    };
    if (!(v.tolerance > 0.0 && v.tolerance < 0.5)) bad("tolerance", "must be in (0, 0.5)");
    if (!(v.fd_step > 0.0 && v.fd_step <= 0.25)) bad("fd_step", "must be in (0, 0.25]");
    if (!(v.homogeneity_tolerance > 0.0 && v.homogeneity_tolerance < 1.0)) bad("homogeneity_tolerance", "must be in (0, 1)");
    if (!(v.penalty > 0.0)) bad("penalty", "must be > 0");

    Section r(ctx, root, "run");
    r.integer("workers", p.workers, 1);
    r.real("timeout_s", p.timeout_s);
    r.finish();
    if (p.workers > 64) throw InputError(ctx.file, ctx.keys["run.workers"].line, "key 'run.workers' must be in [1, 64]");
    if (!(p.timeout_s >= 0.0)) throw InputError(ctx.file, ctx.keys["run.timeout_s"].line, "key 'run.timeout_s' must be >= 0 (0: no limit)");
}

void read_output(Context& ctx, const toml::table& root, CalibrationProblem& p, const std::string& stem) {
    Section s(ctx, root, "output");
    p.out_dir = (ctx.dir / "out" / stem).lexically_normal();
    s.path("dir", p.out_dir);
    s.path("ledger", p.ledger);
    s.finish();
    if (p.ledger.empty()) p.ledger = p.out_dir / "ledger.sqlite";
}

std::string exact(double v) {
    char buf[64];
    std::snprintf(buf, sizeof buf, "%.17g", v);
    return buf;
}

TargetStat read_stat(const nlohmann::json& sand, const char* key, double to_si, const std::string& file, const std::string& name) {
    if (!sand.contains(key) || !sand[key].is_object() || !sand[key].contains("mean"))
        throw InputError(file, 0, "sand '" + name + "': no '" + key + "' statistics (is this a lab_results.json of `gradem lab`?)");
    const auto& j = sand[key];
    TargetStat t;
    t.mean = common::number_or_nan(j, "mean") * to_si;
    t.std = common::number_or_nan(j, "std") * to_si;
    t.n = j.contains("n") && j["n"].is_number_integer() ? j["n"].get<int>() : 0;
    if (!(std::isfinite(t.mean) && t.mean > 0.0))
        throw InputError(file, 0, "sand '" + name + "': " + key + ".mean is missing or not positive - the lab results are inconsistent");
    if (t.n < 1) throw InputError(file, 0, "sand '" + name + "': " + key + ".n = " + std::to_string(t.n) + " (no cubes reduced)");
    if (std::isfinite(t.std) && t.std < 0.0) throw InputError(file, 0, "sand '" + name + "': " + key + ".std is negative");
    return t;
}

/// The lab results file as JSON, with its 'sands' array checked.
nlohmann::json read_lab_json(const fs::path& json_file) {
    const nlohmann::json j = common::read_json_file(json_file, "the lab results");
    if (!j.is_object() || !j.contains("sands") || !j["sands"].is_array())
        throw InputError(json_file.string(), 0, "no 'sands' array: expected the lab_results.json written by `gradem lab`");
    return j;
}

/// The entry of sand `name` in the lab results; InputError listing the sands there otherwise.
const nlohmann::json& find_lab_sand(const nlohmann::json& j, const fs::path& json_file, const std::string& name) {
    std::string names;
    for (const auto& s : j["sands"]) {
        const std::string n = s.value("name", "");
        if (n == name) return s;
        names += (names.empty() ? "'" : ", '") + n + "'";
    }
    throw InputError(json_file.string(), 0, "sand '" + name + "' is not in the lab results (sands: " + names + ")");
}

}  // namespace

const TargetStat& target_of(const SandTargets& t, Quantity q) {
    return q == Quantity::modulus ? t.modulus : q == Quantity::peak ? t.peak : q == Quantity::strain ? t.strain : t.tension;
}

std::vector<Quantity> CalibrationProblem::fitted_quantities() const {
    std::vector<Quantity> out(std::begin(kQuantities), std::end(kQuantities));
    if (tension.fitted()) out.push_back(Quantity::tension);
    return out;
}

std::vector<std::optional<TargetStat>> read_lab_tensile_targets(const fs::path& json_file, const std::vector<std::string>& sands) {
    const nlohmann::json j = read_lab_json(json_file);
    std::vector<std::optional<TargetStat>> out;
    for (const std::string& name : sands) {
        const nlohmann::json& sand = find_lab_sand(j, json_file, name);
        if (sand.contains("tensile_strength_mpa")) out.push_back(read_stat(sand, "tensile_strength_mpa", 1e6, json_file.string(), name));
        else out.push_back(std::nullopt);
    }
    return out;
}

std::vector<SandTargets> read_lab_targets(const fs::path& json_file, const std::vector<std::string>& sands,
                                          bool* representative, std::string* note) {
    const nlohmann::json j = read_lab_json(json_file);
    if (representative) *representative = j.contains("representative_data") && j["representative_data"].is_boolean() &&
                                          j["representative_data"].get<bool>();
    if (note && j.contains("note") && j["note"].is_string()) *note = j["note"].get<std::string>();
    std::vector<SandTargets> out;
    for (const std::string& name : sands) {
        const nlohmann::json& found = find_lab_sand(j, json_file, name);
        SandTargets t;
        t.name = name;
        t.modulus = read_stat(found, "chord_modulus_mpa", 1e6, json_file.string(), name);
        t.peak = read_stat(found, "peak_stress_mpa", 1e6, json_file.string(), name);
        t.strain = read_stat(found, "strain_at_peak", 1.0, json_file.string(), name);
        out.push_back(t);
    }
    return out;
}

const std::vector<std::uint64_t>& CalibrationProblem::seeds_of(std::size_t sand) const {
    return sand_seeds_or(sand_seeds, seeds, sand);
}

PackingSeeds CalibrationProblem::packing_seeds() const {
    PackingSeeds out(seeds);
    out.by_sand = sand_seeds;
    return out;
}

bool CalibrationProblem::runs_tension_on(std::uint64_t seed) const {
    return tension_seeds.empty() || contains(tension_seeds, seed);
}

std::vector<std::uint64_t> CalibrationProblem::tension_seeds_of(std::size_t sand) const {
    std::vector<std::uint64_t> out;
    for (std::uint64_t seed : seeds_of(sand))
        if (runs_tension_on(seed)) out.push_back(seed);
    return out;
}

std::vector<std::size_t> CalibrationProblem::sand_indices() const {
    std::vector<std::size_t> all(sands.size());
    std::iota(all.begin(), all.end(), std::size_t{0});
    return all;
}

int CalibrationProblem::tension_runs_per_test(const std::vector<std::size_t>& of_sands) const {
    std::size_t n = 0;
    for (std::size_t sand : of_sands) n += tension_seeds_of(sand).size();
    return static_cast<int>(n);
}

int CalibrationProblem::tension_runs_per_test() const { return tension_runs_per_test(sand_indices()); }

int CalibrationProblem::runs_per_test(const std::vector<std::size_t>& of_sands) const {
    std::size_t n = 0;
    for (std::size_t sand : of_sands) n += seeds_of(sand).size();
    return static_cast<int>(n);
}

int CalibrationProblem::runs_per_test() const { return runs_per_test(sand_indices()); }

std::string CalibrationProblem::describe() const {
    std::ostringstream d;
    d << "model = " << to_string(model) << "\nmode = " << to_string(mode) << "\nsands =";
    for (const auto& s : sands) d << " '" << s << "'";
    d << "\ncalibrate_on = " << calibrate_on << "\nseeds =";
    for (auto s : seeds) d << " " << s;
    for (std::size_t k = 0; k < sand_seeds.size(); ++k)  // only when given: other problems keep their fingerprints
        if (!sand_seeds[k].empty()) {
            d << "\nseeds of '" << sands[k] << "' =";
            for (auto s : sand_seeds[k]) d << " " << s;
        }
    d << "\nbase material = " << material_key(base.material) << "\n";
    for (const auto& q : parameters)
        d << "parameter " << q.name << " = " << (q.free ? "free" : "fixed") << " start " << exact(q.start) << " bounds "
          << exact(q.lower) << " " << exact(q.upper) << " " << (q.log_scale ? "log" : "linear") << "\n";
    for (const auto& t : targets)
        for (Quantity q : fitted_quantities())
            d << "target " << t.name << " " << to_string(q) << " = " << exact(target_of(t, q).mean) << " +- "
              << exact(target_of(t, q).std) << "\n";
    d << "weights = " << exact(weights.modulus) << " " << exact(weights.peak) << " " << exact(weights.strain) << "\n";
    if (tension.fitted())  // only then: the other problems keep their fingerprints
        d << "tension " << to_string(tension.source) << " weight " << exact(weights.tension) << " ratio " << exact(tension.ratio)
          << "\n";
    if (!tension_seeds.empty()) {  // only when given, as above
        d << "tension seeds =";
        for (auto s : tension_seeds) d << " " << s;
        d << "\n";
    }
    d << "solver = " << to_string(solver.method) << " tolerance " << exact(solver.tolerance) << " fd_step "
      << exact(solver.fd_step) << " homogeneity " << exact(solver.homogeneity_tolerance) << " penalty "
      << exact(solver.penalty) << " seed " << solver.seed << "\ntimeout_s = " << exact(timeout_s) << "\n";
    return d.str();
}

CalibrationProblem load_calibration_problem(const fs::path& toml_file) {
    Context ctx;
    const toml::table root = parse_toml_file(toml_file, ctx);
    CalibrationProblem p;
    p.file = toml_file;
    check_tables(ctx, root, kTables);
    read_calibration(ctx, root, p);
    read_parameters(ctx, root, p);
    read_targets(ctx, root, p);
    check_tension_seeds(ctx, p);
    read_solver(ctx, root, p);
    read_scale_up(ctx, root, p);
    read_validation(ctx, root, p);
    read_output(ctx, root, p, toml_file.stem().string());
    return p;
}

namespace {

/// `problem` on the specimens of `set`, with no other set of its own; it runs what it asks
/// for (its runs are counted apart from the budget).
CalibrationProblem on_specimens(const CalibrationProblem& problem, const SpecimenSetSpec& set) {
    CalibrationProblem v = problem;
    v.base.specimen.genesis.edge = set.edge;
    v.seeds = set.seeds;
    v.sand_seeds.clear();
    v.tension_seeds = set.tension_seeds;
    v.scale_up = {};
    v.validation = {};
    v.solver.max_runs = 1 << 30;
    return v;
}

}  // namespace

CalibrationProblem validation_problem(const CalibrationProblem& problem) { return on_specimens(problem, problem.validation); }
CalibrationProblem scale_up_problem(const CalibrationProblem& problem) { return on_specimens(problem, problem.scale_up); }

}  // namespace gradem::cal
