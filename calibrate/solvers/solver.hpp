#pragma once
// The solvers. Each works through the Evaluator (ledger, budget, concurrency) and returns the
// best evaluated point; none throws when a simulation fails (failures are penalty values) or
// when the budget runs out (it stops and says so).
//   scaling   closed-form E* and strength scale from the homogeneity (verified first on the
//             actual specimens), BOBYQA on the remaining dimensionless shape parameters;
//             falls back to bobyqa on everything if the homogeneity does not hold
//   bobyqa, sbplx, cobyla, crs2, direct   NLopt on all free parameters in the unit box
//   ceres     Levenberg-Marquardt on the residual vector, forward differences of fd_step
#include <cmath>
#include <functional>
#include <string>
#include <vector>

#include "calibrate/evaluator.hpp"
#include "calibrate/objective.hpp"

namespace gradem::cal {

struct SolveContext {
    const CalibrationProblem& problem;
    const ParameterSpace& space;
    Evaluator& evaluator;
    std::vector<std::size_t> sands;               ///< the sands calibrated on
    std::function<void(const std::string&)> log;  ///< one line per milestone
};

struct HomogeneityCheck {
    bool done = false, holds = false;
    double modulus_deviation = 0, peak_deviation = 0, strain_deviation = 0;  ///< max |predicted/actual − 1|
    double tension_deviation = std::nan("");  ///< of σt, when the problem fits it (NaN otherwise)
    double alpha = 1, beta = 1;  ///< the rescaling tested
};

struct SolveResult {
    std::string method;                ///< what actually ran ("scaling", "scaling -> bobyqa", ...)
    std::vector<double> best;          ///< free parameters, config units
    Evaluation best_eval;              ///< its actual runs
    double best_objective = 0.0;
    std::string stop_reason;
    bool budget_exhausted = false;
    HomogeneityCheck homogeneity;
    std::vector<std::string> notes;
};

/// Tracks the best actual evaluation (lowest objective) of a solve.
class BestTracker {
public:
    explicit BestTracker(const CalibrationProblem& p) : problem_(p) {}
    double offer(const Evaluation& e);  ///< returns e's objective
    [[nodiscard]] bool empty() const { return !has_; }
    [[nodiscard]] const Evaluation& best() const { return best_; }
    [[nodiscard]] double objective() const { return objective_; }

private:
    const CalibrationProblem& problem_;
    Evaluation best_;
    double objective_ = 0.0;
    bool has_ = false;
};

SolveResult solve(SolveContext& ctx, const std::vector<double>& start);
SolveResult solve_scaling(SolveContext& ctx, const std::vector<double>& start);
SolveResult solve_nlopt(SolveContext& ctx, Method method, const std::vector<double>& start, BestTracker& tracker);
SolveResult solve_ceres(SolveContext& ctx, const std::vector<double>& start);

/// Forward-difference step in unit-box coordinates for free parameter k at unit value u:
/// a relative change of fd_step (log) or fd_step of the range (linear), reversed at the upper bound.
double unit_fd_step(const ParameterSpace& space, std::size_t k, double u, double fd_step);

/// The objective's noise level from an evaluation's seed spread: Σ_i (w_i · se_i)², with se the
/// relative standard error of the seed mean (0 with a single seed).
double noise_floor_objective(const Evaluation& e, const CalibrationProblem& problem);

}  // namespace gradem::cal
