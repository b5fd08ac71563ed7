// `gradem study` on the analytic stand-in: the kinds' numbers against the stand-in's closed
// form, resume from the ledger, and the bad inputs of the study files.
#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>
#include <fstream>

#include "calibrate/execution/run_executor.hpp"
#include "calibrate/study/study.hpp"
#include "calibrate/study/size_sweep.hpp"
#include "calibrate/study/study_tables.hpp"
#include "calibrate/study/study_models.hpp"
#include "calibrate_fixture.hpp"
#include "common/input_error.hpp"
#include "experiments/config/cube_config.hpp"
#include "reports/calibration_report.hpp"
#include "reports/study_report.hpp"

namespace fs = std::filesystem;
using namespace gradem;
using gradem::test::TempDir;

namespace {

const std::vector<std::string> kSands = {"pre-blended", "Van Buren"};

/// A calibrated analytic problem in `dir`: lab targets from the stand-in at the base material,
/// a short scaling calibration, its summary.json in dir/cal. Returns the summary path.
fs::path calibrated_summary(const fs::path& dir, const std::string& calibration_keys = "") {
    auto model = cal::make_analytic_model(kSands.size());
    const exp::MaterialParams base = exp::load_cube_config(test::calibration_base_config()).material;
    test::write_text(dir / "lab_results.json", test::synthetic_lab_results(*model, kSands, base, {101, 102, 103, 104}).dump(1));
    const fs::path toml = test::write_problem(dir, "model = \"analytic\"\nseeds = [1, 2]\n" + calibration_keys,
                                              "[solver]\nmax_runs = 30\n[output]\ndir = \"" + (dir / "cal").string() + "\"\n");
    const cal::CalibrationProblem problem = cal::load_calibration_problem(toml);
    auto m = cal::make_model(problem);
    const cal::CalibrationResult r = cal::run_calibration(problem, *m);
    report::write_calibration_outputs(problem, r);
    return dir / "cal" / "summary.json";
}

fs::path write_study(const fs::path& dir, const std::string& study_keys, const std::string& name = "study.toml") {
    test::write_text(dir / name, "[study]\n" + study_keys + "\n[output]\ndir = \"" + (dir / "study-out").string() + "\"\n");
    return dir / name;
}

std::string error_of(const fs::path& toml) {
    try {
        const cal::StudyConfig c = cal::load_study_config(toml);
        cal::run_study(c);
    } catch (const common::InputError& e) {
        return e.what();
    }
    return "";
}

}  // namespace

TEST_CASE("study: Student-t quantile and Welch interval", "[calibrate][study]") {
    CHECK(cal::student_t_975(1.0) == Approx(12.706).epsilon(1e-4));
    CHECK(cal::student_t_975(10.0) == Approx(2.228).epsilon(1e-4));
    CHECK(cal::student_t_975(1e6) == Approx(1.960).epsilon(1e-3));
    // Equal samples, n = 5 each, std 1: se = sqrt(2/5), dof = 8, t = 2.306.
    const cal::Interval i = cal::welch_interval({10.0, 1.0, 5}, {8.0, 1.0, 5});
    CHECK(i.estimate == Approx(2.0));
    CHECK(i.high - i.estimate == Approx(2.306 * std::sqrt(0.4)).epsilon(1e-3));
    CHECK(std::isnan(cal::welch_interval({1, 0, 1}, {1, 0, 5}).low));
}

