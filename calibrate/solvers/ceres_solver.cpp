// Ceres Levenberg-Marquardt on the residual vector in unit-box coordinates. The Jacobian is a
// forward difference with steps of solver.fd_step (a few percent, not Ceres' 1e-6, which the
// bond-break staircase of a DEM response defeats); the base point and the n difference points
// of an iteration go to the workers as one batch.
#include <ceres/ceres.h>

#include <cmath>

#include "calibrate/solvers/solver.hpp"

namespace gradem::cal {
namespace {

class BatchedResiduals final : public ceres::CostFunction {
public:
    BatchedResiduals(SolveContext& ctx, BestTracker& tracker, bool& out_of_budget)
        : ctx_(ctx), tracker_(tracker), out_of_budget_(out_of_budget) {
        set_num_residuals(static_cast<int>(ctx.problem.fitted_quantities().size() * ctx.sands.size()));
        mutable_parameter_block_sizes()->push_back(static_cast<int>(ctx.space.size()));
    }

    bool Evaluate(double const* const* parameters, double* residual, double** jacobians) const override {
        const std::size_t n = ctx_.space.size();
        const std::vector<double> u(parameters[0], parameters[0] + n);
        std::vector<std::vector<double>> points = {ctx_.space.from_unit(u)};
        std::vector<double> steps;
        if (jacobians && jacobians[0])
            for (std::size_t k = 0; k < n; ++k) {
                std::vector<double> uk = u;
                steps.push_back(unit_fd_step(ctx_.space, k, u[k], ctx_.problem.solver.fd_step));
                uk[k] += steps.back();
                points.push_back(ctx_.space.from_unit(uk));
            }
        if (ctx_.evaluator.runs_needed(points, ctx_.sands) > ctx_.evaluator.runs_remaining()) {
            out_of_budget_ = true;
            return false;
        }
        const std::vector<Evaluation> e = ctx_.evaluator.evaluate(points, ctx_.sands, steps.empty() ? "lm" : "lm+jacobian");
        tracker_.offer(e[0]);
        ctx_.evaluator.note_best(tracker_.objective());
        const std::vector<double> r0 = residuals(e[0], ctx_.problem);
        std::copy(r0.begin(), r0.end(), residual);
        for (std::size_t k = 0; k < steps.size(); ++k) {
            const std::vector<double> rk = residuals(e[k + 1], ctx_.problem);
            for (std::size_t i = 0; i < r0.size(); ++i) jacobians[0][i * n + k] = (rk[i] - r0[i]) / steps[k];
        }
        return true;
    }

private:
    SolveContext& ctx_;
    BestTracker& tracker_;
    bool& out_of_budget_;
};

class StopOnBudget final : public ceres::IterationCallback {
public:
    explicit StopOnBudget(const bool& flag) : flag_(flag) {}
    ceres::CallbackReturnType operator()(const ceres::IterationSummary&) override {
        return flag_ ? ceres::SOLVER_TERMINATE_SUCCESSFULLY : ceres::SOLVER_CONTINUE;
    }

private:
    const bool& flag_;
};

}  // namespace

SolveResult solve_ceres(SolveContext& ctx, const std::vector<double>& start) {
    BestTracker tracker(ctx.problem);
    bool out_of_budget = false;
    std::vector<double> u = ctx.space.to_unit(start);
    ceres::Problem problem;
    problem.AddResidualBlock(new BatchedResiduals(ctx, tracker, out_of_budget), nullptr, u.data());
    for (int k = 0; k < static_cast<int>(u.size()); ++k) {
        problem.SetParameterLowerBound(u.data(), k, 0.0);
        problem.SetParameterUpperBound(u.data(), k, 1.0);
    }
    StopOnBudget stop(out_of_budget);
    ceres::Solver::Options options;
    options.trust_region_strategy_type = ceres::LEVENBERG_MARQUARDT;
    options.linear_solver_type = ceres::DENSE_QR;
    options.max_num_iterations = 50;  // the run budget stops it first
    options.parameter_tolerance = ctx.problem.solver.tolerance;
    options.function_tolerance = 1e-4;
    options.initial_trust_region_radius = 1.0;
    options.max_num_consecutive_invalid_steps = 3;
    options.num_threads = 1;  // concurrency is in the batch of runs
    options.logging_type = ceres::SILENT;
    options.callbacks.push_back(&stop);
    options.update_state_every_iteration = true;
    ceres::Solver::Summary summary;
    ceres::Solve(options, &problem, &summary);
    SolveResult r;
    r.method = "ceres";
    r.budget_exhausted = out_of_budget;
    r.stop_reason = out_of_budget ? "run budget reached" : summary.message;
    if (!tracker.empty()) {
        r.best = tracker.best().values;
        r.best_eval = tracker.best();
        r.best_objective = tracker.objective();
    }
    return r;
}

}  // namespace gradem::cal
