#pragma once
// When a calibrated target counts as met: |simulated seed mean / lab mean − 1| within the
// quantity's tolerance: modulus and peak within 5 %, strain at peak within 10 % (the strain
// at peak scatters more in the lab (its coefficient
// of variation is about twice the peak's) and is the quantity the bond models' shape sets.
// The direct-tension strength, when fitted, is met by its own rule (tension_met).
// The one place the calibration summary (md, json, html) and the studies read them.
#include <cmath>

#include "calibrate/problem.hpp"

namespace gradem::cal {

struct TargetTolerances {
    double modulus = 0.05;  ///< chord modulus [relative]
    double peak = 0.05;     ///< peak stress [relative]
    double strain = 0.10;   ///< strain at peak [relative]
    [[nodiscard]] constexpr double of(Quantity q) const {
        return q == Quantity::modulus ? modulus : q == Quantity::peak ? peak : strain;
    }
};

inline constexpr TargetTolerances kTargetTolerances{};

/// Is a relative error (simulated / lab − 1) within the quantity's tolerance? NaN: not met.
/// (For the compression test's quantities; the tension target has its own rule, below.)
inline bool target_met(Quantity q, double rel_error) {
    return std::isfinite(rel_error) && std::fabs(rel_error) <= kTargetTolerances.of(q);
}

/// Is the direct-tension target met? From the lab: |σt,sim/σt,lab − 1| <= its tolerance; from
/// an assumed ratio: the simulated σc,sim/σt,sim within the assumed band (the ratio is what is
/// known, not σt). NaN inputs: not met.
inline bool tension_met(const TensionTarget& t, double rel_error, double simulated_ratio) {
    if (t.assumed()) return std::isfinite(simulated_ratio) && simulated_ratio >= t.ratio_low && simulated_ratio <= t.ratio_high;
    return std::isfinite(rel_error) && std::fabs(rel_error) <= t.tolerance;
}

}  // namespace gradem::cal