TEST_CASE("study: gradation_effect gives the seed statistics of the model and a verdict, resumes from the ledger",
          "[calibrate][study]") {
    TempDir dir("study-gradation");
    const fs::path summary = calibrated_summary(dir.path);
    const fs::path toml = write_study(dir.path, "kind = \"gradation_effect\"\ncalibration = \"" + summary.string() + "\"\nseeds = [11, 12, 13, 14]");
    const cal::StudyConfig config = cal::load_study_config(toml);
    const cal::StudyResult r = cal::run_study(config);
    REQUIRE(r.cases.size() == 1);
    CHECK(r.runs_executed == 8);  // 2 sands x 4 seeds
    // Oracle: the same runs made directly with the calibrated material.
    const cal::CalibratedPoint cp = cal::load_calibrated_point(summary);
    const exp::MaterialParams m = cal::ParameterSpace(cp.problem.parameters, cp.problem.base.material).material(cp.values);
    auto model = cal::make_analytic_model(kSands.size());
    std::vector<double> peaks[2];
    for (std::size_t s = 0; s < 2; ++s)
        for (std::uint64_t seed : config.seeds) peaks[s].push_back(model->run({s, seed, m}, 0.0).peak_pa);
    const cal::Sample a = cal::sample_of(peaks[0]), b = cal::sample_of(peaks[1]);
    const nlohmann::json& pair = r.data["pairs"][1];  // modulus, peak, strain
    REQUIRE(pair["quantity"] == "peak_stress");
    CHECK(pair["simulated"]["estimate"].get<double>() == Approx((a.mean - b.mean) * 1e-6).epsilon(1e-12));
    CHECK(pair["simulated"]["low"].get<double>() < pair["simulated"]["estimate"].get<double>());
    CHECK(pair["lab"]["estimate"].get<double>() == Approx((cp.problem.targets[0].peak.mean - cp.problem.targets[1].peak.mean) * 1e-6));
    REQUIRE(r.verdict.size() == 3);
    report::write_study_outputs(r);
    CHECK(fs::exists(config.out_dir / "study.json"));
    CHECK(fs::exists(config.out_dir / "study.md"));

    // Run again: every run is served by the ledger, with the same answer.
    const cal::StudyResult again = cal::run_study(config);
    CHECK(again.runs_executed == 0);
    CHECK(again.runs_from_ledger == 8);
    CHECK(again.data["pairs"] == r.data["pairs"]);
}

TEST_CASE("study: sensitivity recovers the stand-in's exact elasticities", "[calibrate][study]") {
    TempDir dir("study-sensitivity");
    const fs::path summary = calibrated_summary(dir.path);
    const fs::path toml = write_study(dir.path, "kind = \"sensitivity\"\ncalibration = \"" + summary.string() +
                                                    "\"\nseeds = [1, 2, 3]\nparameters = [\"effective_modulus_gpa\", \"tensile_strength_mpa\", \"cohesion_ratio\"]");
    const cal::StudyResult r = cal::run_study(cal::load_study_config(toml));
    REQUIRE(r.cases.size() == 4);
    // E = E* k (…): d ln E / d ln E* = 1; σ ∝ σ̄c (c̄/σ̄c)^q with c̄/σ̄c held: 1; d ln σ / d ln(c̄/σ̄c) = q_s.
    const double q[2] = {0.35, 0.25};
    for (const nlohmann::json& row : r.data["elasticities"]) {
        const std::size_t s = row["sand"] == kSands[0] ? 0 : 1;
        INFO(row.dump());
        if (row["parameter"] == "effective_modulus_gpa") {
            CHECK(row["modulus"]["elasticity"].get<double>() == Approx(1.0).epsilon(1e-9));
            CHECK(std::fabs(row["peak_stress"]["elasticity"].get<double>()) < 1e-9);
        } else if (row["parameter"] == "tensile_strength_mpa") {
            CHECK(row["peak_stress"]["elasticity"].get<double>() == Approx(1.0).epsilon(1e-9));
            CHECK(std::fabs(row["modulus"]["elasticity"].get<double>()) < 1e-9);
        } else {
            CHECK(row["peak_stress"]["elasticity"].get<double>() == Approx(q[s]).epsilon(1e-9));
        }
    }
}

