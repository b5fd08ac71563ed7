#pragma once
// Material keys on a bench program's command line (gradem-bench, gradem-model-sweep): `--set
// key=value` and `--sweep key=v1,v2,...` name rows of the material table
// (experiments/config/material_table.hpp) in its config units, and are applied as the
// calibration applies them (a strength mean keeps its coefficient of variation, rows that follow
// or scale with it move with it). gradem-bench's settings may be scoped to one bond model:
// `<model>:bond_gap_um=20` applies to that model's rows only.
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "bench/bench_args.hpp"
#include "core/bond_models.hpp"
#include "experiments/config/material_table.hpp"
#include "experiments/virtual_tests/cube_test.hpp"

namespace gradem::bench {

/// One material key with one value, or (a sweep) several; `model` scopes it to one bond model.
struct MaterialSetting {
    std::optional<BondModel> model;  ///< empty: every model whose rows have the key
    std::string key;                 ///< a material-table key, e.g. "bond_gap_um"
    std::vector<double> values;      ///< config units; one value for --set
};

/// The material-table row of `key`, or a UsageError.
inline const exp::MaterialParameter& material_row(const std::string& key) {
    const exp::MaterialParameter* p = exp::find_material_parameter(key);
    if (!p) throw UsageError("unknown material key '" + key + "' (see experiments/config/material_table.cpp)");
    return *p;
}

/// `[model:]key=v1,v2,...` of option `option` (--set takes exactly one value).
inline MaterialSetting parse_material_setting(const std::string& option, const std::string& text) {
    MaterialSetting s;
    const auto eq = text.find('=');
    if (eq == std::string::npos) throw UsageError(option + " " + text + ": expected [model:]key=value");
    std::string key = text.substr(0, eq);
    if (const auto colon = key.find(':'); colon != std::string::npos) {
        const std::string model = key.substr(0, colon);
        s.model = parse_bond_model(model);
        if (!s.model) throw UsageError(option + " " + text + ": unknown bond model '" + model + "' (" + exp::bond_model_names() + ")");
        key = key.substr(colon + 1);
    }
    s.key = key;
    const exp::MaterialParameter& row = material_row(key);
    if (s.model && !row.applies_to(*s.model))
        throw UsageError(option + " " + text + ": material key '" + key + "' belongs to " + exp::model_names(row.models));
    s.values = parse_number_list<double>(text.substr(eq + 1), option + " " + key);
    if (option == "--set" && s.values.size() != 1) throw UsageError(option + " " + text + ": expected one value");
    return s;
}

/// Whether `s` applies to a row of bond model `model`.
inline bool setting_applies(const MaterialSetting& s, BondModel model) {
    return (!s.model || *s.model == model) && material_row(s.key).applies_to(model);
}

/// Sets `key` of m to `value` (config units) as the calibration sets it.
inline void apply_material_value(exp::MaterialParams& m, const std::string& key, double value) {
    const exp::MaterialParameter& p = material_row(key);
    if (!p.applies_to(m.bond.model))
        throw UsageError("material key '" + key + "' belongs to " + exp::model_names(p.models));
    if (p.integer) p.set_int(m, static_cast<std::int64_t>(value));
    else exp::apply_calibration_value(p, m, value);
}

/// A bench row's material: contact and bond E* `modulus` [Pa], k_n/k_s 1.5, μ 0.5, σ̄_c
/// `tensile_strength` and c̄ `cohesion` [Pa] with cv 0.2, bonding gap `gap` [m] (0: the
/// packing's own), every law's other parameters at their defaults; then `settings` (config
/// units, as --set gives them). The caller checks it.
inline exp::MaterialParams bench_material(BondModel model, double modulus, double tensile_strength, double cohesion,
                                          double gap, const std::vector<std::pair<std::string, double>>& settings) {
    exp::MaterialParams m;
    m.contact.effective_modulus = modulus;
    m.contact.stiffness_ratio = 1.5;
    m.contact.friction = 0.5;
    m.bond.model = model;
    m.bond.effective_modulus = modulus;
    m.bond.stiffness_ratio = 1.5;
    m.bond.tensile_strength_mean = tensile_strength;
    m.bond.tensile_strength_std = 0.2 * tensile_strength;
    m.bond.cohesion_mean = cohesion;
    m.bond.cohesion_std = 0.2 * cohesion;
    m.bond_gap_absolute = gap;
    for (const auto& [key, value] : settings) apply_material_value(m, key, value);
    return m;
}

}  // namespace gradem::bench
