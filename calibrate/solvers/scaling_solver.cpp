// The scaling-law path (docs/calibration.md "The scaling solver"):
//   1. run the start point x0;
//   2. rescale E* by α and the strengths by β in closed form (objective.hpp) -> x1, predict
//      its outputs, run it, and compare: the homogeneity holds if E and peak are predicted
//      within solver.homogeneity_tolerance on every sand (else: bobyqa on everything);
//   3. BOBYQA over the dimensionless shape parameters only, the scales held at x1's: each trial
//      θ costs one evaluation, and its objective is the one after the best closed-form rescaling
//      (no extra runs);
//   4. confirm: run the best θ with its rescaled E* and strengths; if E or peak still miss their
//      prediction by more than half the tolerance, rescale and run once more. With no shape
//      parameter free, when x1's own rescaling is already within half the tolerance, x1 is the
//      result: a confirmation would run a point that differs from it by less than the test it
//      applies. (With a shape search, the best θ is confirmed: on a DEM model it is seldom x1.)
#include <algorithm>
#include <cmath>
#include <nlopt.hpp>
#include <sstream>

#include "calibrate/rescaling.hpp"
#include "calibrate/solvers/solver.hpp"

namespace gradem::cal {
namespace {

double max_deviation(const Evaluation& predicted, const Evaluation& actual, Quantity q) {
    double worst = 0.0;
    for (std::size_t s = 0; s < actual.sands.size(); ++s)
        worst = std::max(worst, std::fabs(predicted.sands[s].value(q) / actual.sands[s].value(q) - 1.0));
    return worst;
}

Rescaling rescale(const SolveContext& ctx, const ScaleIndices& idx, const Evaluation& e) {
    return cal::rescale(ctx.problem, ctx.space, idx, e);
}

std::string percent(double x) {
    std::ostringstream o;
    o.precision(2);
    o << std::fixed << 100.0 * x << " %";
    return o.str();
}

SolveResult fall_back(SolveContext& ctx, const std::vector<double>& from, BestTracker& tracker, SolveResult head,
                      const std::string& why) {
    if (ctx.log) ctx.log("scaling path: " + why + "; falling back to bobyqa on every free parameter");
    SolveResult r = solve_nlopt(ctx, Method::bobyqa, from, tracker);
    r.method = "scaling -> bobyqa";
    r.homogeneity = head.homogeneity;
    r.notes = head.notes;
    r.notes.push_back(why + "; fell back to BOBYQA on every free parameter");
    return r;
}

/// Step 2's verdict: the rescaled point's measured E and peak against their prediction.
HomogeneityCheck check_homogeneity(const SolveContext& ctx, const Rescaling& r1, const Evaluation& e1) {
    HomogeneityCheck h;
    h.done = true;
    h.alpha = r1.scales.alpha;
    h.beta = r1.scales.beta;
    if (!e1.failed) {
        h.modulus_deviation = max_deviation(r1.prediction, e1, Quantity::modulus);
        h.peak_deviation = max_deviation(r1.prediction, e1, Quantity::peak);
        h.strain_deviation = max_deviation(r1.prediction, e1, Quantity::strain);
        if (!e1.tension_runs.empty()) h.tension_deviation = max_deviation(r1.prediction, e1, Quantity::tension);
        h.holds = h.modulus_deviation <= ctx.problem.solver.homogeneity_tolerance &&
                  h.peak_deviation <= ctx.problem.solver.homogeneity_tolerance;
    }
    return h;
}

std::string homogeneity_line(const HomogeneityCheck& h) {
    return "homogeneity check (moduli x " + std::to_string(h.alpha) + ", strengths x " + std::to_string(h.beta) +
           "): predicted vs run E " + percent(h.modulus_deviation) + ", peak " + percent(h.peak_deviation) + ", strain " +
           percent(h.strain_deviation) + (std::isfinite(h.tension_deviation) ? ", tension " + percent(h.tension_deviation) : "") +
           (h.holds ? " - holds" : " - does not hold");
}

/// Step 3: BOBYQA over the shape parameters' unit coordinates, the scales held at x1's; each
/// trial's objective is the one after its own closed-form rescaling. It keeps back `reserve`
/// runs of the budget (the confirmation and the uncertainty) and stops when a trial would use them.
class ShapeSearch {
public:
    ShapeSearch(SolveContext& ctx, const ScaleIndices& idx, BestTracker& tracker, const Evaluation& e1, const Rescaling& r_e1,
                int reserve)
        : ctx_(ctx), idx_(idx), tracker_(tracker), x1_(e1.values), u1_(ctx.space.to_unit(e1.values)), reserve_(reserve),
          best_point_(r_e1.point), best_predicted_(r_e1.predicted) {
        for (std::size_t k : idx.shape) theta1_.push_back(u1_[k]);
    }