TEST_CASE("study on a shared executor: each case's sands routed to its model, the answer of the thread run bitwise",
          "[calibrate][study]") {
    TempDir dir("study-shared-executor");
    const fs::path summary = calibrated_summary(dir.path);
    const fs::path toml = write_study(dir.path, "kind = \"resolution\"\ncalibration = \"" + summary.string() +
                                                    "\"\nedges_mm = [2.5, 3.0]\nseeds = [1, 2, 3]");
    cal::StudyConfig config = cal::load_study_config(toml);
    const std::vector<cal::CalibrationProblem> problems = cal::study_problems(config);
    REQUIRE(problems.size() == 2);
    CHECK(problems[1].base.specimen.genesis.edge == 3.0e-3);
    CHECK(problems[1].seeds == config.seeds);
    cal::StudyModels models(problems);
    CHECK(models.offset(0) == 0);
    CHECK(models.offset(1) == 2);
    CHECK(models.find(problems[1]) == std::optional<std::size_t>(1));
    cal::CalibrationProblem other = problems[0];
    other.base.specimen.genesis.edge = 4.0e-3;
    CHECK_FALSE(models.find(other).has_value());

    // Routing: the stand-in's coefficients depend on the sand number, so composite sand 2 must
    // run as case 1's sand 0 (not as a third sand of case 0).
    const exp::MaterialParams m = problems[0].base.material;
    const cal::RunOutcome routed = models.run({2, 7, m}, 0.0);
    CHECK(routed.peak_pa == models.model(1).run({0, 7, m}, 0.0).peak_pa);
    CHECK(routed.peak_pa != models.model(0).run({2, 7, m}, 0.0).peak_pa);
    CHECK_THROWS(models.run({4, 7, m}, 0.0));

    // The study through an executor of the StudyModels, as an MPI job runs it, against the
    // plain thread run: the same cases, runs and numbers, bitwise.
    const cal::StudyResult plain = cal::run_study(config);
    config.out_dir = dir.path / "shared";
    config.ledger = config.out_dir / "ledger.sqlite";
    models.prepare(config.seeds, 2, {});
    cal::ThreadExecutor threads(models, 2);
    const cal::StudyExecution execution{models, threads};
    const cal::StudyResult shared = cal::run_study(config, {}, &execution);
    CHECK(shared.runs_executed == plain.runs_executed);
    CHECK(shared.runs_from_ledger == plain.runs_from_ledger);
    CHECK(shared.data == plain.data);
    REQUIRE(shared.cases.size() == plain.cases.size());
    for (std::size_t k = 0; k < plain.cases.size(); ++k)
        for (std::size_t s = 0; s < plain.cases[k].runs.size(); ++s)
            for (std::size_t r = 0; r < plain.cases[k].runs[s].size(); ++r) {
                const cal::RunOutcome &a = plain.cases[k].runs[s][r], &b = shared.cases[k].runs[s][r];
                CHECK(a.modulus_pa == b.modulus_pa);
                CHECK(a.peak_pa == b.peak_pa);
                CHECK(a.strain_at_peak == b.strain_at_peak);
            }
}

