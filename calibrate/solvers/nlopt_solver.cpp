// NLopt derivative-free search over every free parameter in unit-box coordinates.
#include <cmath>
#include <nlopt.hpp>

#include "calibrate/solvers/solver.hpp"

namespace gradem::cal {
namespace {

nlopt::algorithm algorithm_of(Method m) {
    switch (m) {
        case Method::sbplx: return nlopt::LN_SBPLX;
        case Method::cobyla: return nlopt::LN_COBYLA;
        case Method::crs2: return nlopt::GN_CRS2_LM;
        case Method::direct: return nlopt::GN_DIRECT_L;
        default: return nlopt::LN_BOBYQA;
    }
}

std::string nlopt_reason(nlopt::result r) {
    switch (r) {
        case nlopt::SUCCESS: return "converged";
        case nlopt::STOPVAL_REACHED: return "objective below stopval";
        case nlopt::FTOL_REACHED: return "objective change below the noise floor (ftol)";
        case nlopt::XTOL_REACHED: return "parameter change below solver.tolerance (xtol)";
        case nlopt::MAXEVAL_REACHED: return "run budget reached (maxeval)";
        case nlopt::MAXTIME_REACHED: return "time limit";
        default: return "stopped (" + std::to_string(static_cast<int>(r)) + ")";
    }
}

}  // namespace

SolveResult solve_nlopt(SolveContext& ctx, Method method, const std::vector<double>& start, BestTracker& tracker) {
    const std::size_t n = ctx.space.size();
    const int per_eval = ctx.problem.runs_per_test(ctx.sands);
    SolveResult result;
    result.method = to_string(method);
    bool out_of_budget = false;
    nlopt::opt opt(algorithm_of(method), static_cast<unsigned>(n));
    if (method == Method::crs2) nlopt::srand(ctx.problem.solver.seed);
    opt.set_lower_bounds(std::vector<double>(n, 0.0));
    opt.set_upper_bounds(std::vector<double>(n, 1.0));
    opt.set_xtol_abs(ctx.problem.solver.tolerance);
    opt.set_maxeval(std::max(1, ctx.evaluator.runs_remaining() / std::max(1, per_eval)));
    if (method != Method::direct && method != Method::crs2) opt.set_initial_step(std::vector<double>(n, 0.15));
    struct Data {
        SolveContext* ctx;
        BestTracker* tracker;
        bool* out_of_budget;
        nlopt::opt* opt;
    } data{&ctx, &tracker, &out_of_budget, &opt};
    opt.set_min_objective(
        [](unsigned, const double* u, double*, void* d) -> double {
            auto& [c, t, oob, o] = *static_cast<Data*>(d);
            const std::vector<double> values = c->space.from_unit(std::vector<double>(u, u + c->space.size()));
            if (c->evaluator.runs_needed({values}, c->sands) > c->evaluator.runs_remaining()) {
                *oob = true;
                o->force_stop();
                return HUGE_VAL;
            }
            const double j = t->offer(c->evaluator.evaluate(values, c->sands, "search"));
            c->evaluator.note_best(t->objective());
            return j;
        },
        &data);
    std::vector<double> u = ctx.space.to_unit(start);
    double f = 0.0;
    try {
        result.stop_reason = nlopt_reason(opt.optimize(u, f));
    } catch (const nlopt::forced_stop&) {
        result.stop_reason = "run budget reached";
    } catch (const nlopt::roundoff_limited&) {
        result.stop_reason = "round-off limited (the objective is flat at the noise level)";
    } catch (const std::exception& e) {
        result.stop_reason = std::string("NLopt stopped: ") + e.what();
    }
    result.budget_exhausted = out_of_budget || result.stop_reason.find("budget") != std::string::npos;
    if (!tracker.empty()) {
        result.best = tracker.best().values;
        result.best_eval = tracker.best();
        result.best_objective = tracker.objective();
    }
    return result;
}

}  // namespace gradem::cal
