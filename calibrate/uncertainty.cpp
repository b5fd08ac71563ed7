#include "calibrate/uncertainty.hpp"

#include <ceres/ceres.h>

#include <Eigen/Dense>
#include <cmath>
#include <optional>
#include <sstream>

namespace gradem::cal {
namespace {

/// r(z) = r0 + J (z − z0): the residuals linearised at the optimum, for Ceres' Covariance.
class Linearised final : public ceres::CostFunction {
public:
    Linearised(Eigen::VectorXd r0, Eigen::MatrixXd jac, Eigen::VectorXd z0)
        : r0_(std::move(r0)), jac_(std::move(jac)), z0_(std::move(z0)) {
        set_num_residuals(static_cast<int>(r0_.size()));
        mutable_parameter_block_sizes()->push_back(static_cast<int>(z0_.size()));
    }
    bool Evaluate(double const* const* p, double* r, double** jacobians) const override {
        const Eigen::Map<const Eigen::VectorXd> z(p[0], z0_.size());
        Eigen::Map<Eigen::VectorXd>(r, r0_.size()) = r0_ + jac_ * (z - z0_);
        if (jacobians && jacobians[0])
            Eigen::Map<Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>>(jacobians[0], jac_.rows(), jac_.cols()) = jac_;
        return true;
    }

private:
    Eigen::VectorXd r0_;
    Eigen::MatrixXd jac_;
    Eigen::VectorXd z0_;
};

/// Lab-normalised outputs of an evaluation: rows (sand, quantity) with weight > 0.
struct Rows {
    std::vector<std::size_t> sand;
    std::vector<Quantity> quantity;
    std::vector<double> scale;  ///< s_i
};

Rows rows_of(const Evaluation& e, const CalibrationProblem& p) {
    Rows r;
    for (const SandOutcome& s : e.sands)
        for (Quantity q : p.fitted_quantities()) {
            if (p.weights.of(q) <= 0.0) continue;
            const TargetStat& lab = target_of(p.targets[s.sand], q);
            const int k = static_cast<int>(q);
            const double sim_var = s.count(q) > 1 && std::isfinite(s.std[k]) ? s.std[k] * s.std[k] / s.count(q) : 0.0;
            double var = (std::isfinite(lab.std) ? lab.std * lab.std : 0.0) + sim_var;
            if (!(var > 0.0)) var = std::pow(0.05 * lab.mean, 2);  // no scatter known: assume 5 %
            r.sand.push_back(s.sand);
            r.quantity.push_back(q);
            r.scale.push_back(std::sqrt(var));
        }
    return r;
}

double output(const Evaluation& e, std::size_t sand, Quantity q) {
    for (const SandOutcome& s : e.sands)
        if (s.sand == sand) return s.value(q);
    return std::nan("");
}

/// A shape column's difference point taken from the solve's own history instead of a new run.
struct ReusedPoint {
    Evaluation outputs;  ///< the past evaluation, rescaled to the best point's scales
    double unit_step;    ///< its shape coordinate minus the best's, unit box
    std::string what;    ///< for the report
};

/// A past evaluation lies on the shape column k through the best point if every other shape
/// parameter is the same and the scales differ only by one factor per kind (α for the moduli,
/// β for the strengths); returns those factors (best / past).
std::optional<Scales> scales_to_best(const ParameterSpace& space, const std::vector<double>& best, const std::vector<double>& past,
                                     std::size_t k) {
    const std::vector<double> u0 = space.to_unit(best), u = space.to_unit(past);
    std::optional<double> alpha, beta;
    auto same_factor = [](std::optional<double>& factor, double f) {
        if (!factor) factor = f;
        return std::fabs(f / *factor - 1.0) <= 1e-9;
    };
    for (std::size_t j = 0; j < space.size(); ++j) {
        const Role role = space.free(j).role();
        if (role == Role::shape) {
            if (j != k && std::fabs(u[j] - u0[j]) > 1e-9) return std::nullopt;
        } else if (!same_factor(role == Role::stiffness_scale ? alpha : beta, best[j] / past[j])) {
            return std::nullopt;
        }
    }
    return Scales{alpha.value_or(1.0), beta.value_or(1.0)};
}

/// With the homogeneity verified (E ∝ α, peak ∝ β, strain ∝ β/α, docs/calibration.md "Homogeneity"), every
/// evaluation of the scaling path's shape search is, after rescaling, a point on its shape
/// column through the best point. The one whose step is nearest the finite-difference step h,
/// within [h/2, kMaxSecantSteps·h], serves as the difference point for free: a secant over up
/// to three steps, whose curvature error is traded against the runs' seed noise (which a
/// longer step divides down).
constexpr double kMaxSecantSteps = 3.0;

bool same_sands(const Evaluation& a, const Evaluation& b) {
    if (a.sands.size() != b.sands.size()) return false;
    for (std::size_t i = 0; i < a.sands.size(); ++i)
        if (a.sands[i].sand != b.sands[i].sand) return false;
    return true;
}

std::optional<ReusedPoint> reusable_difference(const SolveContext& ctx, const SolveResult& sol, std::size_t k, double h) {
    const ParameterSpace& space = ctx.space;
    const double u_best = space.to_unit(sol.best)[k];
    std::optional<ReusedPoint> chosen;
    for (const Evaluation& e : ctx.evaluator.history()) {
        if (e.failed || e.values.size() != sol.best.size() || !same_sands(e, sol.best_eval)) continue;
        const double step = space.to_unit(e.values)[k] - u_best;
        if (std::fabs(step) < h / 2 || std::fabs(step) > kMaxSecantSteps * h) continue;
        if (chosen && std::fabs(std::fabs(step) - h) >= std::fabs(std::fabs(chosen->unit_step) - h)) continue;
        const std::optional<Scales> sc = scales_to_best(space, sol.best, e.values, k);
        if (!sc) continue;
        std::ostringstream what;
        what.precision(4);
        what << space.free(k).name << ": difference point from evaluation " << e.index << " (" << e.label << ", "
             << space.free(k).name << " = " << e.values[k] << "), rescaled to the best point's scales (moduli x "
             << sc->alpha << ", strengths x " << sc->beta << "; no new runs)";
        chosen = ReusedPoint{rescaled(e, sc->alpha, sc->beta), step, what.str()};
    }
    return chosen;
}

/// Step 1's result: one evaluation per difference column (new runs first, then reused ones).
struct DifferencePoints {
    std::vector<std::size_t> columns;  ///< free-parameter index of each difference point
    std::vector<double> steps;         ///< its step in the unit box
    std::vector<Evaluation> outputs;
};

/// Difference points for every column that is not closed-form: from the shape search's history
/// where the homogeneity allows (scaling path), else new runs. False (with u.note) when they
/// cannot be had.
bool difference_points(SolveContext& ctx, const SolveResult& sol, Uncertainty& u, DifferencePoints& d) {
    const ParameterSpace& space = ctx.space;
    const bool closed_form = sol.homogeneity.holds;
    const std::vector<double> u0 = space.to_unit(sol.best);
    std::vector<std::size_t> reused_columns;
    std::vector<std::vector<double>> points;
    std::vector<double> reused_steps;
    std::vector<Evaluation> reused;
    for (std::size_t k = 0; k < space.size(); ++k) {
        if (closed_form && space.free(k).role() != Role::shape) continue;
        const double h = unit_fd_step(space, k, u0[k], ctx.problem.solver.fd_step);
        if (closed_form) {
            if (std::optional<ReusedPoint> r = reusable_difference(ctx, sol, k, std::fabs(h))) {
                reused_columns.push_back(k);
                reused_steps.push_back(r->unit_step);
                reused.push_back(std::move(r->outputs));
                u.reused.push_back(r->what);
                continue;
            }
        }
        std::vector<double> uk = u0;
        d.steps.push_back(h);
        uk[k] += h;
        d.columns.push_back(k);
        points.push_back(space.from_unit(uk));
    }
    d.columns.insert(d.columns.end(), reused_columns.begin(), reused_columns.end());  // one list of difference columns
    d.steps.insert(d.steps.end(), reused_steps.begin(), reused_steps.end());
    if (!points.empty()) {
        const int before = ctx.evaluator.runs_used();
        try {
            d.outputs = ctx.evaluator.evaluate(points, ctx.sands, "uncertainty");
        } catch (const BudgetExhausted& e) {
            u.note = std::string("not computed: ") + e.what() + " (raise solver.max_runs for standard errors)";
            return false;
        }
        u.fd_runs = ctx.evaluator.runs_used() - before;
        for (const Evaluation& e : d.outputs)
            if (e.failed) {
                u.note = "not computed: a difference point failed (" + e.failure + ")";
                return false;
            }
    }
    d.outputs.insert(d.outputs.end(), reused.begin(), reused.end());
    return true;
}

/// Step 2: the Jacobian of the lab-normalised residuals in natural coordinates z, at the best point.
struct Linearisation {
    Eigen::MatrixXd jac;         ///< ∂r_i/∂z_k
    Eigen::VectorXd r0, z0;      ///< residuals and natural coordinates at the best point
    Eigen::VectorXd unit_scale;  ///< dz/du per free parameter
};

Linearisation linearise(const SolveContext& ctx, const SolveResult& sol, const DifferencePoints& d) {
    const ParameterSpace& space = ctx.space;
    const std::size_t n = space.size();
    const bool closed_form = sol.homogeneity.holds;
    const Rows rows = rows_of(sol.best_eval, ctx.problem);
    const std::size_t m = rows.sand.size();
    Linearisation l{Eigen::MatrixXd::Zero(static_cast<Eigen::Index>(m), static_cast<Eigen::Index>(n)),
                    Eigen::VectorXd(static_cast<Eigen::Index>(m)), Eigen::VectorXd(static_cast<Eigen::Index>(n)),
                    Eigen::VectorXd(static_cast<Eigen::Index>(n))};
    for (std::size_t k = 0; k < n; ++k) {
        const ParameterSpec& p = space.free(k);
        l.z0[k] = space.to_natural(k, sol.best[k]);
        l.unit_scale[k] = p.log_scale ? std::log(p.upper / p.lower) : p.upper - p.lower;  // dz/du
    }
    for (std::size_t i = 0; i < m; ++i) {
        const double y = output(sol.best_eval, rows.sand[i], rows.quantity[i]);
        l.r0[i] = (y - target_of(ctx.problem.targets[rows.sand[i]], rows.quantity[i]).mean) / rows.scale[i];
        for (std::size_t k = 0; k < n; ++k) {
            const Role role = space.free(k).role();
            double dy_dz = 0.0;
            if (closed_form && role != Role::shape) {
                // ∂y/∂ln(scale) from the homogeneity; divide by v for a linear-scaled parameter.
                const Quantity q = rows.quantity[i];
                const double dlny = role == Role::stiffness_scale ? (q == Quantity::modulus ? 1.0 : q == Quantity::strain ? -1.0 : 0.0)
                                                                  : (q == Quantity::modulus ? 0.0 : 1.0);
                dy_dz = dlny * y / (space.free(k).log_scale ? 1.0 : sol.best[k]);
            } else {
                const auto col = static_cast<std::size_t>(std::find(d.columns.begin(), d.columns.end(), k) - d.columns.begin());
                const double yk = output(d.outputs[col], rows.sand[i], rows.quantity[i]);
                dy_dz = (yk - y) / (d.steps[col] * l.unit_scale[k]);
            }
            l.jac(static_cast<Eigen::Index>(i), static_cast<Eigen::Index>(k)) = dy_dz / rows.scale[i];
        }
    }
    return l;
}

/// Step 3: singular values of the unit-box Jacobian (zeros for the directions beyond the
/// number of targets) into u; returns each parameter's share of the directions the targets do
/// not see (σ < 1e-3 σmax).
std::vector<double> blind_shares(const Linearisation& l, Uncertainty& u) {
    const std::size_t n = static_cast<std::size_t>(l.z0.size());
    const Eigen::JacobiSVD<Eigen::MatrixXd> svd(l.jac * l.unit_scale.asDiagonal(), Eigen::ComputeFullV);
    for (Eigen::Index k = 0; k < svd.singularValues().size(); ++k) u.singular_values.push_back(svd.singularValues()[k]);
    u.singular_values.resize(n, 0.0);
    const double smax = u.singular_values.front();
    const double smin = u.singular_values.back();
    u.condition = smin > 0.0 ? smax / smin : HUGE_VAL;
    const Eigen::MatrixXd v = svd.matrixV();
    std::vector<double> share(n, 0.0);
    for (std::size_t j = 0; j < n; ++j)
        if (!(u.singular_values[j] > 1e-3 * smax))
            for (std::size_t k = 0; k < n; ++k) share[k] += std::pow(v(static_cast<Eigen::Index>(k), static_cast<Eigen::Index>(j)), 2);
    return share;
}

/// Step 4: the covariance of z from the linearised least-squares problem (Ceres, dense SVD,
/// unseen directions dropped); NaNs (and u.note) when Ceres cannot compute it.
std::vector<double> covariance_of(const Linearisation& l, Uncertainty& u) {
    const std::size_t n = static_cast<std::size_t>(l.z0.size());
    ceres::Problem problem;
    std::vector<double> z(l.z0.data(), l.z0.data() + n);
    problem.AddResidualBlock(new Linearised(l.r0, l.jac, l.z0), nullptr, z.data());
    ceres::Covariance::Options options;
    options.algorithm_type = ceres::DENSE_SVD;
    options.null_space_rank = -1;  // drop directions the data do not see instead of failing
    options.min_reciprocal_condition_number = 1e-10;
    ceres::Covariance covariance(options);
    std::vector<double> cov(n * n, std::nan(""));
    const std::vector<std::pair<const double*, const double*>> blocks = {{z.data(), z.data()}};
    if (covariance.Compute(blocks, &problem)) covariance.GetCovarianceBlock(z.data(), z.data(), cov.data());
    else u.note = "Ceres could not compute the covariance";
    return cov;
}

/// Step 5: standard errors, intervals, and the parameters the data cannot pin down.
void standard_errors(const ParameterSpace& space, const Linearisation& l, const std::vector<double>& cov,
                     const std::vector<double>& blind_share, Uncertainty& u) {
    const std::size_t n = space.size();
    const auto m = l.r0.size();
    for (std::size_t k = 0; k < n; ++k) {
        const ParameterSpec& p = space.free(k);
        const bool blind = std::sqrt(blind_share[k]) > 0.5;
        const double se = blind ? HUGE_VAL : std::sqrt(std::max(0.0, cov[k * n + k]));
        u.std_error_natural.push_back(se);
        u.low.push_back(space.from_natural(k, l.z0[k] - se));
        u.high.push_back(space.from_natural(k, l.z0[k] + se));
        std::ostringstream why;
        if (blind)
            why << "lies in a direction the targets do not see (" << m << " targets for " << n
                << " free parameters, or collinear columns): its value is set by the start point and the solver's path, not the data";
        else if (se / l.unit_scale[k] > 0.25)
            why << "one standard error spans " << static_cast<int>(std::round(100 * se / l.unit_scale[k])) << " % of its bounds";
        if (!why.str().empty()) u.poorly_identified.push_back(p.name + ": " + why.str());
    }
}

}  // namespace

Uncertainty estimate_uncertainty(SolveContext& ctx, const SolveResult& sol) {
    Uncertainty u;
    if (sol.best_eval.failed || sol.best.empty()) {
        u.note = "not computed: the best point has no successful runs";
        return u;
    }
    DifferencePoints d;
    if (!difference_points(ctx, sol, u, d)) return u;
    const Linearisation l = linearise(ctx, sol, d);
    const std::vector<double> blind = blind_shares(l, u);
    const std::vector<double> cov = covariance_of(l, u);
    standard_errors(ctx.space, l, cov, blind, u);
    u.computed = true;
    return u;
}

}  // namespace gradem::cal
