#include "lab_data/popovics.hpp"

#include <ceres/ceres.h>

#include <cmath>
#include <limits>

namespace gradem::lab {
namespace {

constexpr std::size_t kMaxFitPoints = 400;

// Residual of one sample, scaled by the stress scale f0 so that it is dimensionless.
struct PopovicsResidual {
    double strain, stress, f0, e0;
    template <typename T>
    bool operator()(const T* p, T* residual) const {
        const T fc = f0 * exp(p[0]);
        const T ec = e0 * exp(p[1]);
        const T n = 1.0 + exp(p[2]);
        const T x = strain / ec;
        residual[0] = (fc * n * x / (n - 1.0 + pow(x, n)) - stress) / f0;
        return true;
    }
};

}  // namespace

double popovics_stress(double strain, double peak_stress_pa, double strain_at_peak, double modulus_pa) {
    const double secant = peak_stress_pa / strain_at_peak;
    const double n = modulus_pa / (modulus_pa - secant);
    const double x = strain / strain_at_peak;
    return peak_stress_pa * n * x / (n - 1.0 + std::pow(x, n));
}

PopovicsFit fit_popovics(const StressStrainCurve& c, std::size_t peak_index, double strain_at_peak_guess,
                         double modulus_guess) {
    PopovicsFit fit;
    std::vector<std::size_t> idx;
    for (std::size_t k = 0; k <= peak_index && k < c.strain.size(); ++k)
        if (c.strain[k] > 0 && c.stress_pa[k] > 0) idx.push_back(k);
    if (idx.size() < 6) {
        fit.message = "fewer than 6 positive samples on the ascending branch";
        return fit;
    }
    const std::size_t stride = (idx.size() + kMaxFitPoints - 1) / kMaxFitPoints;
    const double f0 = c.stress_pa[peak_index];
    const double e0 = strain_at_peak_guess > 0 ? strain_at_peak_guess : c.strain[peak_index];
    const double secant = f0 / e0;
    const double n0 = (modulus_guess > 1.05 * secant) ? modulus_guess / (modulus_guess - secant) : 2.0;
    double p[3] = {0.0, 0.0, std::log(n0 - 1.0)};

    ceres::Problem problem;
    for (std::size_t j = 0; j < idx.size(); j += stride) {
        const std::size_t k = idx[j];
        problem.AddResidualBlock(new ceres::AutoDiffCostFunction<PopovicsResidual, 1, 3>(
                                     new PopovicsResidual{c.strain[k], c.stress_pa[k], f0, e0}),
                                 nullptr, p);
        ++fit.points;
    }
    problem.SetParameterLowerBound(p, 2, std::log(1e-3));  // n >= 1.001
    problem.SetParameterUpperBound(p, 2, std::log(100.0));
    ceres::Solver::Options options;
    options.linear_solver_type = ceres::DENSE_QR;
    options.max_num_iterations = 200;
    options.logging_type = ceres::SILENT;
    options.minimizer_progress_to_stdout = false;
    ceres::Solver::Summary summary;
    ceres::Solve(options, &problem, &summary);
    fit.converged = summary.termination_type == ceres::CONVERGENCE;
    fit.message = summary.message;

    const double n = 1.0 + std::exp(p[2]);
    fit.n = n;
    fit.peak_stress_pa = f0 * std::exp(p[0]);
    fit.strain_at_peak = e0 * std::exp(p[1]);
    fit.elastic_modulus_pa = n / (n - 1.0) * fit.peak_stress_pa / fit.strain_at_peak;
    const double m = static_cast<double>(fit.points);
    fit.rms_residual_pa = f0 * std::sqrt(2.0 * summary.final_cost / m);

    const double nan = std::numeric_limits<double>::quiet_NaN();
    fit.peak_stress_se_pa = fit.strain_at_peak_se = fit.elastic_modulus_se_pa = nan;
    ceres::Covariance::Options cov_options;
    ceres::Covariance covariance(cov_options);
    const std::vector<std::pair<const double*, const double*>> blocks = {{p, p}};
    double cov[9];
    if (fit.points > 3 && covariance.Compute(blocks, &problem) && covariance.GetCovarianceBlock(p, p, cov)) {
        const double s2 = 2.0 * summary.final_cost / (m - 3.0);  // residual variance (scaled units)
        const double g[3] = {1.0, -1.0, -1.0 / n};              // ∂ln E/∂(ln f'c, ln ε'c, ln(n−1))
        double var_ln_e = 0;
        for (int i = 0; i < 3; ++i)
            for (int j = 0; j < 3; ++j) var_ln_e += g[i] * cov[3 * i + j] * g[j];
        fit.peak_stress_se_pa = fit.peak_stress_pa * std::sqrt(s2 * cov[0]);
        fit.strain_at_peak_se = fit.strain_at_peak * std::sqrt(s2 * cov[4]);
        fit.elastic_modulus_se_pa = fit.elastic_modulus_pa * std::sqrt(s2 * std::max(var_ln_e, 0.0));
    }
    return fit;
}

}  // namespace gradem::lab
