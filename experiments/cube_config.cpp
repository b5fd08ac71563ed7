#include "experiments/cube_config.hpp"

#include <limits>
#include <map>
#include <set>
#include <sstream>
#include <string_view>
#include <toml++/toml.h>
#include <vector>

#include "lab_data/dataset.hpp"
#include "lab_data/input_error.hpp"
#include "lab_data/sieve_table.hpp"
#include "lab_data/text.hpp"

namespace gradem::exp {
namespace {

namespace fs = std::filesystem;
using lab::InputError;

constexpr double kMm = 1.0e-3, kMpa = 1.0e6, kGpa = 1.0e9;  // display unit -> SI

int line_of(const toml::node& n) { return static_cast<int>(n.source().begin.line); }

std::string show(double v) {
    std::ostringstream os;
    os.precision(15);
    os << v;
    if (os.str().find_first_of(".eEni") == std::string::npos) os << ".0";  // keep it a float
    return os.str();
}

/// The value as the user wrote it (near enough): "text", 1.5, 3, true, or TOML for others.
std::string show(const toml::node& n) {
    if (n.is_floating_point()) return show(n.as_floating_point()->get());
    std::ostringstream os;
    if (n.is_string()) os << '"' << n.as_string()->get() << '"';
    else if (n.is_integer()) os << n.as_integer()->get();
    else if (n.is_boolean()) os << (n.as_boolean()->get() ? "true" : "false");
    else n.visit([&](const auto& v) { os << v; });
    return os.str();
}

/// Where a key was given (line 0: not given, the default applies) and its value as written.
struct KeyInfo {
    int line = 0;
    std::string text;
    bool converted = false;  ///< the struct holds the value in other units (SI, std from cv)
};

struct Context {
    std::string file;                      ///< display name of the config file
    fs::path dir;                          ///< relative paths start here
    std::map<std::string, KeyInfo> keys;   ///< "table.key" -> KeyInfo
};

/// One [table]: typed getters that remember every key asked for, then finish() rejects the
/// keys nobody asked for.
class Section {
public:
    Section(Context& ctx, const toml::table& root, std::string name) : ctx_(ctx), name_(std::move(name)) {
        if (const toml::node* n = root.get(name_)) {
            if (!n->is_table()) throw InputError(ctx_.file, line_of(*n), "'" + name_ + "' must be a table ([" + name_ + "])");
            table_ = n->as_table();
        }
    }

    void real(const char* key, double& v, double to_si = 1.0) {
        const toml::node* n = find(key);
        if (!n) return record_default(key, show(v / to_si), to_si != 1.0);
        if (!n->is_integer() && !n->is_floating_point()) type_error(key, *n, "a number");
        v = n->value<double>().value() * to_si;
        record(key, *n, to_si != 1.0);
    }

    template <typename Int>
    void integer(const char* key, Int& v, std::int64_t lo = std::numeric_limits<std::int64_t>::min()) {
        const toml::node* n = find(key);
        if (!n) return record_default(key, std::to_string(v), false);
        if (!n->is_integer()) type_error(key, *n, "an integer");
        const std::int64_t x = n->as_integer()->get();
        constexpr auto hi = static_cast<std::int64_t>(std::min<std::uint64_t>(std::numeric_limits<Int>::max(),
                                                                                std::numeric_limits<std::int64_t>::max()));
        lo = std::max<std::int64_t>(lo, std::is_signed_v<Int> ? std::numeric_limits<Int>::min() : 0);
        if (x < lo || x > hi)
            throw InputError(ctx_.file, line_of(*n), "key '" + full(key) + "' = " + std::to_string(x) + " violates in [" +
                                                         std::to_string(lo) + ", " + std::to_string(hi) + "]");
        v = static_cast<Int>(x);
        record(key, *n, false);
    }

    void boolean(const char* key, bool& v) {
        const toml::node* n = find(key);
        if (!n) return record_default(key, v ? "true" : "false", false);
        if (!n->is_boolean()) type_error(key, *n, "true or false");
        v = n->as_boolean()->get();
        record(key, *n, false);
    }

    void text(const char* key, std::string& v) {
        const toml::node* n = find(key);
        if (!n) return record_default(key, v, false);
        if (!n->is_string()) type_error(key, *n, "a string");
        v = n->as_string()->get();
        record(key, *n, false);
    }

    /// A path, relative to the config file's folder unless absolute.
    void path(const char* key, fs::path& v) {
        std::string s;
        text(key, s);
        if (!s.empty()) v = (ctx_.dir / fs::path(s)).lexically_normal();
    }

    /// The raw node (nullptr when absent), for keys with several accepted types.
    const toml::node* node(const char* key) { return find(key); }
    void record(const char* key, const toml::node& n, bool converted) {
        ctx_.keys[full(key)] = {line_of(n), show(n), converted};
    }
    void record_default(const char* key, const std::string& text, bool converted) {
        ctx_.keys[full(key)] = {0, text + " (default)", converted};
    }
    [[noreturn]] void type_error(const char* key, const toml::node& n, const std::string& expected) const {
        throw InputError(ctx_.file, line_of(n), "key '" + full(key) + "' = " + show(n) + ": expected " + expected);
    }
    [[nodiscard]] std::string full(const char* key) const { return name_ + "." + key; }

    void finish() const {
        if (!table_) return;
        for (auto&& [key, n] : *table_) {
            if (asked_.count(std::string(key.str()))) continue;
            std::string known;
            for (const auto& k : asked_) known += (known.empty() ? "" : ", ") + k;
            throw InputError(ctx_.file, line_of(n), "unknown key '" + full(std::string(key.str()).c_str()) + "' (known: " + known + ")");
        }
    }

private:
    const toml::node* find(const char* key) {
        asked_.insert(key);
        return table_ ? table_->get(key) : nullptr;
    }

    Context& ctx_;
    std::string name_;
    const toml::table* table_ = nullptr;
    std::set<std::string> asked_;
};

const std::vector<std::string> kTables = {"specimen", "size_rule", "genesis", "material", "test", "output"};

void check_tables(const Context& ctx, const toml::table& root) {
    for (auto&& [key, n] : root) {
        const std::string k(key.str());
        if (std::find(kTables.begin(), kTables.end(), k) != kTables.end()) continue;
        std::string known;
        for (const auto& t : kTables) known += (known.empty() ? "" : ", ") + t;
        throw InputError(ctx.file, line_of(n), (n.is_table() ? "unknown table '[" + k + "]'" : "unknown key '" + k + "'") +
                                                   " (known tables: " + known + ")");
    }
}

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
    {"MaterialParams::bond_gap_fraction", "material.bond_gap_fraction"}, {"MaterialParams::platen_friction", "material.platen_friction"},
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
    ctx.file = toml_file.string();
    ctx.dir = fs::absolute(toml_file).parent_path();
    const std::string text = lab::decode_text(lab::read_file_bytes(toml_file)).utf8;
    toml::table root;
    try {
        root = toml::parse(text, ctx.file);
    } catch (const toml::parse_error& e) {
        throw InputError(ctx.file, static_cast<int>(e.source().begin.line), std::string(e.description()));
    }
    CubeConfig c;
    c.file = toml_file;
    check_tables(ctx, root);
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