    /// Runs the search with at most `evals` new evaluations and a stop at objective changes
    /// below `noise`; returns why it stopped.
    std::string run(int evals, double noise) {
        const std::size_t n = idx_.shape.size();
        nlopt::opt opt(nlopt::LN_BOBYQA, static_cast<unsigned>(n));
        opt.set_lower_bounds(std::vector<double>(n, 0.0));
        opt.set_upper_bounds(std::vector<double>(n, 1.0));
        opt.set_initial_step(std::vector<double>(n, 0.2));
        opt.set_xtol_abs(ctx_.problem.solver.tolerance);
        opt.set_ftol_abs(std::max(noise, 1e-12));
        opt.set_maxeval(evals + 1);  // + BOBYQA's first trial, x1 itself: served by the ledger
        opt_ = &opt;
        opt.set_min_objective([](unsigned, const double* th, double*, void* self) { return static_cast<ShapeSearch*>(self)->trial(th); },
                              this);
        std::vector<double> theta = theta1_;  // optimize() overwrites it
        double f = 0.0;
        try {
            const nlopt::result res = opt.optimize(theta, f);
            return res == nlopt::MAXEVAL_REACHED ? "shape search used its share of the budget"
                   : res == nlopt::FTOL_REACHED  ? "shape search: objective change below the noise floor"
                   : res == nlopt::XTOL_REACHED  ? "shape search: parameter change below solver.tolerance"
                                                 : "shape search converged";
        } catch (const nlopt::roundoff_limited&) {
            return "shape search: round-off limited (flat at the noise level)";
        } catch (const nlopt::forced_stop&) {
            return "shape search used its share of the budget";
        }
    }

    [[nodiscard]] const std::vector<double>& best_point() const { return best_point_; }
    [[nodiscard]] double best_predicted() const { return best_predicted_; }

private:
    double trial(const double* th) {
        std::vector<double> u = u1_;
        for (std::size_t j = 0; j < idx_.shape.size(); ++j) u[idx_.shape[j]] = th[j];
        // BOBYQA starts at x1: take its exact values (the unit-box round trip moves the last
        // bits), so the ledger serves the runs instead of repeating them.
        const bool at_x1 = std::equal(theta1_.begin(), theta1_.end(), th);
        const std::vector<double> values = at_x1 ? x1_ : ctx_.space.from_unit(u);
        if (ctx_.evaluator.runs_needed({values}, ctx_.sands) > ctx_.evaluator.runs_remaining() - reserve_) {
            opt_->force_stop();  // keep the confirmation's share of the budget
            return HUGE_VAL;
        }
        const Evaluation e = ctx_.evaluator.evaluate(values, ctx_.sands, "shape");
        tracker_.offer(e);
        if (e.failed) return objective(e, ctx_.problem);
        const Rescaling r = rescale(ctx_, idx_, e);
        if (r.predicted < best_predicted_) {
            best_predicted_ = r.predicted;
            best_point_ = r.point;
        }
        ctx_.evaluator.note_best(best_predicted_);
        return r.predicted;
    }

