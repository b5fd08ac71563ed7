#include "core/params.hpp"

#include <cmath>
#include <cstddef>
#include <sstream>
#include <stdexcept>

namespace gradem {
namespace {

// Builds "Struct::field = value violates rule" (the Ceres message shape).
std::string violation(const char* field, double value, const char* rule) {
    std::ostringstream out;
    out << field << " = " << value << " violates " << rule;
    return out.str();
}

bool positive(double v) { return std::isfinite(v) && v > 0.0; }
bool non_negative(double v) { return std::isfinite(v) && v >= 0.0; }

// A law's parameters: each row's range (on value / to_si, config units), then the law's own
// rules across fields (Law::invalid_reason, if it has one).
template <class Law>
std::optional<std::string> law_rows_invalid_reason(const typename Law::Params& own) {
    for (const auto& row : Law::kParameters) {
        const double value = row.field.integer ? static_cast<double>(row.field.get_int(own)) : row.field.get(own);
        if (!row.range.contains(value / row.to_si))
            return violation(std::string(row.core_field).c_str(), value, row.range.rule().c_str());
    }
    if constexpr (requires { Law::invalid_reason(own); }) return Law::invalid_reason(own);
    return std::nullopt;
}

}  // namespace

const char* bond_model_name(BondModel model) { return to_string(model); }

std::optional<BondModel> parse_bond_model(const std::string& name) { return parse_enum<BondModel>(name); }

std::optional<std::string> ContactParams::invalid_reason() const {
    if (!positive(effective_modulus))
        return violation("ContactParams::effective_modulus", effective_modulus, "> 0");
    if (!positive(stiffness_ratio))
        return violation("ContactParams::stiffness_ratio", stiffness_ratio, "> 0");
    if (!non_negative(friction)) return violation("ContactParams::friction", friction, ">= 0");
    return std::nullopt;
}

std::optional<std::string> BondParams::invalid_reason() const {
    if (!positive(effective_modulus))
        return violation("BondParams::effective_modulus", effective_modulus, "> 0");
    if (!positive(stiffness_ratio))
        return violation("BondParams::stiffness_ratio", stiffness_ratio, "> 0");
    if (!(radius_multiplier > 0.0 && radius_multiplier <= 1.0))
        return violation("BondParams::radius_multiplier", radius_multiplier, "in (0, 1]");
    if (!(moment_factor >= 0.0 && moment_factor <= 1.0))
        return violation("BondParams::moment_factor", moment_factor, "in [0, 1]");
    if (!positive(tensile_strength_mean))
        return violation("BondParams::tensile_strength_mean", tensile_strength_mean, "> 0");
    if (!non_negative(tensile_strength_std))
        return violation("BondParams::tensile_strength_std", tensile_strength_std, ">= 0");
    if (!positive(cohesion_mean))
        return violation("BondParams::cohesion_mean", cohesion_mean, "> 0");
    if (!non_negative(cohesion_std))
        return violation("BondParams::cohesion_std", cohesion_std, ">= 0");
    if (!(friction_angle_deg >= 0.0 && friction_angle_deg < 90.0))
        return violation("BondParams::friction_angle_deg", friction_angle_deg, "in [0, 90)");
    std::optional<std::string> reason;
    for_each_bond_law([&](auto kernel) {
        using Law = decltype(kernel);
        if (!reason) reason = law_rows_invalid_reason<Law>(law<Law>());
    });
    return reason;
}

std::optional<std::string> WallContactParams::invalid_reason() const {
    if (!positive(effective_modulus))
        return violation("WallContactParams::effective_modulus", effective_modulus, "> 0");
    if (!positive(stiffness_ratio))
        return violation("WallContactParams::stiffness_ratio", stiffness_ratio, "> 0");
    if (!non_negative(friction)) return violation("WallContactParams::friction", friction, ">= 0");
    return std::nullopt;
}

std::optional<std::string> SimParams::invalid_reason() const {
    if (!(local_damping >= 0.0 && local_damping < 1.0))
        return violation("SimParams::local_damping", local_damping, "in [0, 1)");
    if (!non_negative(time_step)) return violation("SimParams::time_step", time_step, ">= 0");
    if (!(time_step_safety > 0.0 && time_step_safety <= 1.0))
        return violation("SimParams::time_step_safety", time_step_safety, "in (0, 1]");
    if (!(skin_fraction > 0.0 && skin_fraction <= 2.0))
        return violation("SimParams::skin_fraction", skin_fraction, "in (0, 2]");
    if (!(divergence_energy_floor >= 0.0))
        return violation("SimParams::divergence_energy_floor", divergence_energy_floor, ">= 0");
    if (!positive(divergence_energy_factor))
        return violation("SimParams::divergence_energy_factor", divergence_energy_factor, "> 0");
    for (const double w : thread_share_weights)
        if (!positive(w)) return violation("SimParams::thread_share_weights", w, "finite and > 0");
    return std::nullopt;
}

void require_valid(const std::optional<std::string>& reason) {
    if (reason) throw std::invalid_argument(*reason);
}

}  // namespace gradem
