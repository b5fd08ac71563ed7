#pragma once
// Grain diameters drawn from a measured gradation curve BY MASS: the solid volume in each sieve
// interval follows the curve's mass fraction, and inside an interval the mass is spread
// uniformly in log(size) (the curve is interpolated linearly in log size), so the number of
// small grains follows from the curve (number density ∝ d^-4 in d). Explicit size rules make a
// reduced specimen possible: a lower cut-off (the fines are left to the bond phase), an optional
// upper cut-off, and an optional uniform upscaling of all sizes.
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "lab_data/gradation.hpp"

namespace gradem::exp {

struct SizeRule {
    double min_diameter = 0.149e-3;  ///< grains finer than this are left out [m] (No. 100 sieve)
    double max_diameter = 0.0;       ///< grains coarser are left out [m]; 0 = keep all
    double scale = 1.0;              ///< every kept diameter is multiplied by this [-]
    [[nodiscard]] std::optional<std::string> invalid_reason() const;
};

struct GrainSample {
    std::vector<double> diameters;        ///< sampled diameters after scaling [m], shuffled
    double removed_fine_fraction = 0.0;   ///< mass fraction of the curve below the lower cut-off
    double removed_coarse_fraction = 0.0; ///< mass fraction above the upper cut-off
    std::vector<double> sieve_sizes;      ///< sieves inside the kept range (unscaled) [m]
    std::vector<double> target_passing;   ///< curve passing, renormalised to the kept range [0,1]
    std::vector<double> achieved_passing; ///< passing of the sampled grains (by mass) [0,1]
    double max_deviation = 0.0;           ///< max |achieved - target| [fraction]
    double d50 = 0.0;                     ///< mass median diameter of the sample, scaled [m]
    double solid_volume = 0.0;            ///< total grain volume [m^3]
};

/// Samples grains with a total volume of about `solid_volume` [m^3]. Throws
/// std::invalid_argument when the curve cannot be sampled (nothing left between the cut-offs).
GrainSample sample_grains(const lab::GradationCurve& curve, const SizeRule& rule,
                          double solid_volume, std::uint64_t seed);

}  // namespace gradem::exp
