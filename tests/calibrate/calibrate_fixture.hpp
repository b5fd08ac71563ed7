#pragma once
// Helpers of the calibration tests: a problem folder with a lab_results.json made from known
// parameters (a twin experiment) and a calibration TOML pointing at it.
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <functional>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "calibrate/calibration.hpp"
#include "calibrate/cube_model.hpp"
#include "calibrate/parameters.hpp"
#include "experiments/config/cube_config.hpp"
#include "../temp_dir.hpp"

namespace gradem::test {

inline std::filesystem::path calibration_base_config() {
    return std::filesystem::path(GRADEM_SOURCE_DIR) / "experiments" / "configs" / "calibration_cube.toml";
}

/// The base config's material with the four default free parameters (E* GPa, σ̄c MPa, c̄/σ̄c,
/// strength cv, in this order) set to `values`.
inline exp::MaterialParams material_at(const std::vector<double>& values) {
    const exp::MaterialParams base = exp::load_cube_config(calibration_base_config()).material;
    std::vector<cal::ParameterSpec> specs;
    for (const char* name : {"effective_modulus_gpa", "tensile_strength_mpa", "cohesion_ratio", "strength_cv"}) {
        specs.push_back(cal::default_parameter(name, base));
        specs.back().free = true;
    }
    return cal::ParameterSpace(specs, base).material(values);
}

/// Lab targets = the model's seed means at `material` over `seeds` (with their spread as std);
/// with `tension`, also the direct-tension strength (`tensile_strength_mpa`) of its tension test.
inline nlohmann::json synthetic_lab_results(const cal::CubeModel& model, const std::vector<std::string>& sands,
                                            const exp::MaterialParams& material, const std::vector<std::uint64_t>& seeds,
                                            bool tension = false) {
    nlohmann::json out = {{"schema", "gradem-lab-results/1"}, {"representative_data", true},
                          {"note", "synthetic twin-experiment targets"}, {"sands", nlohmann::json::array()}};
    for (std::size_t s = 0; s < sands.size(); ++s) {
        double sum[3] = {0, 0, 0}, sq[3] = {0, 0, 0};
        for (std::uint64_t seed : seeds) {
            const cal::RunOutcome o = model.run({s, seed, material}, 0.0);
            const double v[3] = {o.modulus_pa * 1e-6, o.peak_pa * 1e-6, o.strain_at_peak};
            for (int k = 0; k < 3; ++k) sum[k] += v[k], sq[k] += v[k] * v[k];
        }
        const double n = static_cast<double>(seeds.size());
        auto stat = [&](int k) {
            const double mean = sum[k] / n;
            const double var = n > 1 ? std::max(0.0, (sq[k] - n * mean * mean) / (n - 1)) : 0.0;
            return nlohmann::json{{"n", seeds.size()}, {"mean", mean}, {"std", std::sqrt(var) + 0.03 * mean}};
        };
        out["sands"].push_back({{"name", sands[s]}, {"chord_modulus_mpa", stat(0)}, {"peak_stress_mpa", stat(1)}, {"strain_at_peak", stat(2)}});
        if (!tension) continue;
        double t_sum = 0.0;
        for (std::uint64_t seed : seeds) t_sum += model.run({s, seed, material, cal::CubeTest::tension}, 0.0).peak_pa * 1e-6;
        const double t_mean = t_sum / static_cast<double>(seeds.size());
        out["sands"].back()["tensile_strength_mpa"] = {{"n", seeds.size()}, {"mean", t_mean}, {"std", 0.05 * t_mean},
                                                       {"conversion", "synthetic: the stand-in's direct-tension test"}};
    }
    return out;
}

/// The stand-in on other specimens: every modulus × `modulus_factor` and every strength × `strength_factor`
/// (so the strain at peak × strength/modulus), as a larger, better converged cube differs from a small one.
class ScaledSpecimenModel final : public cal::CubeModel {
public:
    /// E x modulus_factor, peak x strength_factor, strain at peak x strength/modulus x shape_factor
    /// (the shape index D = E eps / sigma x shape_factor).
    ScaledSpecimenModel(double modulus_factor, double strength_factor, double shape_factor = 1.0)
        : inner_(cal::make_analytic_model(2, 0.001)), modulus_(modulus_factor), strength_(strength_factor), shape_(shape_factor) {}
    void prepare(const cal::PackingSeeds&, int, const std::function<void(const std::string&)>&) override {}
    cal::RunOutcome run(const cal::RunRequest& q, double t) const override {
        cal::RunOutcome o = inner_->run(q, t);
        o.modulus_pa *= modulus_;
        o.peak_pa *= strength_;
        o.strain_at_peak *= strength_ / modulus_ * shape_;
        return o;
    }
    std::string fingerprint() const override { return inner_->fingerprint() + "; scaled"; }
    std::string run_fingerprint(cal::CubeTest t) const override { return inner_->run_fingerprint(t) + "; scaled"; }

private:
    std::unique_ptr<cal::CubeModel> inner_;
    double modulus_, strength_, shape_;
};

inline void write_text(const std::filesystem::path& p, const std::string& text) {
    std::ofstream(p) << text;
}

/// A calibration TOML in `dir` with the given extra tables/keys (appended after [calibration]).
inline std::filesystem::path write_problem(const std::filesystem::path& dir, const std::string& calibration_keys,
                                           const std::string& rest, const std::string& name = "problem.toml") {
    const std::string text = "[calibration]\nbase = \"" + calibration_base_config().string() + "\"\n" + calibration_keys +
                             "\n[targets]\nlab_results = \"lab_results.json\"\n" + rest + "\n";
    write_text(dir / name, text);
    return dir / name;
}

}  // namespace gradem::test
