#pragma once
// JSON has no NaN or infinity: a value that is not finite (not measured, not converged) is
// written as null, which every reader (Python's json, the report generator) takes as missing,
// and read back as NaN.
#include <cmath>
#include <nlohmann/json.hpp>

namespace gradem::common {

/// `v`, or null when it is not finite. Json: nlohmann::json or nlohmann::ordered_json.
template <typename Json = nlohmann::json>
Json json_number(double v) {
    return std::isfinite(v) ? Json(v) : Json(nullptr);
}

/// The reverse: `object[key]` as a double, NaN when the key is absent, null or not a number.
template <typename Json>
double number_or_nan(const Json& object, const char* key) {
    const auto it = object.find(key);
    return it != object.end() && it->is_number() ? it->template get<double>() : std::nan("");
}

}  // namespace gradem::common
