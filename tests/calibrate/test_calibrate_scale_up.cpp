// Scales set on larger specimens ([scale_up] edge_mm, seeds; docs/calibration.md "Scales set on
// larger specimens"): the shape is fitted on small cubes, then the fit's point runs once on the
// scale-up cubes and the moduli and strengths are rescaled there in closed form. Oracle: a
// size effect of known factors (moduli × 1.12, strengths × 1.08 on the larger cubes) is undone
// exactly, so the result recovers the parameters the lab targets were made with.
#include <catch2/catch.hpp>
#include <algorithm>
#include <cmath>

#include <toml++/toml.h>

#include "calibrate/problem.hpp"
#include "calibrate/scale_up.hpp"
#include "calibrate/study/study.hpp"
#include "calibrate/validation.hpp"
#include "calibrate_fixture.hpp"
#include "reports/calibrated_config.hpp"
#include "reports/calibration_report.hpp"

namespace fs = std::filesystem;
using namespace gradem;
using gradem::test::TempDir;

namespace {

const std::vector<std::string> kSands = {"pre-blended", "Van Buren"};
constexpr double kModulusEffect = 1.12, kStrengthEffect = 1.08;  // larger cubes vs the fit's
const std::vector<double> kTruth = {20.0, 12.0, 1.6, 0.25};        // E* GPa, σ̄c MPa, c̄/σ̄c, cv

/// Lab targets = the LARGER specimens at the truth; the fit runs on the small ones.
fs::path problem_with(const fs::path& dir, const std::string& tables) {
    const test::ScaledSpecimenModel large(kModulusEffect, kStrengthEffect);
    test::write_text(dir / "lab_results.json",
                     test::synthetic_lab_results(large, kSands, test::material_at(kTruth), {101, 102, 103, 104, 105, 106}).dump(1));
    return test::write_problem(dir, "model = \"analytic\"\nseeds = [1, 2, 3]\n",
                               "strain_weight = 1.0\n[solver]\nmethod = \"scaling\"\nmax_runs = 300\ntolerance = 0.002\n" + tables +
                                   "\n[output]\ndir = \"out\"\n");
}

/// The fit on the stand-in, the scale-up and validation sets on the larger specimens.
cal::ValidatedModel sized_model(const cal::CalibrationProblem& p) {
    cal::ValidatedModel model(cal::make_analytic_model(2, 0.001), kSands.size());
    if (p.scale_up.enabled())
        model.add(cal::SpecimenSet::scale_up, std::make_unique<test::ScaledSpecimenModel>(kModulusEffect, kStrengthEffect),
                  p.scale_up.seeds);
    if (p.validation.enabled())
        model.add(cal::SpecimenSet::validation, std::make_unique<test::ScaledSpecimenModel>(kModulusEffect, kStrengthEffect),
                  p.validation.seeds);
    return model;
}

double rel_error_of(const nlohmann::json& summary, const std::string& role, const std::string& sand, const std::string& q) {
    for (const auto& t : summary["targets"])
        if (t["role"] == role && t["sand"] == sand && t["quantity"] == q) return t["rel_error"].get<double>();
    return std::nan("");
}

}  // namespace

