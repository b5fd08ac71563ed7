#pragma once
// Popovics (1973) stress–strain law and its least-squares fit (Ceres).
//   σ(ε) = f'c · n·x / (n − 1 + xⁿ),  x = ε/ε'c,  n = E/(E − f'c/ε'c)
// E is the initial tangent modulus; the law needs E > f'c/ε'c (secant modulus at peak), n > 1.

#include <cstddef>

#include "lab_data/curve_reduction.hpp"

namespace gradem::lab {

/// Stress [Pa] of the Popovics law at `strain`; all arguments SI, compression positive.
double popovics_stress(double strain, double peak_stress_pa, double strain_at_peak, double modulus_pa);

/// Fits the law to the ascending branch (samples 0..peak_index with positive strain and stress,
/// at most 400, evenly thinned). Parameters are fitted as ln f'c, ln ε'c, ln(n − 1), so the
/// constraint n > 1 holds by construction; standard errors come from Ceres's covariance scaled
/// by the residual variance and are mapped to E, f'c, ε'c by the delta method.
/// `strain_at_peak_guess` and `modulus_guess` (may be NaN) seed the solver.
PopovicsFit fit_popovics(const StressStrainCurve& curve, std::size_t peak_index, double strain_at_peak_guess,
                         double modulus_guess);

}  // namespace gradem::lab
