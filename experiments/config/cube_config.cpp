#include "experiments/config/cube_config.hpp"
#include "experiments/config/cube_config_source.hpp"

#include <bit>
#include <limits>
#include <optional>
#include <map>
#include <set>
#include <sstream>
#include <string_view>
#include <toml++/toml.h>
#include <vector>

#include "common/input_error.hpp"
#include "common/toml_section.hpp"
#include "experiments/config/material_table.hpp"
#include "experiments/config/paste_config.hpp"
#include "lab_data/dataset.hpp"
#include "lab_data/sieve_table.hpp"
#include "lab_data/text.hpp"

namespace gradem::exp {
namespace {

namespace fs = std::filesystem;
using common::InputError;
using namespace common::toml_io;

constexpr double kMm = 1.0e-3, kMpa = 1.0e6, kGpa = 1.0e9;  // display unit -> SI

CubeConfig read_cube_config(Context& ctx, const toml::table& root, const fs::path& toml_file);

const std::vector<std::string> kTables = {"specimen", "size_rule", "genesis", "material", "test", "output",
                                          "tension", "mix", "paste"};  // [tension]: tension_config.hpp; [mix], [paste]: paste_config.hpp

void read_specimen(Context& ctx, const toml::table& root, CubeConfig& c) {
    Section s(ctx, root, "specimen");
    s.path("dataset", c.dataset);
    s.text("sand", c.sand);
    s.path("sieve_csv", c.sieve_csv);
    s.choice("representation", c.representation);  // paste_config.hpp
    s.finish();
    const int line = ctx.keys["specimen.dataset"].line + ctx.keys["specimen.sieve_csv"].line;
    if (c.dataset.empty() == c.sieve_csv.empty())
        throw InputError(ctx.file, c.dataset.empty() ? 0 : line,
                         "[specimen] needs either dataset (with sand) or sieve_csv, not " + std::string(c.dataset.empty() ? "neither" : "both"));
    const std::string key = c.dataset.empty() ? "specimen.sieve_csv" : "specimen.dataset";
    const KeyInfo& given = ctx.keys[key];
    c.source_key = {key, given.text, given.line, ctx.dir};
    if (!c.dataset.empty() && c.sand.empty())
        throw InputError(ctx.file, ctx.keys["specimen.dataset"].line, "key 'specimen.sand' is required with specimen.dataset");
    if (c.dataset.empty() && !c.sand.empty())
        throw InputError(ctx.file, ctx.keys["specimen.sand"].line, "key 'specimen.sand' needs specimen.dataset (sieve_csv has one sand)");

    Section r(ctx, root, "size_rule");
    SizeRule& rule = c.specimen.size_rule;
    r.real("min_diameter_mm", rule.min_diameter, kMm);
    r.real("max_diameter_mm", rule.max_diameter, kMm);
    r.real("scale", rule.scale);
    r.finish();
}

void read_genesis(Context& ctx, const toml::table& root, CubeConfig& c) {
    Section s(ctx, root, "genesis");
    GenesisSpec& g = c.specimen.genesis;
    s.real("edge_mm", g.edge, kMm);
    s.real("target_solid_fraction", g.target_solid_fraction);
    s.real("locked_in_stress_mpa", g.locked_in_stress, kMpa);
    s.real("stress_tolerance", g.stress_tolerance);
    s.real("reference_modulus_gpa", g.reference_modulus, kGpa);
    s.real("stiffness_ratio", g.stiffness_ratio);
    s.real("density_kg_m3", g.density);
    s.real("damping", g.damping);
    s.integer("min_contacts", g.min_contacts);
    s.integer("floater_passes", g.floater_passes);
    s.real("floater_growth", g.floater_growth);
    s.real("equilibrium_ratio", g.equilibrium_ratio);
    s.integer("max_steps", g.max_steps);
    s.integer("seed", c.specimen.seed);
    s.finish();
}

// The bond model: one of bond_model_names() (core/bond_models.hpp), parallel_bond by default.
BondModel read_bond_model(Section& s, Context& ctx) {
    std::string name = bond_model_name(BondModel::parallel_bond);
    s.text("model", name);
    if (const auto model = parse_bond_model(name)) return *model;
    throw InputError(ctx.file, ctx.keys["material.model"].line,
                     "key 'material.model' = \"" + name + "\": unknown bond model (known: " + bond_model_names() + ")");
}

// A key of another bond model than the file's: an error naming the model it belongs to.
[[noreturn]] void wrong_model(Context& ctx, const toml::node& n, const MaterialParameter& p, BondModel model) {
    const int model_line = ctx.keys["material.model"].line;
    throw InputError(ctx.file, line_of(n),
                     "key 'material." + std::string(p.key) + "' belongs to bond model " + model_names(p.models) +
                         ", but material.model = \"" + bond_model_name(model) + "\"" +
                         (model_line > 0 ? " (line " + std::to_string(model_line) + ")" : " (the default)") +
                         ": set model = \"" + bond_model_name(bond_models().at(std::countr_zero(p.models))) + "\" or remove the key");
}

// One row of the material table: its key in config units, converted to SI once.
void read_parameter(Section& s, Context& ctx, const MaterialParameter& p, MaterialParams& m) {
    const std::string key(p.key);
    if (!p.applies_to(m.bond.model)) {
        if (const toml::node* n = s.node(key.c_str())) wrong_model(ctx, *n, p, m.bond.model);
        return;
    }
    if (!p.follows.empty()) p.set(m, find_material_parameter(p.follows)->get(m));  // default: the leader's value
    if (p.flag) {
        bool v = p.get_int(m) != 0;
        s.boolean(key.c_str(), v);
        p.set_int(m, v ? 1 : 0);
    } else if (p.integer) {
        std::int64_t v = p.get_int(m);
        s.integer(key.c_str(), v);
        if (!p.range.contains(static_cast<double>(v)))
            throw InputError(ctx.file, ctx.keys["material." + key].line,
                             "key 'material." + key + "' = " + std::to_string(v) + " violates " + p.range.rule());
        p.set_int(m, v);
    } else if (!p.cv_of.empty()) {  // the struct stores std = cv x mean
        double cv = config_value(p, m);
        s.real(key.c_str(), cv);
        set_config_value(p, m, cv);
    } else {
        double v = p.get(m);
        s.real(key.c_str(), v, p.to_si);
        p.set(m, v);
    }
    ctx.keys["material." + key].converted = p.to_si != 1.0 || !p.cv_of.empty();
}

void read_material(Context& ctx, const toml::table& root, CubeConfig& c) {
    Section s(ctx, root, "material");
    MaterialParams& m = c.material;
    m.bond.model = read_bond_model(s, ctx);
    for (const MaterialParameter& p : material_table())
        if (p.in_config) read_parameter(s, ctx, p, m);
    s.finish();
    c.test.loading.platen_friction = m.platen_friction;
}

void read_test(Context& ctx, const toml::table& root, CubeConfig& c) {
    Section s(ctx, root, "test");
    CubeTestSpec& t = c.test;
    if (const toml::node* n = s.node("strain_rate_per_s"); n && n->is_string()) {
        if (n->as_string()->get() != "auto") s.type_error("strain_rate_per_s", *n, "a number [1/s] or \"auto\"");
        c.auto_strain_rate = true;
        s.record("strain_rate_per_s", *n, false);
    } else if (n && !n->is_integer() && !n->is_floating_point()) {
        s.type_error("strain_rate_per_s", *n, "a number [1/s] or \"auto\"");
    } else {
        s.real("strain_rate_per_s", t.loading.strain_rate);
    }
    s.real("ramp_strain", t.loading.ramp_strain);
    s.real("stop_fraction", t.loading.stop_fraction);
    s.real("stop_strain_ratio", t.loading.stop_strain_ratio);
    s.real("max_strain", t.loading.max_strain);
    s.integer("record_interval", t.loading.record_interval);
    s.real("gauge_length_fraction", t.gauge_length_fraction);
    s.real("slab_fraction", t.slab_fraction);
    s.real("core_fraction", t.core_fraction);
    s.real("settle_ratio", t.settle_ratio);
    s.integer("max_settle_steps", t.max_settle_steps);
    s.real("imbalance_warning", t.imbalance_warning);
    s.finish();
}

void read_output(Context& ctx, const toml::table& root, CubeConfig& c, const std::string& stem) {
    Section s(ctx, root, "output");
    c.out_dir = (ctx.dir / "out" / stem).lexically_normal();
    c.cache_dir = (ctx.dir / "out" / "packing-cache").lexically_normal();
    s.path("dir", c.out_dir);
    s.path("cache_dir", c.cache_dir);
    s.boolean("vtk", c.vtk);
    s.integer("vtk_every", c.vtk_every, 0);
    s.finish();
}

// --- validation: the structs' invalid_reason(), mapped back to the TOML key ---------------

// "Struct::field" or "table.field" as the validators spell it -> the TOML key.
using FieldMap = std::map<std::string, std::string, std::less<>>;

const FieldMap kFields = {
    {"size_rule.min_diameter", "size_rule.min_diameter_mm"}, {"size_rule.max_diameter", "size_rule.max_diameter_mm"},
    {"size_rule.scale", "size_rule.scale"},
    {"genesis.edge", "genesis.edge_mm"}, {"genesis.target_solid_fraction", "genesis.target_solid_fraction"},
    {"genesis.locked_in_stress", "genesis.locked_in_stress_mpa"}, {"genesis.stress_tolerance", "genesis.stress_tolerance"},
    {"genesis.reference_modulus", "genesis.reference_modulus_gpa"}, {"genesis.stiffness_ratio", "genesis.stiffness_ratio"},
    {"genesis.density", "genesis.density_kg_m3"}, {"genesis.damping", "genesis.damping"},
    {"genesis.min_contacts", "genesis.min_contacts"}, {"genesis.floater_passes", "genesis.floater_passes"},
    {"genesis.floater_growth", "genesis.floater_growth"}, {"genesis.equilibrium_ratio", "genesis.equilibrium_ratio"},
    {"genesis.max_steps", "genesis.max_steps"},
    {"PlatenTestSpec::strain_rate", "test.strain_rate_per_s"}, {"PlatenTestSpec::ramp_strain", "test.ramp_strain"},
    {"PlatenTestSpec::platen_friction", "material.platen_friction"}, {"PlatenTestSpec::stop_fraction", "test.stop_fraction"},
    {"PlatenTestSpec::stop_strain_ratio", "test.stop_strain_ratio"},
    {"PlatenTestSpec::max_strain", "test.max_strain"}, {"PlatenTestSpec::record_interval", "test.record_interval"},
    {"CubeTestSpec::gauge_length_fraction", "test.gauge_length_fraction"}, {"CubeTestSpec::slab_fraction", "test.slab_fraction"},
    {"CubeTestSpec::core_fraction", "test.core_fraction"}, {"CubeTestSpec::settle_ratio", "test.settle_ratio"},
    {"CubeTestSpec::max_settle_steps", "test.max_settle_steps"}, {"CubeTestSpec::imbalance_warning", "test.imbalance_warning"},
};

// The TOML key a validator's message is about: its leading "field = " token, a material
// parameter (by "material.<key>" or core's field name, from the material table), or looked up
// as spelled, or with the struct prefix normalised ("cube_test.x", "CubeTestSpec::x").
std::optional<std::string> toml_key_of(const std::string& reason) {
    const std::string token = reason.substr(0, reason.find(" = "));
    if (const MaterialParameter* p = material_parameter_of_field(token)) return "material." + std::string(p->key);
    if (auto it = kFields.find(token); it != kFields.end()) return it->second;
    const auto cut = token.find_last_of(".:");
    if (cut == std::string::npos) return std::nullopt;
    const std::string field = token.substr(cut + 1);
    for (const char* prefix : {"CubeTestSpec::", "PlatenTestSpec::"})
        if (auto it = kFields.find(prefix + field); it != kFields.end()) return it->second;
    return std::nullopt;
}

void check(const Context& ctx, const std::optional<std::string>& reason) {
    if (!reason) return;
    const std::optional<std::string> key = toml_key_of(*reason);
    const auto info = key ? ctx.keys.find(*key) : ctx.keys.end();
    if (info == ctx.keys.end()) throw InputError(ctx.file, 0, *reason);
    const auto at = reason->find(" violates ");
    const std::string rule = at == std::string::npos ? *reason : reason->substr(at + 10);
    std::string what = "key '" + *key + "' = " + info->second.text + " violates " + rule;
    const bool in_config_units = reason->starts_with(*key + " = ");
    if (info->second.converted && !in_config_units) what += " (checked as " + *reason + ")";
    throw InputError(ctx.file, info->second.line, what);
}

}  // namespace

CubeConfig load_cube_config(const fs::path& toml_file) {
    Context ctx;
    const toml::table root = parse_toml_file(toml_file, ctx);
    return read_cube_config(ctx, root, toml_file);
}

CubeConfig load_cube_config(const toml::table& root, const fs::path& toml_file, std::map<std::string, KeyInfo>* keys) {
    Context ctx;
    ctx.file = toml_file.string();
    ctx.dir = fs::absolute(toml_file).parent_path();
    CubeConfig c = read_cube_config(ctx, root, toml_file);
    if (keys) *keys = ctx.keys;
    return c;
}

namespace {

CubeConfig read_cube_config(Context& ctx, const toml::table& root, const fs::path& toml_file) {
    CubeConfig c;
    c.file = toml_file;
    check_tables(ctx, root, kTables);
    read_specimen(ctx, root, c);
    read_genesis(ctx, root, c);
    read_material(ctx, root, c);
    read_paste_config(ctx, root, c);
    read_test(ctx, root, c);
    read_output(ctx, root, c, toml_file.stem().string());
    check(ctx, c.specimen.invalid_reason());
    check(ctx, c.material.invalid_reason());
    check(ctx, c.test.loading.invalid_reason());
    check(ctx, c.test.invalid_reason());
    return c;
}

}  // namespace

lab::GradationCurve load_gradation(const CubeConfig& c) {
    const fs::path& source = c.sieve_csv.empty() ? c.dataset : c.sieve_csv;
    std::error_code ec;
    if (!source.empty() && !fs::exists(source, ec)) {
        const CubeConfig::SourceKey& k = c.source_key;
        throw InputError(c.file.string(), k.line,
                         "key '" + k.key + "' = " + k.text + ": no such file or folder " + source.string() +
                             (k.dir.empty() ? std::string() : " (relative paths are resolved against the config's folder " +
                                                                  k.dir.string() + ")"));
    }
    if (!c.sieve_csv.empty()) return lab::read_sieve_csv(c.sieve_csv).curve;
    const lab::DatasetConfig dataset = lab::load_dataset_config(c.dataset, false);
    std::string names;
    for (const lab::SandSpec& sand : dataset.sands) {
        if (sand.name == c.sand) {
            if (sand.sieve.empty())
                throw InputError(c.file.string(), 0, "sand '" + c.sand + "' of " + dataset.file.string() + " has no sieve file");
            return lab::read_sieve_csv(sand.sieve).curve;
        }
        names += (names.empty() ? "'" : ", '") + sand.name + "'";
    }
    throw InputError(c.file.string(), 0, "specimen.sand = '" + c.sand + "' is not a sand of " + dataset.file.string() +
                                             " (sands: " + (names.empty() ? "none" : names) + ")");
}

double strain_rate_for(const CubeConfig& c, const Packing& packing) {
    return c.auto_strain_rate ? quasi_static_strain_rate(packing, c.material) : c.test.loading.strain_rate;
}

}  // namespace gradem::exp
