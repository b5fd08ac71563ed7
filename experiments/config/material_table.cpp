// The material-parameter table (material_table.hpp) and the operations every reader of it
// shares: unit conversion, range checks, and how the calibration applies a value.
#include "experiments/config/material_table.hpp"

#include <array>
#include <cmath>
#include <sstream>
#include <type_traits>
#include <utility>
#include <vector>

#include "experiments/virtual_tests/cube_test.hpp"

namespace gradem::exp {
namespace {

// --- accessors: a member path into MaterialParams, e.g. <&MaterialParams::bond, &BondParams::seed> ---

template <auto... Path>
double si_get(const MaterialParams& m) {
    return static_cast<double>((m .* ... .* Path));
}

template <auto... Path>
void si_set(MaterialParams& m, double v) {
    auto& field = (m .* ... .* Path);
    using T = std::remove_reference_t<decltype(field)>;
    if constexpr (std::is_integral_v<T>) field = static_cast<T>(std::llround(v));
    else field = v;
}

template <auto... Path>
std::int64_t int_get(const MaterialParams& m) {
    return static_cast<std::int64_t>((m .* ... .* Path));
}

template <auto... Path>
void int_set(MaterialParams& m, std::int64_t v) {
    auto& field = (m .* ... .* Path);
    field = static_cast<std::remove_reference_t<decltype(field)>>(v);
}

using M = MaterialParams;
using C = ContactParams;
using B = BondParams;

using ranges::non_negative;
using ranges::positive;
using ranges::unit_open_right;

double cv_of(double std_dev, double mean) { return mean > 0.0 ? std_dev / mean : 0.0; }

// --- derived calibration parameters (no config key): get/set in config units --------------

/// c̄ / σ̄c; setting it moves c̄ (keeping its coefficient of variation).
double cohesion_ratio_get(const M& m) {
    return m.bond.tensile_strength_mean > 0.0 ? m.bond.cohesion_mean / m.bond.tensile_strength_mean : 2.0;
}
void cohesion_ratio_set(M& m, double v) {
    const double cv_c = cv_of(m.bond.cohesion_std, m.bond.cohesion_mean);
    m.bond.cohesion_mean = v * m.bond.tensile_strength_mean;
    m.bond.cohesion_std = cv_c * m.bond.cohesion_mean;
}

/// One coefficient of variation for σ̄c and c̄.
double strength_cv_get(const M& m) { return cv_of(m.bond.tensile_strength_std, m.bond.tensile_strength_mean); }
void strength_cv_set(M& m, double v) {
    m.bond.tensile_strength_std = v * m.bond.tensile_strength_mean;
    m.bond.cohesion_std = v * m.bond.cohesion_mean;
}

// Designated initializers leave the other members at their defaults on purpose (GCC warns).
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wmissing-field-initializers"
// clang-format off
const std::array kCommonRows = {
    // ---- every bond model: the linear contact, the bond's shared parameters, the specimen ----
    MaterialParameter{.key = "effective_modulus_gpa", .unit = "GPa",
        .description = "E*, contact modulus (calibration: E* and the bond modulus together)",
        .to_si = 1e9, .get = si_get<&M::contact, &C::effective_modulus>, .set = si_set<&M::contact, &C::effective_modulus>,
        .si_group = "contact", .si_name = "effective_modulus_pa", .core_field = "ContactParams::effective_modulus",
        .range = positive,
        .calibration = Calibration::free, .role = ParameterRole::stiffness_scale, .lower = 1.0, .upper = 100.0, .log_scale = true},
    MaterialParameter{.key = "stiffness_ratio", .unit = "-",
        .description = "kappa* = k_n / k_s of contacts (calibration: of contacts and bonds together)",
        .get = si_get<&M::contact, &C::stiffness_ratio>, .set = si_set<&M::contact, &C::stiffness_ratio>,
        .si_group = "contact", .si_name = "stiffness_ratio", .core_field = "ContactParams::stiffness_ratio",
        .range = positive,
        .calibration = Calibration::free, .lower = 1.0, .upper = 3.0},
    MaterialParameter{.key = "friction", .unit = "-", .description = "mu, grain-grain friction coefficient",
        .get = si_get<&M::contact, &C::friction>, .set = si_set<&M::contact, &C::friction>,
        .si_group = "contact", .si_name = "friction", .core_field = "ContactParams::friction",
        .range = non_negative,
        .calibration = Calibration::free, .lower = 0.1, .upper = 1.0},
    MaterialParameter{.key = "radius_multiplier", .unit = "-", .description = "lambda-bar, bond radius / smaller grain radius",
        .get = si_get<&M::bond, &B::radius_multiplier>, .set = si_set<&M::bond, &B::radius_multiplier>,
        .si_group = "bond", .si_name = "radius_multiplier", .core_field = "BondParams::radius_multiplier",
        .range = {0.0, 1.0, true, false},
        .calibration = Calibration::free, .lower = 0.3, .upper = 1.0},
    MaterialParameter{.key = "moment_factor", .unit = "-", .description = "beta-bar, moment contribution factor",
        .get = si_get<&M::bond, &B::moment_factor>, .set = si_set<&M::bond, &B::moment_factor>,
        .si_group = "bond", .si_name = "moment_factor", .core_field = "BondParams::moment_factor",
        .range = {0.0, 1.0, false, false},
        .calibration = Calibration::free, .lower = 0.0, .upper = 1.0},
    MaterialParameter{.key = "friction_angle_deg", .unit = "deg", .description = "phi-bar, bond friction angle",
        .get = si_get<&M::bond, &B::friction_angle_deg>, .set = si_set<&M::bond, &B::friction_angle_deg>,
        .si_group = "bond", .si_name = "friction_angle_deg", .core_field = "BondParams::friction_angle_deg",
        .range = {0.0, 90.0, false, true},
        .calibration = Calibration::free, .lower = 0.0, .upper = 60.0},
    MaterialParameter{.key = "bond_gap_um", .unit = "um",
        .description = "if > 0: the bonding gap itself, the same for every sand, replacing bond_gap_fraction",
        .to_si = 1e-6, .get = si_get<&M::bond_gap_absolute>, .set = si_set<&M::bond_gap_absolute>,
        .si_name = "bond_gap_absolute_m", .core_field = "MaterialParams::bond_gap_absolute",
        .range = {0.0, 1000.0, false, true},
        .calibration = Calibration::free, .lower = 0.0, .upper = 100.0},
    MaterialParameter{.key = "bond_gap_fraction", .unit = "-", .description = "bonding gap / mean grain radius",
        .get = si_get<&M::bond_gap_fraction>, .set = si_set<&M::bond_gap_fraction>,
        .si_name = "bond_gap_fraction", .core_field = "MaterialParams::bond_gap_fraction",
        .range = {0.0, 1.0, false, false},
        .calibration = Calibration::free, .lower = 0.0, .upper = 0.5},
    MaterialParameter{.key = "tensile_strength_mpa", .unit = "MPa",
        .description = "mean bond tensile strength sigma-bar_c (calibration: c-bar keeps its ratio to it)",
        .to_si = 1e6, .get = si_get<&M::bond, &B::tensile_strength_mean>, .set = si_set<&M::bond, &B::tensile_strength_mean>,
        .si_group = "bond", .si_name = "tensile_strength_mean_pa", .core_field = "BondParams::tensile_strength_mean",
        .range = positive,
        .calibration = Calibration::free, .role = ParameterRole::strength_scale, .lower = 0.5, .upper = 100.0, .log_scale = true},
    MaterialParameter{.key = "cohesion_ratio", .unit = "-", .description = "c-bar / sigma-bar_c (calibration only)",
        .in_config = false, .get = cohesion_ratio_get, .set = cohesion_ratio_set,
        .calibration = Calibration::free, .lower = 0.5, .upper = 5.0, .log_scale = true},
    MaterialParameter{.key = "cohesion_mpa", .unit = "MPa", .description = "mean bond cohesion c-bar",
        .to_si = 1e6, .get = si_get<&M::bond, &B::cohesion_mean>, .set = si_set<&M::bond, &B::cohesion_mean>,
        .si_group = "bond", .si_name = "cohesion_mean_pa", .core_field = "BondParams::cohesion_mean",
        .range = positive,
        .calibration = Calibration::free, .role = ParameterRole::strength_scale, .lower = 0.5, .upper = 200.0, .log_scale = true,
        .scales_with = "tensile_strength_mpa"},
    MaterialParameter{.key = "strength_cv", .unit = "-",
        .description = "coefficient of variation of sigma-bar_c and c-bar together (calibration only)",
        .in_config = false, .get = strength_cv_get, .set = strength_cv_set,
        .calibration = Calibration::free, .lower = 0.0, .upper = 0.5},
    // ---- explicit paste: the interfacial-zone factors, config keys of [paste] ----
    MaterialParameter{.key = "itz_strength_factor", .unit = "-",
        .description = "paste-sand (ITZ) bond strengths / paste-paste, explicit paste only (config: [paste] itz_strength_factor)",
        .in_config = false, .paste_only = true,
        .get = si_get<&M::families, &M::FamilyBonds::itz_strength_factor>,
        .set = si_set<&M::families, &M::FamilyBonds::itz_strength_factor>,
        .range = positive,
        .calibration = Calibration::free, .lower = 0.25, .upper = 2.0, .log_scale = true},
    MaterialParameter{.key = "itz_modulus_factor", .unit = "-",
        .description = "paste-sand (ITZ) bond modulus / paste-paste, explicit paste only (config: [paste] itz_modulus_factor)",
        .in_config = false, .paste_only = true,
        .get = si_get<&M::families, &M::FamilyBonds::itz_modulus_factor>,
        .set = si_set<&M::families, &M::FamilyBonds::itz_modulus_factor>,
        .range = positive,
        .calibration = Calibration::free, .lower = 0.25, .upper = 2.0, .log_scale = true},
    MaterialParameter{.key = "bond_modulus_gpa", .unit = "GPa", .description = "E-bar, bond modulus",
        .to_si = 1e9, .get = si_get<&M::bond, &B::effective_modulus>, .set = si_set<&M::bond, &B::effective_modulus>,
        .si_group = "bond", .si_name = "effective_modulus_pa", .core_field = "BondParams::effective_modulus",
        .range = positive, .follows = "effective_modulus_gpa"},
    MaterialParameter{.key = "bond_stiffness_ratio", .unit = "-", .description = "kappa-bar of bonds",
        .get = si_get<&M::bond, &B::stiffness_ratio>, .set = si_set<&M::bond, &B::stiffness_ratio>,
        .si_group = "bond", .si_name = "stiffness_ratio", .core_field = "BondParams::stiffness_ratio",
        .range = positive, .follows = "stiffness_ratio"},
    MaterialParameter{.key = "tensile_strength_cv", .unit = "-", .description = "coefficient of variation of sigma-bar_c",
        .cv_of = "tensile_strength_mpa",
        .get = si_get<&M::bond, &B::tensile_strength_std>, .set = si_set<&M::bond, &B::tensile_strength_std>,
        .si_group = "bond", .si_name = "tensile_strength_std_pa", .core_field = "BondParams::tensile_strength_std",
        .range = non_negative},
    MaterialParameter{.key = "cohesion_cv", .unit = "-", .description = "coefficient of variation of c-bar",
        .cv_of = "cohesion_mpa",
        .get = si_get<&M::bond, &B::cohesion_std>, .set = si_set<&M::bond, &B::cohesion_std>,
        .si_group = "bond", .si_name = "cohesion_std_pa", .core_field = "BondParams::cohesion_std",
        .range = non_negative},
    MaterialParameter{.key = "platen_friction", .unit = "-", .description = "mu_w, grain-platen friction",
        .get = si_get<&M::platen_friction>, .set = si_set<&M::platen_friction>,
        .si_name = "platen_friction", .core_field = "MaterialParams::platen_friction",
        .range = non_negative},
    MaterialParameter{.key = "damping", .unit = "-", .description = "local damping during the test",
        .get = si_get<&M::damping>, .set = si_set<&M::damping>,
        .si_name = "damping", .core_field = "MaterialParams::damping",
        .range = unit_open_right},
    MaterialParameter{.key = "bond_seed", .unit = "-", .description = "seed of the bond strength draws", .integer = true,
        .get = si_get<&M::bond, &B::seed>, .set = si_set<&M::bond, &B::seed>,
        .get_int = int_get<&M::bond, &B::seed>, .set_int = int_set<&M::bond, &B::seed>,
        .si_group = "bond", .si_name = "seed",
        .range = non_negative},
};

// Rows of a field BondParams shares but only some laws use: each goes right after the rows of
// the first law it applies to (the order the ledger's material keys were written in).
const std::array kPartlySharedRows = {
    MaterialParameter{.key = "bond_replaces_contact", .unit = "-",
        .description = "true: while intact the bond replaces the linear contact (PFC softbond/flatjoint, one spring set); "
                       "false: bond and contact in parallel (every law but the parallel bond)",
        .models = kEveryModel & ~model_bit(BondModel::parallel_bond), .integer = true, .flag = true,
        .get = si_get<&M::bond, &B::replaces_contact>, .set = si_set<&M::bond, &B::replaces_contact>,
        .get_int = int_get<&M::bond, &B::replaces_contact>, .set_int = int_set<&M::bond, &B::replaces_contact>,
        .si_group = "bond", .si_name = "replaces_contact", .core_field = "BondParams::replaces_contact",
        .range = {0.0, 1.0, false, false}, .calibration = Calibration::fixed_only, .lower = 0.0, .upper = 1.0},
};
// clang-format on
#pragma GCC diagnostic pop

// --- a law's rows (Law::kParameters, core/<law>_law.hpp) as material-table rows ---------------

template <class Law, std::size_t I>
double law_row_get(const MaterialParams& m) {
    return Law::kParameters[I].field.get(m.bond.law<Law>());
}
template <class Law, std::size_t I>
void law_row_set(MaterialParams& m, double v) {
    Law::kParameters[I].field.set(m.bond.law<Law>(), v);
}
template <class Law, std::size_t I>
std::int64_t law_row_get_int(const MaterialParams& m) {
    return Law::kParameters[I].field.get_int(m.bond.law<Law>());
}
template <class Law, std::size_t I>
void law_row_set_int(MaterialParams& m, std::int64_t v) {
    Law::kParameters[I].field.set_int(m.bond.law<Law>(), v);
}

template <class Law, std::size_t I>
MaterialParameter law_row() {
    constexpr auto& row = Law::kParameters[I];
    MaterialParameter p;
    p.key = row.key;
    p.unit = row.unit;
    p.description = row.description;
    p.models = model_bit(bond_model_of<Law>);
    p.integer = row.field.integer;
    p.flag = row.field.flag;
    p.to_si = row.to_si;
    p.get = law_row_get<Law, I>;
    p.set = law_row_set<Law, I>;
    if (row.field.integer) {
        p.get_int = law_row_get_int<Law, I>;
        p.set_int = law_row_set_int<Law, I>;
    }
    p.si_group = bond_model_name(bond_model_of<Law>);
    p.si_name = row.key;
    p.core_field = row.core_field;
    p.range = row.range;
    p.calibration = row.calibration;
    p.role = row.role;
    p.lower = row.lower;
    p.upper = row.upper;
    p.log_scale = row.log_scale;
    return p;
}

template <class Law>
void append_law_rows(std::vector<MaterialParameter>& table) {
    [&]<std::size_t... I>(std::index_sequence<I...>) {
        (table.push_back(law_row<Law, I>()), ...);
    }(std::make_index_sequence<Law::kParameters.size()>{});
}

/// The common rows, then each law's rows in BondModel order (with the partly shared rows).
const std::vector<MaterialParameter>& table_rows() {
    static const std::vector<MaterialParameter> rows = [] {
        std::vector<MaterialParameter> out(kCommonRows.begin(), kCommonRows.end());
        std::vector<bool> placed(kPartlySharedRows.size(), false);
        for_each_bond_law([&](auto kernel) {
            using Law = decltype(kernel);
            append_law_rows<Law>(out);
            for (std::size_t k = 0; k < kPartlySharedRows.size(); ++k)
                if (!placed[k] && kPartlySharedRows[k].applies_to(bond_model_of<Law>)) {
                    out.push_back(kPartlySharedRows[k]);
                    placed[k] = true;
                }
        });
        return out;
    }();
    return rows;
}

std::string show(double v) {
    std::ostringstream out;
    out << v;
    return out.str();
}

/// Sets a row's SI value; the coefficients of variation of rows that are its cv keep their value.
void set_keeping_cv(const MaterialParameter& p, MaterialParams& m, double si) {
    std::vector<std::pair<const MaterialParameter*, double>> cvs;
    for (const MaterialParameter& q : table_rows())
        if (q.cv_of == p.key) cvs.emplace_back(&q, config_value(q, m));
    p.set(m, si);
    for (const auto& [q, cv] : cvs) set_config_value(*q, m, cv);
}

}  // namespace

std::span<const MaterialParameter> material_table() { return table_rows(); }

const MaterialParameter* find_material_parameter(std::string_view key) {
    for (const MaterialParameter& p : table_rows())
        if (p.key == key) return &p;
    return nullptr;
}

const MaterialParameter* material_parameter_of_field(std::string_view field) {
    constexpr std::string_view prefix = "material.";
    if (field.starts_with(prefix)) return find_material_parameter(field.substr(prefix.size()));
    for (const MaterialParameter& p : table_rows())
        if (!p.core_field.empty() && p.core_field == field) return &p;
    return nullptr;
}

double config_value(const MaterialParameter& p, const MaterialParams& m) {
    if (!p.in_config) return p.get(m);
    if (!p.cv_of.empty()) return cv_of(p.get(m), find_material_parameter(p.cv_of)->get(m));
    return p.get(m) / p.to_si;
}

void set_config_value(const MaterialParameter& p, MaterialParams& m, double value) {
    if (!p.in_config) return p.set(m, value);
    if (!p.cv_of.empty()) return p.set(m, value * find_material_parameter(p.cv_of)->get(m));
    p.set(m, value * p.to_si);
}

void apply_calibration_value(const MaterialParameter& p, MaterialParams& m, double value) {
    if (!p.in_config) return p.set(m, value);  // a derived parameter knows its own rule
    const double before = p.get(m);
    set_keeping_cv(p, m, p.cv_of.empty() ? value * p.to_si : value * find_material_parameter(p.cv_of)->get(m));
    const double after = p.get(m);
    for (const MaterialParameter& q : table_rows()) {
        if (q.follows == p.key) set_keeping_cv(q, m, after);
        if (q.scales_with == p.key && before > 0.0) set_keeping_cv(q, m, q.get(m) / before * after);
    }
}

std::optional<std::string> material_range_violation(const MaterialParams& m) {
    for (const MaterialParameter& p : table_rows()) {
        if (!p.in_config || !p.applies_to(m.bond.model)) continue;
        const double v = p.integer ? static_cast<double>(p.get_int(m)) : config_value(p, m);
        if (!p.range.contains(v))
            return "material." + std::string(p.key) + " = " + show(v) + " violates " + p.range.rule();
    }
    return std::nullopt;
}

const std::vector<BondModel>& bond_models() {
    static const std::vector<BondModel> models = [] {
        std::vector<BondModel> out;
        for_each_bond_law([&](auto kernel) { out.push_back(bond_model_of<decltype(kernel)>); });
        return out;
    }();
    return models;
}

std::string model_names(ModelSet models) {
    std::string out;
    for (BondModel b : bond_models())
        if (models & model_bit(b)) out += (out.empty() ? "" : ", ") + std::string(bond_model_name(b));
    return out;
}

std::string bond_model_names() { return model_names(kEveryModel); }

}  // namespace gradem::exp
