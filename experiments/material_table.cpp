// The material-parameter table (material_table.hpp) and the operations every reader of it
// shares: unit conversion, range checks, and how the calibration applies a value.
#include "experiments/material_table.hpp"

#include <array>
#include <cmath>
#include <sstream>
#include <type_traits>
#include <vector>

#include "experiments/cube_test.hpp"

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

constexpr double kInf = std::numeric_limits<double>::infinity();
constexpr Range positive{0.0, kInf, true, false};       // > 0
constexpr Range non_negative{0.0, kInf, false, false};  // >= 0
constexpr Range unit_open_right{0.0, 1.0, false, true}; // in [0, 1)
constexpr Range unit_closed{0.0, 1.0, false, false};    // in [0, 1]

constexpr ModelSet kSoftBond = model_bit(BondModel::soft_bond);
constexpr ModelSet kFlatJoint = model_bit(BondModel::flat_joint);

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
const std::array kTable = {
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
    // ---- soft bond (docs/bond_laws.md "Soft bond") ----
    MaterialParameter{.key = "softening_factor", .unit = "-",
        .description = "zeta, softening slope / bond normal stiffness (soft_bond)", .models = kSoftBond,
        .get = si_get<&M::bond, &B::soft, &SoftBondParams::softening_factor>,
        .set = si_set<&M::bond, &B::soft, &SoftBondParams::softening_factor>,
        .si_group = "soft_bond", .si_name = "softening_factor", .core_field = "SoftBondParams::softening_factor",
        .range = positive,
        .calibration = Calibration::free, .lower = 0.05, .upper = 1.0, .log_scale = true},
    MaterialParameter{.key = "cut_fraction", .unit = "-",
        .description = "gamma, the bond breaks once its softened stress <= gamma x sigma-bar_c (soft_bond)", .models = kSoftBond,
        .get = si_get<&M::bond, &B::soft, &SoftBondParams::cut_fraction>,
        .set = si_set<&M::bond, &B::soft, &SoftBondParams::cut_fraction>,
        .si_group = "soft_bond", .si_name = "cut_fraction", .core_field = "SoftBondParams::cut_fraction",
        .range = unit_open_right,
        .calibration = Calibration::free, .lower = 0.0, .upper = 0.5},
    // ---- soft bond and flat joint: one spring set (docs/bond_laws.md) ----
    MaterialParameter{.key = "bond_replaces_contact", .unit = "-",
        .description = "true: while intact the bond replaces the linear contact (PFC softbond/flatjoint, one spring set); "
                       "false: bond and contact in parallel (soft_bond, flat_joint)",
        .models = kSoftBond | kFlatJoint, .integer = true, .flag = true,
        .get = si_get<&M::bond, &B::replaces_contact>, .set = si_set<&M::bond, &B::replaces_contact>,
        .get_int = int_get<&M::bond, &B::replaces_contact>, .set_int = int_set<&M::bond, &B::replaces_contact>,
        .si_group = "bond", .si_name = "replaces_contact", .core_field = "BondParams::replaces_contact",
        .range = {0.0, 1.0, false, false}, .calibration = Calibration::fixed_only, .lower = 0.0, .upper = 1.0},
    // ---- flat joint (docs/bond_laws.md "Flat joint") ----
    MaterialParameter{.key = "radial_elements", .unit = "-", .description = "N_r, elements across the joint radius (flat_joint)",
        .models = kFlatJoint, .integer = true,
        .get = si_get<&M::bond, &B::flat, &FlatJointParams::radial_elements>,
        .set = si_set<&M::bond, &B::flat, &FlatJointParams::radial_elements>,
        .get_int = int_get<&M::bond, &B::flat, &FlatJointParams::radial_elements>,
        .set_int = int_set<&M::bond, &B::flat, &FlatJointParams::radial_elements>,
        .si_group = "flat_joint", .si_name = "radial_elements", .core_field = "FlatJointParams::radial_elements",
        .range = {1.0, 64.0, false, false}, .calibration = Calibration::fixed_only, .lower = 1.0, .upper = 64.0},
    MaterialParameter{.key = "angular_elements", .unit = "-", .description = "N_alpha, elements around the joint (flat_joint)",
        .models = kFlatJoint, .integer = true,
        .get = si_get<&M::bond, &B::flat, &FlatJointParams::angular_elements>,
        .set = si_set<&M::bond, &B::flat, &FlatJointParams::angular_elements>,
        .get_int = int_get<&M::bond, &B::flat, &FlatJointParams::angular_elements>,
        .set_int = int_set<&M::bond, &B::flat, &FlatJointParams::angular_elements>,
        .si_group = "flat_joint", .si_name = "angular_elements", .core_field = "FlatJointParams::angular_elements",
        .range = {1.0, 64.0, false, false}, .calibration = Calibration::fixed_only, .lower = 1.0, .upper = 64.0},
    MaterialParameter{.key = "residual_friction", .unit = "-",
        .description = "mu of a broken joint element (flat_joint)", .models = kFlatJoint,
        .get = si_get<&M::bond, &B::flat, &FlatJointParams::residual_friction>,
        .set = si_set<&M::bond, &B::flat, &FlatJointParams::residual_friction>,
        .si_group = "flat_joint", .si_name = "residual_friction", .core_field = "FlatJointParams::residual_friction",
        .range = non_negative,
        .calibration = Calibration::free, .lower = 0.2, .upper = 1.0},
    MaterialParameter{.key = "bonded_fraction", .unit = "-",
        .description = "phi_B, fraction of joints installed bonded (flat_joint; the rest gapped or slit)",
        .models = kFlatJoint,
        .get = si_get<&M::bond, &B::flat, &FlatJointParams::bonded_fraction>,
        .set = si_set<&M::bond, &B::flat, &FlatJointParams::bonded_fraction>,
        .si_group = "flat_joint", .si_name = "bonded_fraction", .core_field = "FlatJointParams::bonded_fraction",
        .range = unit_closed, .calibration = Calibration::free, .lower = 0.3, .upper = 1.0},
    MaterialParameter{.key = "gapped_fraction", .unit = "-",
        .description = "phi_G, fraction of joints installed unbonded with an initial gap (flat_joint; slit = 1 - phi_B - phi_G)",
        .models = kFlatJoint,
        .get = si_get<&M::bond, &B::flat, &FlatJointParams::gapped_fraction>,
        .set = si_set<&M::bond, &B::flat, &FlatJointParams::gapped_fraction>,
        .si_group = "flat_joint", .si_name = "gapped_fraction", .core_field = "FlatJointParams::gapped_fraction",
        .range = unit_closed, .calibration = Calibration::free, .lower = 0.0, .upper = 0.5},
    MaterialParameter{.key = "gap_ratio", .unit = "-",
        .description = "g_0 / joint radius, the initial gap of a gapped joint (flat_joint)",
        .models = kFlatJoint,
        .get = si_get<&M::bond, &B::flat, &FlatJointParams::gap_ratio>,
        .set = si_set<&M::bond, &B::flat, &FlatJointParams::gap_ratio>,
        .si_group = "flat_joint", .si_name = "gap_ratio", .core_field = "FlatJointParams::gap_ratio",
        .range = non_negative, .calibration = Calibration::free, .lower = 0.0, .upper = 0.05},
    MaterialParameter{.key = "stiffness_over_gap", .unit = "-",
        .description = "true: a joint installed across a gap g has k_n = E*/(R_A + R_B + g) (a bridge as long as the "
                       "centre distance); false: E*/(R_A + R_B) (flat_joint)",
        .models = kFlatJoint, .integer = true, .flag = true,
        .get = si_get<&M::bond, &B::flat, &FlatJointParams::stiffness_over_gap>,
        .set = si_set<&M::bond, &B::flat, &FlatJointParams::stiffness_over_gap>,
        .get_int = int_get<&M::bond, &B::flat, &FlatJointParams::stiffness_over_gap>,
        .set_int = int_set<&M::bond, &B::flat, &FlatJointParams::stiffness_over_gap>,
        .si_group = "flat_joint", .si_name = "stiffness_over_gap", .core_field = "FlatJointParams::stiffness_over_gap",
        .range = {0.0, 1.0, false, false}, .calibration = Calibration::fixed_only, .lower = 0.0, .upper = 1.0},
};
// clang-format on
#pragma GCC diagnostic pop

