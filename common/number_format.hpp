#pragma once
// Numbers for people and for CSV cells, printf-style so every table formats alike. A value
// that is not finite (NaN: not measured, not converged) prints as `missing` ("-" in tables,
// "" in CSV cells).
#include <cmath>
#include <cstdio>
#include <string>

namespace gradem::common {

/// `digits` significant digits ("%.*g"): 12.35, 1.2e+04.
inline std::string format_significant(double v, int digits, const char* missing = "-") {
    if (!std::isfinite(v)) return missing;
    char buf[64];
    std::snprintf(buf, sizeof buf, "%.*g", digits, v);
    return buf;
}

/// `decimals` digits after the point ("%.*f"): 12.35.
inline std::string format_fixed(double v, int decimals, const char* missing = "-") {
    if (!std::isfinite(v)) return missing;
    char buf[64];
    std::snprintf(buf, sizeof buf, "%.*f", decimals, v);
    return buf;
}

}  // namespace gradem::common
