// The analytic stand-in for the cube test: closed-form macro response with the DEM model's
// structure, so calibration logic can be tested in milliseconds (twin experiments).
//   E      = E* k_s (1 − 0.15 v)                               [Pa]
//   σpeak  = σ̄c p_s ρ^q_s (1 − r_s v)                          [Pa]
//   εpeak  = D σpeak / E,  D = 1.05 + a_s v + g_s ln ρ         [-]
// with ρ = c̄/σ̄c, v = strength cv, and per-sand coefficients (k, p, q, r, a, g) that differ,
// so a joint fit of two sands pins down four parameters. Another bond law adds ductility to
// the shape index D (its parameters are dimensionless, so the homogeneity is kept):
//   D += Law::analytic_ductility(its parameters, h)
// with a per-sand h; each law's header gives its term (e.g. the soft bond's h ln(1 + (1 − γ²)/ζ),
// its fracture energy over its elastic energy at σ̄c); a law without the hook adds nothing. The direct-tension test (CubeTest::tension) is linear to its peak:
//   E_t = E (as in compression),  σt = σ̄c t_s (1 − r_s v),  εt = σt / E_t
// with a per-sand t_s of 0.40-0.45, so σc/σt = p_s ρ^q_s / t_s ≈ 3 (as low as parallel-bond
// specimens give, Potyondy & Cundall 2004). Cost: every run reports 1000 particles, 1 step and a nominal
// wall time of kNominalWallSeconds (deterministic, so answers stay bitwise comparable).
// It is exactly homogeneous (E ∝ E*, σ ∝ σ̄c, ε ∝ σ̄c/E*) like the DEM model. Seed noise: every output is multiplied by
// 1 + noise·z with z a deterministic pseudo-normal draw from (sand, seed, output).
#include <cmath>
#include <cstdio>
#include <memory>

#include "calibrate/cube_model.hpp"
#include "core/random.hpp"

namespace gradem::cal {
namespace {

struct SandCoefficients {
    double k, p, q, r, a, g, h;
};
constexpr SandCoefficients kSands[] = {{0.90, 1.80, 0.35, 0.90, 1.20, 0.05, 0.25}, {0.75, 1.60, 0.25, 0.60, 0.80, 0.15, 0.12},
                                       {0.82, 1.70, 0.30, 0.75, 1.00, 0.10, 0.18}};

constexpr double kNominalWallSeconds = 1e-3;  ///< [s] per run: the cost the stand-in reports

constexpr double kTensionFactor[] = {0.45, 0.40, 0.42};  ///< t_s: σt / σ̄c before the cv term [-]

/// The bond law's extra ductility in D (see the header); none for a law without
/// analytic_ductility (the parallel bond).
double law_ductility(const BondParams& b, double h) {
    return visit_bond_law(b.model, [&](auto kernel) {
        using Law = decltype(kernel);
        // A law that declares the hook must take (its parameters, h): another signature fails to compile.
        if constexpr (requires { &Law::analytic_ductility; }) return Law::analytic_ductility(b.law<Law>(), h);
        else return 0.0;
    });
}

/// A deterministic N(0,1)-like draw: the sum of 12 uniforms minus 6.
double pseudo_normal(std::uint64_t sand, std::uint64_t seed, std::uint64_t output) {
    double sum = 0.0;
    for (std::uint64_t k = 0; k < 12; ++k) sum += hashed_uniform(seed, sand * 16 + output, k);
    return sum - 6.0;
}

class AnalyticCubeModel final : public CubeModel {
public:
    AnalyticCubeModel(std::size_t sands, double noise, double diverge_above)
        : sands_(sands), noise_(noise), diverge_above_(diverge_above) {}

    void prepare(const PackingSeeds&, int, const std::function<void(const std::string&)>&) override {}

    RunOutcome run(const RunRequest& q, double) const override {
        RunOutcome out = q.test == CubeTest::tension ? tension(q) : compression(q);
        if (out.ok()) out.wall_seconds = kNominalWallSeconds;
        return out;
    }