TEST_CASE("scales set on larger specimens undo a known size effect", "[calibrate][scale_up]") {
    TempDir dir("cal-scale-up");
    const cal::CalibrationProblem without = cal::load_calibration_problem(problem_with(dir.path, "[validation]\nseeds = [11, 12]\n"));
    const cal::CalibrationProblem with = cal::load_calibration_problem(
        problem_with(dir.path, "[scale_up]\nedge_mm = 5.0\nseeds = [21, 22]\n[validation]\nedge_mm = 5.0\nseeds = [11, 12]\n"));
    REQUIRE(with.scale_up.enabled());
    CHECK(with.scale_up.edge == Approx(5e-3));

    // Without the scale-up the fit lands on the small cubes' parameters (moduli and strengths
    // high by the size effect) and misses on the larger validation cubes by that effect.
    cal::ValidatedModel plain_model = sized_model(without);
    const cal::CalibrationResult plain = cal::run_calibration(without, plain_model);
    const nlohmann::json plain_summary = report::summary_json(without, plain);
    CHECK(plain.stages.at(0).result()[0] == Approx(kTruth[0] * kModulusEffect).epsilon(0.03));
    CHECK(rel_error_of(plain_summary, "validation", "pre-blended", "modulus") == Approx(kModulusEffect - 1.0).margin(0.03));
    CHECK(plain_summary["stages"][0]["validation"]["holds"] == false);

    // With it: one run per sand and scale-up seed, apart from the budget; α and β are the inverse
    // effects and the result is the truth; the larger cubes' targets are met and validation holds.
    cal::ValidatedModel model = sized_model(with);
    const cal::CalibrationResult r = cal::run_calibration(with, model);
    const cal::CalibrationStage& st = r.stages.at(0);
    CHECK(st.scale_up.runs == 4);
    CHECK(r.scale_up_runs == 4);
    CHECK(r.scale_up_cost.executed == 4);  // apart from the fit's cost: 4 stand-in runs of 1000 grains x 1 step
    CHECK(r.scale_up_cost.particle_steps == 4000.0);
    CHECK(st.scale_up.measured.values == st.solution.best);
    CHECK(st.scale_up.scales.alpha == Approx(1.0 / kModulusEffect).epsilon(0.02));
    CHECK(st.scale_up.scales.beta == Approx(1.0 / kStrengthEffect).epsilon(0.02));
    CHECK(st.result()[0] == Approx(kTruth[0]).epsilon(0.03));
    CHECK(st.result()[1] == Approx(kTruth[1]).epsilon(0.03));
    CHECK(st.result()[2] == st.solution.best[2]);  // a shape parameter is not touched
    CHECK(st.validation.evaluation.values == st.result());
    const nlohmann::json summary = report::summary_json(with, r);
    for (const std::string& sand : kSands)
        for (const char* q : {"modulus", "peak_stress", "strain_at_peak"}) {
            INFO(sand << " " << q);
            CHECK(std::fabs(rel_error_of(summary, "scale-up", sand, q)) < 0.02);
            CHECK(std::fabs(rel_error_of(summary, "validation", sand, q)) < 0.02);
        }
    CHECK(summary["stages"][0]["validation"]["holds"] == true);
    CHECK(summary["stages"][0]["scale_up"]["done"] == true);
    CHECK(summary["runs"]["scale_up"] == 4);
    // The milestone gives the seeds and the edge as a person writes them ("5 mm", not "5.000000").
    const auto milestone = std::find_if(r.log.begin(), r.log.end(), [](const std::string& line) { return line.rfind("scale-up on", 0) == 0; });
    REQUIRE(milestone != r.log.end());
    CHECK_THAT(*milestone, Catch::StartsWith("scale-up on 2 seeds, edge 5 mm: 4 runs (0 from the ledger); moduli x "));
    CHECK(summary["stages"][0]["parameters"][0]["value"].get<double>() == st.result()[0]);
    CHECK(summary["stages"][0]["parameters"][0]["fit_value"].get<double>() == st.solution.best[0]);
    const std::string md = report::summary_markdown(with, r);
    CHECK_THAT(md, Catch::Contains("**Scales set** on 5 mm cubes, packing seeds 21, 22"));
    CHECK_THAT(report::brief_report(with, r), Catch::Contains("scales set on 5 mm cubes"));

    // The written result is the scale-up's: its calibrated configs and the studies that read
    // summary.json run the scale-up edge.
    report::write_calibration_outputs(with, r);
    const cal::CalibratedPoint point = cal::load_calibrated_point(with.out_dir / "summary.json");
    CHECK(point.problem.base.specimen.genesis.edge == Approx(5e-3));
    CHECK(point.values == st.result());
    const toml::table calibrated = toml::parse_file((with.out_dir / "calibrated-pre-blended.toml").string());
    CHECK(calibrated["genesis"]["edge_mm"].value<double>().value_or(0.0) == Approx(5.0));

    // A second run serves the scale-up from the ledger.
    const cal::CalibrationResult again = cal::run_calibration(with, model);
    CHECK(again.stages.at(0).scale_up.from_ledger == 4);
    CHECK(again.runs_executed == 0);
}