    SolveContext& ctx_;
    const ScaleIndices& idx_;
    BestTracker& tracker_;
    std::vector<double> x1_, u1_, theta1_;  ///< x1's exact values, unit coordinates, shape coordinates
    int reserve_;
    std::vector<double> best_point_;
    double best_predicted_;
    nlopt::opt* opt_ = nullptr;
};

/// Whether a run point's closed-form rescaling moves E* and the strengths by at most half the
/// homogeneity tolerance: the point is then on target (the confirmation's test).
bool on_target(const SolveContext& ctx, const Rescaling& r) {
    const double half = ctx.problem.solver.homogeneity_tolerance / 2;
    return std::fabs(r.scales.alpha - 1.0) <= half && std::fabs(r.scales.beta - 1.0) <= half;
}

/// Step 4: runs the best point; if E or peak still miss their prediction by more than half the
/// homogeneity tolerance, rescales and runs once more.
void confirm(SolveContext& ctx, const ScaleIndices& idx, BestTracker& tracker, std::vector<double> point) {
    for (int round = 0; round < 2; ++round) {
        const Evaluation e = ctx.evaluator.evaluate(point, ctx.sands, "confirm");
        tracker.offer(e);
        ctx.evaluator.note_best(tracker.objective());
        if (e.failed) break;
        const Rescaling r = rescale(ctx, idx, e);
        if (on_target(ctx, r)) break;
        point = r.point;
    }
}

/// The line that says x1 is the result without a confirmation run.
std::string x1_on_target_line(const Rescaling& r) {
    return "the rescaled point is on target (its own rescaling: moduli x " + std::to_string(r.scales.alpha) +
           ", strengths x " + std::to_string(r.scales.beta) + ", within half the homogeneity tolerance): it is the result";
}

}  // namespace

SolveResult solve_scaling(SolveContext& ctx, const std::vector<double>& start) {
    const ScaleIndices idx = split_by_role(ctx.space);
    BestTracker tracker(ctx.problem);
    SolveResult head;
    head.method = "scaling";
    if (idx.stiffness.empty() && idx.strength.empty()) return fall_back(ctx, start, tracker, head, "no free scale parameter");
    const int per_eval = ctx.problem.runs_per_test(ctx.sands);
    try {
        // 1. The start point.
        const Evaluation e0 = ctx.evaluator.evaluate(start, ctx.sands, "start");
        tracker.offer(e0);
        if (e0.failed) return fall_back(ctx, start, tracker, head, "the start point failed (" + e0.failure + ")");
        // 2. Closed-form rescaling, and the homogeneity check on the actual specimens.
        const Rescaling r1 = rescale(ctx, idx, e0);
        const Evaluation e1 = ctx.evaluator.evaluate(r1.point, ctx.sands, "rescaled");
        tracker.offer(e1);
        ctx.evaluator.note_best(tracker.objective());
        head.homogeneity = check_homogeneity(ctx, r1, e1);
        if (ctx.log) ctx.log(homogeneity_line(head.homogeneity));
        if (!head.homogeneity.holds)
            return fall_back(ctx, tracker.best().values, tracker, head,
                             e1.failed ? "the rescaled point failed (" + e1.failure + ")"
                                       : "homogeneity does not hold within " + percent(ctx.problem.solver.homogeneity_tolerance));
        // 3. Shape search at x1's scales.
        const Rescaling r_e1 = rescale(ctx, idx, e1);
        ShapeSearch search(ctx, idx, tracker, e1, r_e1, per_eval * (2 + static_cast<int>(idx.shape.size())));
        std::string stop = "no shape parameter is free";
        if (!idx.shape.empty()) {
            const int evals = (ctx.evaluator.runs_remaining() - per_eval * (2 + static_cast<int>(idx.shape.size()))) / per_eval;
            if (evals < static_cast<int>(idx.shape.size()) + 2) {
                stop = "shape search skipped: too few runs left in the budget";
                head.notes.push_back(stop);
            } else {
                stop = search.run(evals, noise_floor_objective(e1, ctx.problem));
            }
        }
        if (ctx.log) ctx.log(stop + "; best predicted objective " + std::to_string(search.best_predicted()));
        // 4. Confirmation runs, unless there was no shape to search and x1 is already on target.
        if (idx.shape.empty() && on_target(ctx, r_e1)) {
            head.notes.push_back(x1_on_target_line(r_e1));
            if (ctx.log) ctx.log(head.notes.back());
        } else {
            confirm(ctx, idx, tracker, search.best_point());
        }
        head.stop_reason = stop;
    } catch (const BudgetExhausted& e) {
        head.budget_exhausted = true;
        head.stop_reason = std::string("stopped: ") + e.what();
    }
    head.best = tracker.best().values;
    head.best_eval = tracker.best();
    head.best_objective = tracker.objective();
    return head;
}

}  // namespace gradem::cal
