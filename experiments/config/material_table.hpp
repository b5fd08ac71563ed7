#pragma once
// The material-parameter table: ONE row per micro-parameter of MaterialParams. Everything that
// names, converts, checks, writes or calibrates a material parameter reads this table:
//   - the cube config reader ([material] keys, unit conversion, struct defaults, which keys a
//     bond model accepts)                                         experiments/config/cube_config.cpp
//   - the validator (MaterialParams::invalid_reason, ranges in config units)
//                                                                 experiments/virtual_tests/cube_test.cpp
//   - the JSON writer (macro.json "material": SI and config units) reports/cube_output.cpp
//   - the calibration (parameter names, units, roles, default bounds and scale, how a value is
//     applied; the ledger's material key)                        calibrate/parameters.cpp,
//                                                                 calibrate/cube_model.cpp
// The rows of every bond model come first, written out below; each bond law's own rows are
// appended from its header (Law::kParameters, core/law_parameters.hpp) with models = that law
// and si_group = its name (core/bond_models.hpp): a new law changes nothing in experiments/ or
// calibrate/.
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

#include "core/law_parameters.hpp"
#include "core/params.hpp"

namespace gradem::exp {

struct MaterialParams;

using gradem::Calibration;    // what the calibration may do with a row (core/law_parameters.hpp)
using gradem::ParameterRole;  // stiffness scale, strength scale or shape
using gradem::Range;          // allowed values in config units

/// The bond models a row applies to (a bit set over BondModel).
using ModelSet = std::uint32_t;
constexpr ModelSet model_bit(BondModel m) { return ModelSet{1} << static_cast<unsigned>(m); }
constexpr ModelSet kEveryModel = ~ModelSet{0};  ///< a row every bond model uses
/// Every BondModel core knows (the rows of core/bond_models.hpp), in enum order.
const std::vector<BondModel>& bond_models();

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
    std::string_view si_group;     ///< macro.json "si" sub-object ("contact", "bond", a law's name; "" top level)
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

/// Every model's name, comma separated (the names a model key accepts).
std::string bond_model_names();
/// The names of the models in a set, comma separated.
std::string model_names(ModelSet models);

}  // namespace gradem::exp
