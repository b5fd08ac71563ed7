#pragma once
// The material-parameter table: ONE row per micro-parameter of MaterialParams. Everything that
// names, converts, checks, writes or calibrates a material parameter reads this table:
//   - the cube config reader ([material] keys, unit conversion, struct defaults, which keys a
//     bond model accepts)                                         experiments/cube_config.cpp
//   - the validator (MaterialParams::invalid_reason, ranges in config units)
//                                                                 experiments/cube_test.cpp
//   - the JSON writer (macro.json "material": SI and config units) experiments/cube_output.cpp
//   - the calibration (parameter names, units, roles, default bounds and scale, how a value is
//     applied; the ledger's material key)                        calibrate/parameters.cpp,
//                                                                 calibrate/cube_model.cpp
// A new bond law adds its param struct to core/params.hpp, its kernel to core/ and its rows
// here (models = that law); nothing else in experiments/ or calibrate/ changes.
//
// The row order is the order in which the calibration applies parameters (a strength mean
// before the cohesion ratio before the scatter), and the order of the config's keys in
// messages and macro.json.
#include <cstdint>
#include <limits>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "core/params.hpp"

namespace gradem::exp {

struct MaterialParams;

/// What the calibration does with a parameter (docs/calibration.md "Homogeneity"): the homogeneity acts on the
/// stiffness and strength scales; shape parameters are dimensionless.
enum class ParameterRole : std::uint8_t { stiffness_scale, strength_scale, shape };

/// The bond models a row applies to (a bit set over BondModel).
using ModelSet = std::uint32_t;
constexpr ModelSet model_bit(BondModel m) { return ModelSet{1} << static_cast<unsigned>(m); }
constexpr ModelSet kEveryModel = ~ModelSet{0};  ///< a row every bond model uses
/// Every BondModel core knows (those bond_model_name() names), in enum order: a new law in
/// core/params.hpp appears here without an edit.
const std::vector<BondModel>& bond_models();

/// Allowed values in config units: lower/upper bounds (infinite = none), each open or closed.
struct Range {
    double lower = -std::numeric_limits<double>::infinity(), upper = std::numeric_limits<double>::infinity();
    bool lower_open = false, upper_open = false;
    [[nodiscard]] bool contains(double v) const;
    [[nodiscard]] std::string rule() const;  ///< "> 0", ">= 0", "in (0, 1]", ...
};

/// How the calibration may use a row.
enum class Calibration : std::uint8_t {
    none,        ///< not a calibration parameter (set in the base cube config only)
    free,        ///< a calibration parameter: fixed or free in [parameters.<key>]
    fixed_only,  ///< integer parameter: may be fixed in [parameters.<key>], never free
};

struct MaterialParameter {
    std::string_view key;          ///< [material] config key = calibration parameter name
    std::string_view unit;         ///< config unit: "GPa", "MPa", "um", "deg", "-"
    std::string_view description;  ///< what it is (README and messages)
    ModelSet models = kEveryModel; ///< bond models that use it
    bool integer = false;          ///< integer-valued (counts, seeds)
    bool flag = false;             ///< a yes/no (an integer row 0/1; the config takes true/false)
    bool in_config = true;         ///< false: a calibration-only reparametrisation (no config key)
    bool paste_only = false;       ///< acts on explicit-paste specimens only (their paste-sand bonds)

    // --- SI storage in MaterialParams -------------------------------------------------------
    double to_si = 1.0;            ///< SI value = config value × to_si (unless cv_of is set)
    std::string_view cv_of;        ///< a coefficient of variation: SI std = cv × (that row's SI mean)
    double (*get)(const MaterialParams&) = nullptr;   ///< SI value (or the config value of a derived row)
    void (*set)(MaterialParams&, double) = nullptr;   ///< sets the SI value (derived rows: config value)
    std::int64_t (*get_int)(const MaterialParams&) = nullptr;  ///< integer rows: exact value
    void (*set_int)(MaterialParams&, std::int64_t) = nullptr;  ///< integer rows: sets it (range checked first)
    std::string_view si_group;     ///< macro.json "si" sub-object ("contact", "bond", "soft_bond", ...; "" top level)
    std::string_view si_name;      ///< its key there (with the SI unit)
    std::string_view core_field;   ///< how core/params.cpp's validators name it ("BondParams::friction_angle_deg")

    // --- the allowed values, and relations between rows --------------------------------------
    Range range;                   ///< in config units
    std::string_view follows;      ///< if absent from the config: that row's value; calibration sets both

    // --- calibration -------------------------------------------------------------------------
    Calibration calibration = Calibration::none;
    ParameterRole role = ParameterRole::shape;
    double lower = 0.0, upper = 0.0;  ///< default calibration bounds, config units
    bool log_scale = false;           ///< default calibration scale
    std::string_view scales_with;     ///< calibration: when that row is set, this one keeps its ratio to it

    [[nodiscard]] bool applies_to(BondModel m) const { return (models & model_bit(m)) != 0; }
};

/// Every row, in application order.
std::span<const MaterialParameter> material_table();
/// The row with this config key / calibration name, or nullptr.
const MaterialParameter* find_material_parameter(std::string_view key);
/// The row whose core validator field ("BondParams::x") or "material.<key>" is `field`, or nullptr.
const MaterialParameter* material_parameter_of_field(std::string_view field);

/// The row's value in config units (GPa, MPa, cv, ...).
double config_value(const MaterialParameter& p, const MaterialParams& m);
/// Sets the row's field from a config-unit value, nothing else (what the config reader does).
void set_config_value(const MaterialParameter& p, MaterialParams& m, double value);
/// Sets a calibration parameter (config units) the way the calibration varies it: rows that
/// follow it get the same value, a mean keeps its coefficient of variation, and rows that
/// scale with it keep their ratio to it.
void apply_calibration_value(const MaterialParameter& p, MaterialParams& m, double value);

/// The first row (applying to m's bond model) whose value is outside its range, as
/// "material.<key> = <config value> violates <rule>"; nullopt when every row is in range.
std::optional<std::string> material_range_violation(const MaterialParams& m);

/// "parallel_bond, soft_bond, flat_joint" (the names a model key accepts).
std::string bond_model_names();
/// The names of the models in a set, "soft_bond" or "soft_bond, flat_joint".
std::string model_names(ModelSet models);

}  // namespace gradem::exp