std::string show(double v) {
    std::ostringstream out;
    out << v;
    return out.str();
}

/// Sets a row's SI value; the coefficients of variation of rows that are its cv keep their value.
void set_keeping_cv(const MaterialParameter& p, MaterialParams& m, double si) {
    std::vector<std::pair<const MaterialParameter*, double>> cvs;
    for (const MaterialParameter& q : kTable)
        if (q.cv_of == p.key) cvs.emplace_back(&q, config_value(q, m));
    p.set(m, si);
    for (const auto& [q, cv] : cvs) set_config_value(*q, m, cv);
}

}  // namespace

bool Range::contains(double v) const {
    if (!std::isfinite(v)) return false;
    if (lower_open ? !(v > lower) : !(v >= lower)) return false;
    if (upper_open ? !(v < upper) : !(v <= upper)) return false;
    return true;
}

std::string Range::rule() const {
    if (std::isinf(upper)) return std::string(lower_open ? "> " : ">= ") + show(lower);
    if (std::isinf(lower)) return std::string(upper_open ? "< " : "<= ") + show(upper);
    return std::string("in ") + (lower_open ? "(" : "[") + show(lower) + ", " + show(upper) + (upper_open ? ")" : "]");
}

std::span<const MaterialParameter> material_table() { return kTable; }

const MaterialParameter* find_material_parameter(std::string_view key) {
    for (const MaterialParameter& p : kTable)
        if (p.key == key) return &p;
    return nullptr;
}

const MaterialParameter* material_parameter_of_field(std::string_view field) {
    constexpr std::string_view prefix = "material.";
    if (field.starts_with(prefix)) return find_material_parameter(field.substr(prefix.size()));
    for (const MaterialParameter& p : kTable)
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
    for (const MaterialParameter& q : kTable) {
        if (q.follows == p.key) set_keeping_cv(q, m, after);
        if (q.scales_with == p.key && before > 0.0) set_keeping_cv(q, m, q.get(m) / before * after);
    }
}

std::optional<std::string> material_range_violation(const MaterialParams& m) {
    for (const MaterialParameter& p : kTable) {
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
        for (unsigned k = 0; k < 32; ++k) {
            const auto m = static_cast<BondModel>(k);
            if (parse_bond_model(bond_model_name(m)) != m) break;  // past the last law core names
            out.push_back(m);
        }
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
