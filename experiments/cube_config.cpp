#include "experiments/cube_config.hpp"

#include <limits>
#include <map>
#include <set>
#include <sstream>
#include <string_view>
#include <toml++/toml.h>
#include <vector>

#include "experiments/toml_section.hpp"
#include "lab_data/dataset.hpp"
#include "lab_data/input_error.hpp"
#include "lab_data/sieve_table.hpp"
#include "lab_data/text.hpp"

namespace gradem::exp {
namespace {

namespace fs = std::filesystem;
using lab::InputError;
using namespace toml_io;

constexpr double kMm = 1.0e-3, kMpa = 1.0e6, kGpa = 1.0e9;  // display unit -> SI

const std::vector<std::string> kTables = {"specimen", "size_rule", "genesis", "material", "test", "output",
                                          "tension"};  // [tension]: tension_config.hpp

void read_specimen(Context& ctx, const toml::table& root, CubeConfig& c) {
    Section s(ctx, root, "specimen");
    s.path("dataset", c.dataset);
    s.text("sand", c.sand);
    s.path("sieve_csv", c.sieve_csv);
    s.finish();
    const int line = ctx.keys["specimen.dataset"].line + ctx.keys["specimen.sieve_csv"].line;
    if (c.dataset.empty() == c.sieve_csv.empty())
        throw InputError(ctx.file, c.dataset.empty() ? 0 : line,
                         "[specimen] needs either dataset (with sand) or sieve_csv, not " + std::string(c.dataset.empty() ? "neither" : "both"));
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

// A coefficient of variation: the struct stores std = cv x mean.
void read_cv(Section& s, const char* key, double mean, double& std_dev) {
    double cv = mean > 0.0 ? std_dev / mean : 0.0;
    s.real(key, cv);
    std_dev = cv * mean;
}

void read_material(Context& ctx, const toml::table& root, CubeConfig& c) {
    Section s(ctx, root, "material");
    MaterialParams& m = c.material;
    s.real("effective_modulus_gpa", m.contact.effective_modulus, kGpa);
    s.real("stiffness_ratio", m.contact.stiffness_ratio);
    s.real("friction", m.contact.friction);
    m.bond.effective_modulus = m.contact.effective_modulus;  // defaults: the contact's
    m.bond.stiffness_ratio = m.contact.stiffness_ratio;
    s.real("bond_modulus_gpa", m.bond.effective_modulus, kGpa);
    s.real("bond_stiffness_ratio", m.bond.stiffness_ratio);
    s.real("radius_multiplier", m.bond.radius_multiplier);
    s.real("moment_factor", m.bond.moment_factor);
    s.real("tensile_strength_mpa", m.bond.tensile_strength_mean, kMpa);
    read_cv(s, "tensile_strength_cv", m.bond.tensile_strength_mean, m.bond.tensile_strength_std);
    s.real("cohesion_mpa", m.bond.cohesion_mean, kMpa);
    read_cv(s, "cohesion_cv", m.bond.cohesion_mean, m.bond.cohesion_std);
    s.real("friction_angle_deg", m.bond.friction_angle_deg);
    s.real("bond_gap_fraction", m.bond_gap_fraction);
    s.real("bond_gap_um", m.bond_gap_absolute, 1.0e-6);
    s.real("platen_friction", m.platen_friction);
    s.real("damping", m.damping);
    s.integer("bond_seed", m.bond.seed);
    s.finish();
    for (const char* k : {"tensile_strength_cv", "cohesion_cv"}) ctx.keys["material." + std::string(k)].converted = true;
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
    {"ContactParams::effective_modulus", "material.effective_modulus_gpa"},
    {"ContactParams::stiffness_ratio", "material.stiffness_ratio"}, {"ContactParams::friction", "material.friction"},
    {"BondParams::effective_modulus", "material.bond_modulus_gpa"}, {"BondParams::stiffness_ratio", "material.bond_stiffness_ratio"},
    {"BondParams::radius_multiplier", "material.radius_multiplier"}, {"BondParams::moment_factor", "material.moment_factor"},
    {"BondParams::tensile_strength_mean", "material.tensile_strength_mpa"},
    {"BondParams::tensile_strength_std", "material.tensile_strength_cv"}, {"BondParams::cohesion_mean", "material.cohesion_mpa"},
    {"BondParams::cohesion_std", "material.cohesion_cv"}, {"BondParams::friction_angle_deg", "material.friction_angle_deg"},
    {"MaterialParams::bond_gap_fraction", "material.bond_gap_fraction"},
    {"MaterialParams::bond_gap_absolute", "material.bond_gap_um"}, {"MaterialParams::platen_friction", "material.platen_friction"},
    {"MaterialParams::damping", "material.damping"},
    {"PlatenTestSpec::strain_rate", "test.strain_rate_per_s"}, {"PlatenTestSpec::ramp_strain", "test.ramp_strain"},
    {"PlatenTestSpec::platen_friction", "material.platen_friction"}, {"PlatenTestSpec::stop_fraction", "test.stop_fraction"},
    {"PlatenTestSpec::max_strain", "test.max_strain"}, {"PlatenTestSpec::record_interval", "test.record_interval"},
    {"CubeTestSpec::gauge_length_fraction", "test.gauge_length_fraction"}, {"CubeTestSpec::slab_fraction", "test.slab_fraction"},
    {"CubeTestSpec::core_fraction", "test.core_fraction"}, {"CubeTestSpec::settle_ratio", "test.settle_ratio"},
    {"CubeTestSpec::max_settle_steps", "test.max_settle_steps"}, {"CubeTestSpec::imbalance_warning", "test.imbalance_warning"},
};

// The TOML key a validator's message is about: its leading "field = " token, looked up as
// spelled, or with the struct prefix normalised ("material.x", "cube_test.x", "MaterialParams::x").
const std::string* toml_key_of(const std::string& reason) {
    const std::string token = reason.substr(0, reason.find(" = "));
    if (auto it = kFields.find(token); it != kFields.end()) return &it->second;
    const auto cut = token.find_last_of(".:");
    if (cut == std::string::npos) return nullptr;
    const std::string field = token.substr(cut + 1);
    for (const char* prefix : {"MaterialParams::", "CubeTestSpec::", "PlatenTestSpec::"})
        if (auto it = kFields.find(prefix + field); it != kFields.end()) return &it->second;
    return nullptr;
}

void check(const Context& ctx, const std::optional<std::string>& reason) {
    if (!reason) return;
    const std::string* key = toml_key_of(*reason);
    const auto info = key ? ctx.keys.find(*key) : ctx.keys.end();
    if (info == ctx.keys.end()) throw InputError(ctx.file, 0, *reason);
    const auto at = reason->find(" violates ");
    const std::string rule = at == std::string::npos ? *reason : reason->substr(at + 10);
    std::string what = "key '" + *key + "' = " + info->second.text + " violates " + rule;
    if (info->second.converted) what += " (checked as " + *reason + ")";
    throw InputError(ctx.file, info->second.line, what);
}

}  // namespace

CubeConfig load_cube_config(const fs::path& toml_file) {
    Context ctx;
    const toml::table root = parse_toml_file(toml_file, ctx);
    CubeConfig c;
    c.file = toml_file;
    check_tables(ctx, root, kTables);
    read_specimen(ctx, root, c);
    read_genesis(ctx, root, c);
    read_material(ctx, root, c);
    read_test(ctx, root, c);
    read_output(ctx, root, c, toml_file.stem().string());
    check(ctx, c.specimen.invalid_reason());
    check(ctx, c.material.invalid_reason());
    check(ctx, c.test.loading.invalid_reason());
    check(ctx, c.test.invalid_reason());
    return c;
}

lab::GradationCurve load_gradation(const CubeConfig& c) {
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