TEST_CASE("study: a size sweep of one of the calibration's sands runs that sand only", "[calibrate][study]") {
    TempDir dir("study-one-sand");
    const fs::path summary = calibrated_summary(dir.path);
    const std::string cal_key = "calibration = \"" + summary.string() + "\"\n";
    const fs::path toml = write_study(dir.path, "kind = \"resolution\"\n" + cal_key +
                                                    "edges_mm = [2.5, 3.0]\nseeds = [1, 2]\nsands = [\"Van Buren\"]");
    const cal::StudyConfig config = cal::load_study_config(toml);
    const std::vector<cal::CalibrationProblem> problems = cal::study_problems(config);
    REQUIRE(problems.size() == 2);
    CHECK(problems[0].sands == std::vector<std::string>{"Van Buren"});
    REQUIRE(problems[0].targets.size() == 1);
    const cal::CalibrationProblem full = cal::load_calibrated_point(summary).problem;
    CHECK(problems[0].targets[0].modulus.mean == full.targets[1].modulus.mean);  // Van Buren's lab targets, not the first sand's

    const cal::StudyResult r = cal::run_study(config);
    // Two edges x two seeds x one sand (the stand-in ignores the edge: the second edge's runs
    // are the first's, served by the ledger).
    CHECK(r.runs_executed + r.runs_from_ledger == 2 * 2);
    CHECK(r.runs_failed == 0);
    REQUIRE(r.cases.size() == 2);
    for (const cal::StudyCase& c : r.cases) {
        CHECK(c.sands == std::vector<std::string>{"Van Buren"});
        REQUIRE(c.runs.size() == 1);
        CHECK(c.runs[0].size() == 2);
    }
    // The key changes the study's identity: a sweep of every sand does not resume from this ledger.
    cal::StudyConfig every = config;
    every.sands.clear();
    CHECK(every.describe() != config.describe());

    CHECK_THAT(error_of(write_study(dir.path, "kind = \"resolution\"\n" + cal_key + "edges_mm = [2.5, 3.0]\nsands = [\"Ottawa\"]")),
               Catch::Contains("study.toml:5: key 'study.sands': 'Ottawa' is not a sand of the calibration (pre-blended, Van Buren)"));
    CHECK_THAT(error_of(write_study(dir.path, "kind = \"gradation_effect\"\n" + cal_key + "sands = [\"Van Buren\"]")),
               Catch::Contains("study.toml:4: key 'study.sands' belongs to kinds \"resolution\" and \"fines_truncation\""));
}

TEST_CASE("study: model_form tabulates calibrations with their shape index, sigma_c/sigma_t and cost, resumes",
          "[calibrate][study]") {
    TempDir dir("study-model-form");
    const fs::path summary = calibrated_summary(dir.path);
    const fs::path toml = write_study(dir.path, "kind = \"model_form\"\ncalibrations = [\"" + summary.string() + "\"]");
    const cal::StudyResult r = cal::run_study(cal::load_study_config(toml));
    REQUIRE(r.data["models"].size() == 1);
    const auto& model = r.data["models"][0];
    CHECK(model["sands"][0]["shape_index_lab"].get<double>() > 0.5);
    // The tension tests: the calibration's sands x its seeds (1, 2), at its calibrated parameters.
    CHECK(r.runs_executed == 4);
    CHECK(r.runs_failed == 0);

    // Oracle: σc/σt = the summary's simulated peak / the stand-in's tensile strength at the
    // calibrated material, seed mean; cost: particle-steps/s x wall s/run = particles x steps
    // of a stand-in run (1000 x 1).
    const cal::CalibratedPoint cp = cal::load_calibrated_point(summary);
    const exp::MaterialParams m = cal::ParameterSpace(cp.problem.parameters, cp.problem.base.material).material(cp.values);
    const auto tension = cal::make_analytic_model(kSands.size(), 0.003, 0.0);
    nlohmann::json sj;
    std::ifstream(summary) >> sj;
    for (std::size_t s = 0; s < kSands.size(); ++s) {
        INFO(kSands[s]);
        const auto& row = model["sands"][s];
        const double sigma_t = 0.5 * (tension->run({s, 1, m, cal::CubeTest::tension}, 0.0).peak_pa +
                                      tension->run({s, 2, m, cal::CubeTest::tension}, 0.0).peak_pa);
        double sigma_c = 0.0;
        for (const auto& t : sj["targets"])
            if (t["sand"] == kSands[s] && t["quantity"] == "peak_stress") sigma_c = t["sim_mean"].get<double>() * 1e6;
        REQUIRE(sigma_c > 0.0);
        CHECK(row["tensile_strength_mpa"]["n"] == 2);
        CHECK(row["tensile_strength_mpa"]["mean"].get<double>() == Approx(sigma_t * 1e-6).epsilon(1e-12));
        CHECK(row["compressive_to_tensile_ratio"].get<double>() == Approx(sigma_c / sigma_t).epsilon(1e-12));
        const auto& cost = row["cost"];
        CHECK(cost["runs"].get<int>() > 0);
        REQUIRE(cost["wall_seconds_per_run"].is_number());
        REQUIRE(cost["particle_steps_per_second"].is_number());
        CHECK(cost["wall_seconds_per_run"].get<double>() > 0.0);
        CHECK(cost["particle_steps_per_second"].get<double>() * cost["wall_seconds_per_run"].get<double>() == Approx(1000.0));
        CHECK(row["targets_met"].get<int>() >= 0);
        CHECK(row["validation"]["modulus_error"].is_null());  // the calibration has no [validation]
    }
    // The table and the written files carry the new columns.
    const auto& header = r.tables.front().header;
    CHECK(std::find(header.begin(), header.end(), "sigma_c/sigma_t") != header.end());
    CHECK(std::find(header.begin(), header.end(), "particle-steps/s") != header.end());
    report::write_study_outputs(r);
    nlohmann::json written;
    std::ifstream(dir.path / "study-out" / "study.json") >> written;
    CHECK(written["data"]["models"][0]["sands"][1]["compressive_to_tensile_ratio"].is_number());

    // Resumed: the tension tests come from the study's ledger, with the same answer.
    const cal::StudyResult again = cal::run_study(cal::load_study_config(toml));
    CHECK(again.runs_executed == 0);
    CHECK(again.runs_from_ledger == 4);
    CHECK(again.data["models"][0]["sands"][0]["compressive_to_tensile_ratio"] == model["sands"][0]["compressive_to_tensile_ratio"]);
}

