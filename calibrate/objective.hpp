#pragma once
// Residuals, the objective, and the model's homogeneity (docs/calibration.md "Objective and weights"):
//   r(sand, q) = w_q (y_sim / y_lab − 1)         relative error, weighted; a failed evaluation
//                                                gets r = w_q · penalty for every target
//   J          = Σ r²
// Homogeneity: multiplying every modulus by α and every strength by β changes the outputs to
//   E' = α E,  σ' = β σ,  ε' = (β/α) ε,  σt' = β σt (the direct-tension strength)
// so the best α, β for a run are the weighted least-squares solution in logs:
//   min Σ_s [w_E (ln α + ln E_s/E_lab)]² + [w_σ (ln β + ln σ_s/σ_lab)]² + [w_ε (ln β − ln α + ln ε_s/ε_lab)]²
//           (+ [w_t (ln β + ln σt_s/σt_target)]² when the problem fits tension)
#include <vector>

#include "calibrate/evaluator.hpp"
#include "calibrate/problem.hpp"

namespace gradem::cal {

std::vector<double> residuals(const Evaluation& e, const CalibrationProblem& problem);
double objective(const std::vector<double>& r);
inline double objective(const Evaluation& e, const CalibrationProblem& problem) { return objective(residuals(e, problem)); }

/// The outputs this evaluation's runs would give with moduli × α and strengths × β.
Evaluation rescaled(const Evaluation& e, double alpha, double beta);

struct Scales {
    double alpha = 1.0, beta = 1.0;
};
/// Best α (if `stiffness`) and β (if `strength`) in the log least-squares sense above.
Scales best_scales(const Evaluation& e, const CalibrationProblem& problem, bool stiffness, bool strength);

/// The lab-normalised residual (y_sim − y_lab) / sqrt(s_lab² + s_sim²/n), for reports and
/// the covariance (NaN where a standard deviation is unknown).
double z_score(double sim_mean, double sim_std, int n_sim, const TargetStat& lab);

}  // namespace gradem::cal
