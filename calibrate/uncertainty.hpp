#pragma once
// Uncertainty and identifiability at the optimum (docs/calibration.md "Uncertainty and
// identifiability"). The Jacobian of the
// lab-normalised residuals r_i = (y_i − y_lab,i) / s_i, s_i = sqrt(s_lab² + s_sim²/n), with
// respect to the natural coordinates z (ln v for log parameters, v for linear ones):
//   - scale columns in closed form when the homogeneity was verified (∂ln E/∂ln E* = 1,
//     ∂ln σ/∂ln s = 1, ∂ln ε/∂ln s = −∂ln ε/∂ln E* = 1);
//   - other columns by forward differences of solver.fd_step, run as one concurrent batch;
//     with the homogeneity verified, a shape column's difference point is instead taken from
//     the shape search's own evaluations where one lies on that column within three steps
//     (rescaled to the best point's scales: a secant that costs no run).
// Covariance of z: Ceres' Covariance (dense SVD, rank-deficient directions dropped) on the
// linearised problem, i.e. (JᵀJ)⁻¹. Singular values of J (columns in unit-box scale) and the
// condition number tell how well the data pin the parameters down.
#include <string>
#include <vector>

#include "calibrate/solvers/solver.hpp"

namespace gradem::cal {

struct Uncertainty {
    bool computed = false;
    std::string note;                        ///< why not computed, or caveats
    std::vector<double> std_error_natural;   ///< per free parameter: of ln v (log) or v (linear)
    std::vector<double> low, high;           ///< one-standard-error interval, config units
    std::vector<double> singular_values;     ///< of J with unit-box columns, descending
    double condition = 0.0;
    std::vector<std::string> poorly_identified;  ///< names, with the reason
    int fd_runs = 0;                         ///< runs spent on difference points
    std::vector<std::string> reused;         ///< difference points taken from the solve's history
};

Uncertainty estimate_uncertainty(SolveContext& ctx, const SolveResult& solution);

}  // namespace gradem::cal