TEST_CASE("study: model_form runs each sand's tension tests on the calibration's own seeds of that sand, "
          "its validation errors apart",
          "[calibrate][study][seeds]") {
    TempDir dir("study-model-form-sand-seeds");
    const fs::path summary = calibrated_summary(dir.path, "sand_seeds = { \"Van Buren\" = [1, 2, 3, 5] }\n");
    // Rows of validation specimens, as a calibration with [validation] writes them after the
    // fitted ones: reported apart, never mixed into the fitted errors or σc.
    nlohmann::json sj;
    std::ifstream(summary) >> sj;
    const nlohmann::json fitted = sj["targets"];
    for (nlohmann::json row : fitted) {
        row["role"] = "validation";
        row["rel_error"] = 0.5;
        row["sim_mean"] = 3.0 * row["sim_mean"].get<double>();
        sj["targets"].push_back(row);
    }
    test::write_text(summary, sj.dump(1));
    const fs::path toml = write_study(dir.path, "kind = \"model_form\"\ncalibrations = [\"" + summary.string() + "\"]");
    const cal::StudyResult r = cal::run_study(cal::load_study_config(toml));
    CHECK(r.runs_executed == 2 + 4);
    REQUIRE(r.cases.size() == 1);
    REQUIRE(r.cases[0].runs.size() == 2);
    CHECK(r.cases[0].runs[0].size() == 2);
    CHECK(r.cases[0].runs[1].size() == 4);

    // Oracle: each sand's σt is the stand-in's mean over that sand's own seeds, as the
    // calibration's simulated peak (σc) is: σc/σt compares the same specimens.
    const cal::CalibratedPoint cp = cal::load_calibrated_point(summary);
    const exp::MaterialParams m = cal::ParameterSpace(cp.problem.parameters, cp.problem.base.material).material(cp.values);
    const auto tension = cal::make_analytic_model(kSands.size(), 0.003, 0.0);
    const std::vector<std::vector<std::uint64_t>> seeds = {{1, 2}, {1, 2, 3, 5}};
    for (std::size_t s = 0; s < kSands.size(); ++s) {
        INFO(kSands[s]);
        double sum = 0.0;
        for (std::uint64_t seed : seeds[s]) sum += tension->run({s, seed, m, cal::CubeTest::tension}, 0.0).peak_pa;
        const auto& row = r.data["models"][0]["sands"][s];
        const double sigma_t = sum / static_cast<double>(seeds[s].size());
        CHECK(row["tensile_strength_mpa"]["n"] == static_cast<int>(seeds[s].size()));
        CHECK(row["tensile_strength_mpa"]["mean"].get<double>() == Approx(sigma_t * 1e-6).epsilon(1e-12));
        for (const auto& t : fitted) {
            if (t["sand"] != kSands[s]) continue;
            if (t["quantity"] == "modulus") CHECK(row["modulus_error"] == t["rel_error"]);
            if (t["quantity"] == "peak_stress")
                CHECK(row["compressive_to_tensile_ratio"].get<double>() ==
                      Approx(t["sim_mean"].get<double>() * 1e6 / sigma_t).epsilon(1e-12));
        }
        CHECK(row["validation"]["modulus_error"] == 0.5);
        CHECK(row["validation"]["strain_error"] == 0.5);
    }
}