// A standard error needs two seeds: scales set on one cube per sand carry that cube's scatter,
// and their noise floor is "not measured", not 0 %.
TEST_CASE("the noise floor of one seed per sand is not measured, not zero", "[calibrate][scale_up]") {
    cal::SandOutcome one;
    one.ok = one.tension_ok = 1;
    for (int k = 0; k < cal::kQuantityCount; ++k) one.mean[k] = 1.0, one.std[k] = std::nan("");
    cal::SandOutcome two = one;
    two.ok = two.tension_ok = 2;
    for (int k = 0; k < cal::kQuantityCount; ++k) two.std[k] = 0.1 * (k + 1);
    cal::Evaluation single, mixed;
    single.sands = {one, one};
    mixed.sands = {one, two};
    double floor_single[cal::kQuantityCount] = {0, 0, 0, 0}, floor_mixed[cal::kQuantityCount] = {0, 0, 0, 0};
    cal::measure_noise(single, floor_single);
    cal::measure_noise(mixed, floor_mixed);
    for (int k = 0; k < cal::kQuantityCount; ++k) {
        CHECK(std::isnan(floor_single[k]));
        CHECK(floor_mixed[k] == Approx(0.1 * (k + 1) / std::sqrt(2.0)));  // the sand that has two seeds
    }

    TempDir dir("cal-scale-up-one-seed");
    const cal::CalibrationProblem p =
        cal::load_calibration_problem(problem_with(dir.path, "[scale_up]\nedge_mm = 5.0\nseeds = [21]\n"));
    cal::ValidatedModel model = sized_model(p);
    const cal::CalibrationResult r = cal::run_calibration(p, model);
    REQUIRE(r.stages.at(0).scale_up.runs == 2);
    CHECK_THAT(report::summary_markdown(p, r),
               Catch::Contains("modulus not measured (one seed), peak not measured (one seed), strain not measured (one seed) on the "
                               "scale-up specimens"));
    CHECK(report::summary_json(p, r)["stages"][0]["scale_up"]["noise_floor_rel_se"]["modulus"].is_null());
}

TEST_CASE("bad [scale_up] tables are refused naming the key, line and rule", "[calibrate][scale_up]") {
    TempDir dir("cal-scale-up-bad");
    auto refused = [&](const std::string& tables, const std::string& what) {
        INFO(tables);
        CHECK_THROWS_WITH(cal::load_calibration_problem(problem_with(dir.path, tables)),
                          Catch::Contains("problem.toml:") && Catch::Contains(what));
    };
    refused("[scale_up]\nedge_mm = 5.0\n", "'scale_up.seeds' is required");
    refused("[scale_up]\nedge_mm = 1.0\nseeds = [21]\n", "'scale_up.edge_mm' = 1.0 violates >= 3 x the largest grain (0.8 mm)");
    refused("[scale_up]\nseeds = [21]\n[validation]\nseeds = [21]\n", "seed 21 is also a scale-up seed");
    refused("[scale_up]\nseeds = [21]\nedges = 5\n", "unknown key 'scale_up.edges'");
    refused("[scale_up]\nseeds = [21]\n[parameters.effective_modulus_gpa]\nfree = false\n[parameters.tensile_strength_mpa]\nfree = false\n",
            "needs a free stiffness or strength parameter");
}
