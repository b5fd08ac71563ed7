// What every solver shares (calibrate/solvers/solver.hpp): the best-point tracker, the finite-difference
// step, the noise-floor objective, and the dispatch from [solver] method to a solver.
#include <cmath>

#include "calibrate/solvers/solver.hpp"

namespace gradem::cal {

double BestTracker::offer(const Evaluation& e) {
    const double j = cal::objective(e, problem_);
    if (!has_ || j < objective_) {
        best_ = e;
        objective_ = j;
        has_ = true;
    }
    return j;
}

double unit_fd_step(const ParameterSpace& space, std::size_t k, double u, double fd_step) {
    const ParameterSpec& p = space.free(k);
    const double h = p.log_scale ? std::log1p(fd_step) / std::log(p.upper / p.lower) : fd_step;
    return u + h <= 1.0 ? h : -h;
}

double noise_floor_objective(const Evaluation& e, const CalibrationProblem& problem) {
    double j = 0.0;
    for (const SandOutcome& s : e.sands)
        for (Quantity q : problem.fitted_quantities()) {
            const int k = static_cast<int>(q);
            if (s.count(q) < 2 || !std::isfinite(s.std[k])) continue;
            const double se = s.std[k] / s.mean[k] / std::sqrt(static_cast<double>(s.count(q)));
            j += std::pow(problem.weights.of(q) * se, 2);
        }
    return j;
}

SolveResult solve(SolveContext& ctx, const std::vector<double>& start) {
    switch (ctx.problem.solver.method) {
        case Method::scaling: return solve_scaling(ctx, start);
        case Method::ceres: return solve_ceres(ctx, start);
        default: {
            BestTracker tracker(ctx.problem);
            return solve_nlopt(ctx, ctx.problem.solver.method, start, tracker);
        }
    }
}

}  // namespace gradem::cal