TEST_CASE("study: sigma_c/sigma_t and cost per cube test from known inputs", "[calibrate][study]") {
    CHECK(cal::compressive_to_tensile_ratio(24e6, {3e6, 0.2e6, 2}) == Approx(8.0).epsilon(1e-15));
    CHECK(std::isnan(cal::compressive_to_tensile_ratio(24e6, {0.0, 0.0, 0})));  // no successful tension run
    CHECK(std::isnan(cal::compressive_to_tensile_ratio(std::nan(""), {3e6, 0.2e6, 2})));
    const std::vector<cal::RunCost> runs = {{"a", 100, 10, 2.0}, {"a", 200, 10, 3.0}, {"b", 50, 4, 1.0}, {"a", 100, 10, 0.0}};
    const cal::RunCostSummary a = cal::summarise_costs(runs, "a");  // the run without a wall time is left out
    CHECK(a.runs == 2);
    CHECK(a.mean_wall_seconds == Approx(2.5));
    CHECK(a.particle_steps_per_second == Approx((100.0 * 10 + 200.0 * 10) / 5.0));
    CHECK(cal::summarise_costs(runs, "b").particle_steps_per_second == Approx(200.0));
    CHECK(std::isnan(cal::summarise_costs(runs, "c").mean_wall_seconds));
}

