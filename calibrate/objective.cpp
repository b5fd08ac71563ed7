#include "calibrate/objective.hpp"

#include <cmath>

namespace gradem::cal {

std::vector<double> residuals(const Evaluation& e, const CalibrationProblem& problem) {
    std::vector<double> r;
    for (const SandOutcome& s : e.sands)
        for (Quantity q : problem.fitted_quantities()) {
            const double w = problem.weights.of(q);
            const double lab = target_of(problem.targets[s.sand], q).mean;
            const double sim = s.value(q);
            r.push_back(e.failed || !std::isfinite(sim) ? w * problem.solver.penalty : w * (sim / lab - 1.0));
        }
    return r;
}

double objective(const std::vector<double>& r) {
    double j = 0.0;
    for (double x : r) j += x * x;
    return j;
}

Evaluation rescaled(const Evaluation& e, double alpha, double beta) {
    Evaluation out = e;
    const double factor[kQuantityCount] = {alpha, beta, beta / alpha, beta};  // by Quantity: E, σ, ε, σt
    for (SandOutcome& s : out.sands)
        for (int k = 0; k < kQuantityCount; ++k) {
            s.mean[k] *= factor[k];
            s.std[k] *= factor[k];
        }
    for (auto* runs : {&out.runs, &out.tension_runs})
        for (RunOutcome& r : *runs) {
            r.modulus_pa *= alpha;
            r.peak_pa *= beta;
            r.strain_at_peak *= beta / alpha;
            for (double& x : r.curve_strain) x *= beta / alpha;
            for (double& x : r.curve_stress_pa) x *= beta;
        }
    return out;
}

Scales best_scales(const Evaluation& e, const CalibrationProblem& problem, bool stiffness, bool strength) {
    // Normal equations of the 2-unknown linear least squares in (a, b) = (ln α, ln β).
    double aa = 0, ab = 0, bb = 0, ra = 0, rb = 0;
    for (const SandOutcome& s : e.sands) {
        const SandTargets& t = problem.targets[s.sand];
        const double dE = std::log(s.value(Quantity::modulus) / t.modulus.mean);
        const double dS = std::log(s.value(Quantity::peak) / t.peak.mean);
        const double dP = std::log(s.value(Quantity::strain) / t.strain.mean);
        const double wE = std::pow(problem.weights.modulus, 2), wS = std::pow(problem.weights.peak, 2),
                     wP = std::pow(problem.weights.strain, 2);
        // rows: wE (a + dE), wS (b + dS), wP (b − a + dP)
        aa += wE + wP;
        bb += wS + wP;
        ab += -wP;
        ra += -wE * dE + wP * dP;
        rb += -wS * dS - wP * dP;
        if (problem.tension.fitted() && problem.weights.tension > 0.0) {  // row wT (b + dT): σt scales with the strengths alone
            const double dT = std::log(s.value(Quantity::tension) / t.tension.mean), wT = std::pow(problem.weights.tension, 2);
            bb += wT;
            rb += -wT * dT;
        }
    }
    Scales sc;
    if (stiffness && strength) {
        const double det = aa * bb - ab * ab;
        if (std::fabs(det) > 1e-300) {
            sc.alpha = std::exp((ra * bb - ab * rb) / det);
            sc.beta = std::exp((aa * rb - ab * ra) / det);
        }
    } else if (stiffness && aa > 0) {
        sc.alpha = std::exp(ra / aa);
    } else if (strength && bb > 0) {
        sc.beta = std::exp(rb / bb);
    }
    if (!std::isfinite(sc.alpha)) sc.alpha = 1.0;
    if (!std::isfinite(sc.beta)) sc.beta = 1.0;
    return sc;
}

double z_score(double sim_mean, double sim_std, int n_sim, const TargetStat& lab) {
    const double sim_var = n_sim > 1 && std::isfinite(sim_std) ? sim_std * sim_std / n_sim : 0.0;
    const double var = lab.std * lab.std + sim_var;
    return std::isfinite(var) && var > 0 ? (sim_mean - lab.mean) / std::sqrt(var) : std::nan("");
}

}  // namespace gradem::cal
