#pragma once
// JSON has no NaN or infinity: a value that is not finite (not measured, not converged) is
// written as null, which every reader (Python's json, the report generator) takes as missing.
#include <cmath>
#include <nlohmann/json.hpp>

namespace gradem::common {

/// `v`, or null when it is not finite. Json: nlohmann::json or nlohmann::ordered_json.
template <typename Json = nlohmann::json>
Json json_number(double v) {
    return std::isfinite(v) ? Json(v) : Json(nullptr);
}

}  // namespace gradem::common