TEST_CASE("study: bad study files are refused naming the file, key and rule", "[calibrate][study][errors]") {
    TempDir dir("study-errors");
    const fs::path summary = calibrated_summary(dir.path);
    const std::string cal_key = "calibration = \"" + summary.string() + "\"\n";
    CHECK_THAT(error_of(write_study(dir.path, "kind = \"gradation_effect\"\ncalibration = \"nope/summary.json\"")),
               Catch::Contains("study.toml:3: key 'study.calibration'") && Catch::Contains("not found"));
    CHECK_THAT(error_of(write_study(dir.path, "kind = \"resolution\"\n" + cal_key + "edges_mm = []")),
               Catch::Contains("study.toml:4: key 'study.edges_mm'"));
    CHECK_THAT(error_of(write_study(dir.path, "kind = \"resolution\"\n" + cal_key + "edges_mm = [2.5]")),
               Catch::Contains("needs at least two cube edges"));
    CHECK_THAT(error_of(write_study(dir.path, "kind = \"resolution\"\n" + cal_key + "edges_mm = [1.0, 2.5]")),
               Catch::Contains("study.edges_mm value 1 mm") && Catch::Contains("3 x the largest grain"));
    CHECK_THAT(error_of(write_study(dir.path, "kind = \"sideways\"\n" + cal_key)), Catch::Contains("key 'study.kind' = \"sideways\""));
    CHECK_THAT(error_of(write_study(dir.path, "kind = \"resolution\"\n" + cal_key + "edges_mm = [2.5, 3.0]\nmin_diameters_mm = [0.1, 0.2]")),
               Catch::Contains("belongs to kind \"fines_truncation\""));
    CHECK_THAT(error_of(write_study(dir.path, "kind = \"resolution\"\n" + cal_key + "edges_mm = [2.5, 3.0]\ntolerance = 1.5")),
               Catch::Contains("key 'study.tolerance' must be a relative change in [0, 1)"));
    CHECK_THAT(error_of(write_study(dir.path, "kind = \"gradation_effect\"\n" + cal_key + "tolerance = 0.02")),
               Catch::Contains("key 'study.tolerance' belongs to kind \"resolution\""));
    // A summary of another dataset: its lab results are not those of its config any more.
    nlohmann::json j;
    std::ifstream(summary) >> j;
    j["lab_results"] = "/elsewhere/lab_results.json";
    test::write_text(dir.path / "other.json", j.dump());
    CHECK_THAT(error_of(write_study(dir.path, "kind = \"gradation_effect\"\ncalibration = \"" + (dir.path / "other.json").string() + "\"")),
               Catch::Contains("other.json") && Catch::Contains("belongs to another dataset"));
    CHECK_FALSE(fs::exists(dir.path / "study-out" / "study.json"));
}

namespace {

// A resolution case whose one sand has the given moduli per seed [Pa] (peak and strain: 1).
cal::StudyCase edge_case(double edge_mm, const std::vector<double>& moduli) {
    cal::StudyCase c;
    c.label = "edge " + std::to_string(edge_mm);
    c.x = edge_mm;
    c.sands = {"pre-blended"};
    c.runs.resize(1);
    for (double e : moduli) {
        cal::RunOutcome r;
        r.status = cal::OutcomeStatus::ok;
        r.modulus_pa = e, r.peak_pa = 1.0, r.strain_at_peak = 1.0;
        c.runs[0].push_back(r);
        c.seeds.push_back(c.seeds.size() + 1);
    }
    return c;
}

nlohmann::json modulus_convergence(double tolerance) {
    cal::StudyResult result;
    result.config.kind = cal::StudyKind::resolution;
    result.config.tolerance = tolerance;
    // Means 100, 110, 113, 114.5 with a seed std of 1 (the last steps: 2.7 %, 1.3 %).
    result.cases = {edge_case(2.5, {99, 100, 101}), edge_case(3.5, {109, 110, 111}), edge_case(5.0, {112, 113, 114}),
                    edge_case(6.0, {113.5, 114.5, 115.5})};
    cal::summarise_convergence(result);
    for (const auto& row : result.data["convergence"])
        if (row["quantity"] == "modulus") return row;
    FAIL("no modulus row");
    return {};
}

}  // namespace

TEST_CASE("resolution: converged where later changes stay under the seed spread, or under study.tolerance",
          "[calibrate][study]") {
    // Every step (10, 3, 1.5) exceeds the seed std (1): not converged within the sweep.
    const nlohmann::json strict = modulus_convergence(0.0);
    CHECK_FALSE(strict["converged"].get<bool>());
    CHECK(strict["last_relative_change"].get<double>() == Approx(1.5 / 114.5));
    CHECK(strict["relative_seed_std"].get<double>() == Approx(1.0 / 114.5));
    // 2 %: the last step (1.3 %) is under it, the one before (2.7 %) is not -> from 5 mm on.
    const nlohmann::json two_percent = modulus_convergence(0.02);
    CHECK(two_percent["converged"].get<bool>());
    CHECK(two_percent["from_x"].get<double>() == 5.0);
    // 3 %: both last steps are under it -> from 3.5 mm on.
    CHECK(modulus_convergence(0.03)["from_x"].get<double>() == 3.5);
}
