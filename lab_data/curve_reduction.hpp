#pragma once
// Reduction of one compression curve to the calibration targets. The same function serves lab
// cubes and simulated DEM specimens, so a definition can never differ between the two.
//
// Conventions: SI units; compression positive for stress and strain.
//   peak stress      ASTM C109/C109M §11: compressive strength = maximum load / loaded area,
//                    i.e. the largest stress sample (no smoothing).
//   strain at peak   strain at the vertex of a parabola fitted to the ascending-branch samples
//                    within `peak_window_fraction` of the peak (falls back to the strain of the
//                    largest sample when the parabola has no maximum there). The ascending side
//                    alone is used because cubes often soften abruptly after the peak.
//   chord modulus    ASTM C469/C469M §7 (modulus of elasticity): E = (S2 − S1)/(ε2 − 0.000050)
//                    with S2 = 40 % of ultimate stress, ε2 the strain at S2, S1 the stress at
//                    ε1 = 50 µε. Both points are read on the ascending branch by local
//                    least-squares lines over a narrow window (robust to sampling noise).
//   tangent modulus  slope dσ/dε of a least-squares line over stresses within ±5 % of peak
//                    about 50 % of peak on the ascending branch.
//   Poisson's ratio  ASTM C469 §7: (εt2 − εt1)/(ε2 − 0.000050), if a lateral strain is given.
//   Popovics fit     σ = f'c·n·(ε/ε'c)/(n − 1 + (ε/ε'c)^n), n = E/(E − f'c/ε'c) (Popovics 1973),
//                    least squares with Ceres on the ascending branch, standard errors from
//                    the covariance of the fit.

#include <cstddef>
#include <optional>
#include <string>
#include <vector>

#include "common/named_enum.hpp"

namespace gradem::lab {

/// A compression curve. `strain` and `stress_pa` are required and of equal length; the other
/// channels are optional (empty, or the same length).
struct StressStrainCurve {
    std::vector<double> strain;            ///< axial strain, compression positive [-] (extensometer in the lab)
    std::vector<double> stress_pa;         ///< axial stress, compression positive [Pa]
    std::vector<double> crosshead_strain;  ///< platen displacement / specimen height [-] (optional)
    std::vector<double> lateral_strain;    ///< lateral strain [-] (optional; for Poisson's ratio)
    std::vector<double> time_s;            ///< time [s] (optional; for the stress rate)
};

struct ReductionOptions {
    double chord_upper_fraction = 0.40;  ///< S2 as a fraction of peak (ASTM C469: 0.40)
    double chord_lower_strain = 50e-6;   ///< ε1 (ASTM C469: 50 millionths)
    double tangent_fraction = 0.50;      ///< stress level of the tangent modulus, fraction of peak
    double window_fraction = 0.05;       ///< half-width of the S2/tangent regression windows, fraction of peak
    double strain_window = 25e-6;        ///< half-width of the S1 regression window around ε1 [-]
    double peak_window_fraction = 0.01;  ///< ascending samples within this fraction below peak define the peak parabola
    bool fit_popovics = true;            ///< run the Ceres fit (skip for speed, e.g. in fuzzing)
    [[nodiscard]] std::optional<std::string> invalid_reason() const;
};

enum class ReductionStatus {
    ok,
    modulus_window_not_reached,  ///< the curve never spans ε1 .. S2 on its ascending branch
    invalid_curve,               ///< too few samples, non-finite values, or no compressive stress
};
constexpr EnumNameTable<ReductionStatus, 3> enum_name_table(ReductionStatus) {
    return {{{ReductionStatus::ok, "ok"},
             {ReductionStatus::modulus_window_not_reached, "modulus_window_not_reached"},
             {ReductionStatus::invalid_curve, "invalid_curve"}}};
}

struct PopovicsFit {
    bool converged = false;
    double elastic_modulus_pa = 0, elastic_modulus_se_pa = 0;  ///< initial tangent modulus E and its standard error
    double peak_stress_pa = 0, peak_stress_se_pa = 0;          ///< f'c
    double strain_at_peak = 0, strain_at_peak_se = 0;          ///< ε'c
    double n = 0;                                             ///< shape exponent
    double rms_residual_pa = 0;
    int points = 0;
    std::string message;
};

struct CurveReduction {
    ReductionStatus status = ReductionStatus::invalid_curve;
    std::string message;           ///< why status is not ok
    std::size_t peak_index = 0;    ///< sample with the largest stress
    std::size_t problem_index = 0; ///< sample the message refers to (for file:line)
    double peak_stress_pa = 0;
    double strain_at_peak = 0;
    double strain_at_peak_crosshead = 0;  ///< NaN without crosshead strain
    double chord_modulus_pa = 0;          ///< NaN unless status ok
    double chord_s1_pa = 0, chord_s2_pa = 0, chord_strain2 = 0;
    double tangent_modulus_pa = 0;        ///< NaN if the tangent window has too few samples
    double poisson_ratio = 0;             ///< NaN without lateral strain
    double stress_rate_pa_per_s = 0;      ///< mean rate between 10 % and 50 % of peak; NaN without time
    PopovicsFit popovics;
};

/// Reduces one curve. Never throws for bad curves: the status says what went wrong, and every
/// quantity that could be computed is filled (others are NaN).
CurveReduction reduce_curve(const StressStrainCurve& curve, const ReductionOptions& options = {});

}  // namespace gradem::lab
