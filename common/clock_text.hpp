#pragma once
// Durations for people: "4m05s", "1h12m"; "?" for an unknown (NaN or negative) duration.
#include <cmath>
#include <cstdio>
#include <string>

namespace gradem::common {

inline std::string clock_text(double seconds) {
    if (!std::isfinite(seconds) || seconds < 0) return "?";
    const long s = std::lround(seconds);
    char buf[32];
    if (s >= 3600) std::snprintf(buf, sizeof buf, "%ldh%02ldm", s / 3600, (s / 60) % 60);
    else std::snprintf(buf, sizeof buf, "%ldm%02lds", s / 60, s % 60);
    return buf;
}

}  // namespace gradem::common
