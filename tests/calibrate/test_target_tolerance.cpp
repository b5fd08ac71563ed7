// When a calibrated target counts as met (calibrate/target_tolerance.hpp: modulus and peak
// within 5 %, strain at peak within 10 %), as the calibration summary reports it.
#include <catch2/catch.hpp>
#include <cmath>

#include "calibrate/target_tolerance.hpp"
#include "calibrate_fixture.hpp"
#include "experiments/config/cube_config.hpp"
#include "reports/calibration_report.hpp"

namespace fs = std::filesystem;
using namespace gradem;
using gradem::test::TempDir;

namespace {

/// A calibrated stage whose seed means sit at lab × (1 + error) for the given relative errors
/// (modulus, peak, strain at peak) on every sand.
cal::CalibrationResult result_with_errors(const cal::CalibrationProblem& p, const double (&error)[3]) {
    cal::CalibrationStage st;
    st.label = "joint";
    st.solution.method = "scaling";
    for (std::size_t s = 0; s < p.sands.size(); ++s) {
        st.fitted.push_back(s);
        cal::SandOutcome o;
        o.sand = s;
        o.ok = 2;
        for (cal::Quantity q : cal::kQuantities) {
            const int k = static_cast<int>(q);
            o.mean[k] = cal::target_of(p.targets[s], q).mean * (1.0 + error[k]);
            o.std[k] = 0.01 * o.mean[k];
        }
        st.solution.best_eval.sands.push_back(o);
    }
    cal::CalibrationResult r;
    r.stages.push_back(st);
    return r;
}

/// The summary's "met" flag of sand 0's target `quantity`.
bool met_in_summary(const cal::CalibrationProblem& p, const double (&error)[3], const std::string& quantity) {
    const nlohmann::json j = report::summary_json(p, result_with_errors(p, error));
    for (const auto& t : j.at("targets"))
        if (t.at("sand") == p.sands[0] && t.at("quantity") == quantity) return t.at("met").get<bool>();
    FAIL("no target " << quantity);
    return false;
}

}  // namespace

TEST_CASE("target tolerances: modulus and peak within 5 %, strain at peak within 10 %", "[calibrate][report]") {
    using cal::Quantity;
    CHECK(cal::target_met(Quantity::strain, 0.08));
    CHECK(cal::target_met(Quantity::strain, -0.08));
    CHECK_FALSE(cal::target_met(Quantity::strain, 0.12));
    CHECK_FALSE(cal::target_met(Quantity::modulus, 0.06));
    CHECK_FALSE(cal::target_met(Quantity::peak, -0.06));
    CHECK(cal::target_met(Quantity::peak, 0.04));
    CHECK_FALSE(cal::target_met(Quantity::modulus, std::nan("")));

    // The calibration summary decides with the same table, in json and markdown.
    TempDir dir("target-tolerance");
    auto model = cal::make_analytic_model(2);
    const exp::MaterialParams base = exp::load_cube_config(test::calibration_base_config()).material;
    test::write_text(dir.path / "lab_results.json",
                     test::synthetic_lab_results(*model, {"pre-blended", "Van Buren"}, base, {1, 2}).dump(1));
    const cal::CalibrationProblem p =
        cal::load_calibration_problem(test::write_problem(dir.path, "model = \"analytic\"\n", ""));

    CHECK(met_in_summary(p, {0.01, -0.02, 0.08}, "strain_at_peak"));
    CHECK_FALSE(met_in_summary(p, {0.01, -0.02, 0.12}, "strain_at_peak"));
    CHECK_FALSE(met_in_summary(p, {0.06, -0.02, 0.08}, "modulus"));
    CHECK(met_in_summary(p, {0.06, -0.02, 0.08}, "peak_stress"));

    const std::string all_met = report::summary_markdown(p, result_with_errors(p, {0.01, -0.02, 0.08}));
    CHECK_THAT(all_met, Catch::Contains("Every target is met (modulus and peak within 5 %, strain at peak within 10 %"));
    const std::string strain_off = report::summary_markdown(p, result_with_errors(p, {0.01, -0.02, 0.12}));
    CHECK_THAT(strain_off, Catch::Contains("**Targets not met") && Catch::Contains("strain at peak (fitted)"));
    CHECK_THAT(strain_off, !Catch::Contains("chord modulus (fitted)"));
    const std::string modulus_off = report::summary_markdown(p, result_with_errors(p, {0.06, -0.02, 0.08}));
    CHECK_THAT(modulus_off, Catch::Contains("chord modulus (fitted)") && !Catch::Contains("strain at peak (fitted)"));
}