    std::string fingerprint() const override { return run_fingerprint(CubeTest::compression); }

    std::string run_fingerprint(CubeTest test) const override {
        // Still v1: the parallel bond's outputs did not change when the other laws' terms came;
        // their runs differ from it in the material key (model and its parameters).
        char buf[96];
        std::snprintf(buf, sizeof buf, "analytic stand-in v1; sands %zu; noise %a; diverge %a", sands_, noise_, diverge_above_);
        return test == CubeTest::tension ? std::string(buf) + "; direct tension v1" : std::string(buf);
    }

private:
    RunOutcome tension(const RunRequest& q) const {
        const BondParams& b = q.material.bond;
        const double v = b.tensile_strength_mean > 0.0 ? b.tensile_strength_std / b.tensile_strength_mean : 0.0;
        auto noisy = [&](double x, std::uint64_t output) { return x * (1.0 + noise_ * pseudo_normal(q.sand, q.seed, output)); };
        RunOutcome out;
        out.particles = 1000;
        out.steps = 1;
        out.modulus_pa = noisy(q.material.contact.effective_modulus * kSands[q.sand % 3].k * (1.0 - 0.15 * v), 4);
        out.peak_pa = noisy(b.tensile_strength_mean * kTensionFactor[q.sand % 3] * (1.0 - kSands[q.sand % 3].r * v), 5);
        out.strain_at_peak = out.peak_pa / out.modulus_pa;
        out.poisson = 0.15;
        for (int i = 1; i <= 10; ++i) {
            out.curve_strain.push_back(out.strain_at_peak * i / 10.0);
            out.curve_stress_pa.push_back(out.peak_pa * i / 10.0);
        }
        out.status = OutcomeStatus::ok;
        return out;
    }

    RunOutcome compression(const RunRequest& q) const {
        const SandCoefficients& c = kSands[q.sand % 3];
        const BondParams& b = q.material.bond;
        const double estar = q.material.contact.effective_modulus;
        const double v = b.tensile_strength_mean > 0.0 ? b.tensile_strength_std / b.tensile_strength_mean : 0.0;
        const double rho = b.cohesion_mean / b.tensile_strength_mean;
        auto noisy = [&](double x, std::uint64_t output) { return x * (1.0 + noise_ * pseudo_normal(q.sand, q.seed, output)); };
        RunOutcome out;
        out.particles = 1000;
        out.steps = 1;
        if (diverge_above_ > 0.0 && estar > diverge_above_ * 1e9) {
            out.status = OutcomeStatus::diverged;
            out.reason = "diverged: kinetic energy blew up (analytic stand-in, E* above its limit)";
            return out;
        }
        out.modulus_pa = noisy(estar * c.k * (1.0 - 0.15 * v), 1);
        out.peak_pa = noisy(b.tensile_strength_mean * c.p * std::pow(rho, c.q) * (1.0 - c.r * v), 2);
        const double d = 1.05 + c.a * v + c.g * std::log(rho) + law_ductility(b, c.h);
        out.strain_at_peak = noisy(d * out.peak_pa / out.modulus_pa, 3);
        out.poisson = 0.15;
        // A Popovics curve through the three numbers (for the curve outputs).
        const double n = out.modulus_pa / (out.modulus_pa - out.peak_pa / out.strain_at_peak);
        for (int i = 1; i <= 60; ++i) {
            const double e = out.strain_at_peak * 1.5 * i / 60.0, x = e / out.strain_at_peak;
            out.curve_strain.push_back(e);
            out.curve_stress_pa.push_back(out.peak_pa * x * n / (n - 1.0 + std::pow(x, n)));
        }
        out.status = OutcomeStatus::ok;
        return out;
    }

    std::size_t sands_;
    double noise_, diverge_above_;
};

}  // namespace

std::unique_ptr<CubeModel> make_analytic_model(std::size_t sands, double noise, double diverge_above_gpa) {
    return std::make_unique<AnalyticCubeModel>(sands, noise, diverge_above_gpa);
}

}  // namespace gradem::cal
