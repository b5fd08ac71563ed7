// The direct-tension target of a calibration ([targets] tension): a twin experiment on the
// analytic stand-in in which only the tension target pins the cohesion ratio down, the assumed
// σc/σt with its band, the homogeneity of σt (× β), the run requests' test on the wire, and
// the config's errors.
#include <catch2/catch.hpp>
#include <cmath>
#include <fstream>
#include <tuple>

#include "calibrate/objective.hpp"
#include "calibrate/plan.hpp"
#include "calibrate/problem.hpp"
#include "calibrate/execution/run_message.hpp"
#include "calibrate_fixture.hpp"
#include "common/input_error.hpp"
#include "experiments/config/cube_config.hpp"
#include "lab_data/lab_stats.hpp"
#include "reports/lab_report.hpp"
#include "reports/calibration_report.hpp"

namespace fs = std::filesystem;
using namespace gradem;
using gradem::test::TempDir;

namespace {

const std::vector<std::string> kOneSand = {"pre-blended"};
constexpr double kTruthModulus = 20.0, kTruthStrength = 12.0, kTruthRatio = 1.6, kCv = 0.25;  // GPa, MPa, -, -

exp::MaterialParams truth_material() { return test::material_at({kTruthModulus, kTruthStrength, kTruthRatio, kCv}); }

/// One sand, E* σ̄c and c̄/σ̄c free, the strength cv fixed at the truth, no strain target: the
/// compression test alone gives E and σc, two numbers for three parameters (σc = σ̄c p ρ^q
/// trades σ̄c against ρ); σt = σ̄c t (1 − r v) separates them.
fs::path one_sand_problem(const fs::path& dir, const cal::CubeModel& model, const std::string& tension_keys,
                          const std::string& method = "scaling") {
    std::vector<std::uint64_t> seeds;
    for (std::uint64_t s = 101; s <= 108; ++s) seeds.push_back(s);
    test::write_text(dir / "lab_results.json", test::synthetic_lab_results(model, kOneSand, truth_material(), seeds, true).dump(1));
    return test::write_problem(dir, "sands = [\"pre-blended\"]\nseeds = [1, 2]\n",
                               "strain_weight = 0.0\n" + tension_keys +
                                   "\n[parameters.strength_cv]\nfree = false\nstart = 0.25\n"
                                   "[solver]\nmethod = \"" + method + "\"\nmax_runs = 400\ntolerance = 0.002\n[output]\ndir = \"out\"\n");
}

double value_of(const cal::CalibrationProblem& p, const cal::CalibrationResult& r, const std::string& name) {
    const cal::ParameterSpace space(p.parameters, p.base.material);
    return r.stages.at(0).solution.best.at(*space.index_of(name));
}

}  // namespace

TEST_CASE("a tension target from the lab pins down what compression alone cannot: known σt and c̄/σ̄c recovered",
          "[calibrate][tension]") {
    TempDir dir("cal-tension-lab");
    auto model = cal::make_analytic_model(1, 0.001);
    const cal::CalibrationProblem problem = cal::load_calibration_problem(one_sand_problem(dir.path, *model, "tension = \"lab\"\n"));
    REQUIRE(problem.tension.source == cal::TensionSource::lab);
    REQUIRE(problem.fitted_quantities().size() == 4);
    const cal::CalibrationResult r = cal::run_calibration(problem, *model);
    INFO("runs " << r.runs_used << "; E* " << value_of(problem, r, "effective_modulus_gpa") << ", sigma_c "
                 << value_of(problem, r, "tensile_strength_mpa") << ", ratio " << value_of(problem, r, "cohesion_ratio"));
    CHECK(value_of(problem, r, "effective_modulus_gpa") == Approx(kTruthModulus).epsilon(0.01));
    CHECK(value_of(problem, r, "tensile_strength_mpa") == Approx(kTruthStrength).epsilon(0.01));
    CHECK(value_of(problem, r, "cohesion_ratio") == Approx(kTruthRatio).epsilon(0.02));
    // Every evaluation ran both tests: one tension run per compression run, each in the budget.
    for (const cal::Evaluation& e : r.history) CHECK(e.tension_runs.size() == e.runs.size());
    const nlohmann::json summary = report::summary_json(problem, r);
    CHECK(summary["tension_target"]["source"] == "lab");
    int tension_rows = 0;
    for (const auto& row : summary["targets"])
        if (row["quantity"] == "tensile_strength") {
            ++tension_rows;
            CHECK(std::fabs(row["rel_error"].get<double>()) < 0.01);
            CHECK(row["met"] == true);
            CHECK(row["assumed"] == false);
        }
    CHECK(tension_rows == 1);
    // Resumed: every run, compression and tension, is served from the ledger.
    const cal::CalibrationResult again = cal::run_calibration(problem, *model);
    CHECK(again.runs_executed == 0);
    CHECK(again.runs_from_ledger == r.runs_used);
}

TEST_CASE("an assumed σc/σt: the target is σc,lab / ratio, met when the simulated ratio is in the band, shown as assumed",
          "[calibrate][tension]") {
    TempDir dir("cal-tension-assumed");
    auto model = cal::make_analytic_model(1, 0.001);
    // The stand-in's own ratio at the truth (seed means): the assumed ratio that the truth meets exactly.
    const exp::MaterialParams truth = truth_material();
    double sc = 0.0, st = 0.0;
    for (std::uint64_t seed : {101, 102, 103, 104, 105, 106, 107, 108}) {
        sc += model->run({0, seed, truth}, 0.0).peak_pa;
        st += model->run({0, seed, truth, cal::CubeTest::tension}, 0.0).peak_pa;
    }
    const double ratio = sc / st;
    const std::string keys = "tension = \"assumed_ratio\"\ntension_ratio = " + std::to_string(ratio) +
                             "\ntension_ratio_low = " + std::to_string(0.9 * ratio) + "\ntension_ratio_high = " +
                             std::to_string(1.1 * ratio) + "\ntension_basis = \"the stand-in's own ratio (test)\"\n";
    const cal::CalibrationProblem problem = cal::load_calibration_problem(one_sand_problem(dir.path, *model, keys));
    // The target is the lab's peak over the ratio, with no lab scatter of its own.
    REQUIRE(problem.tension.ratio == Approx(ratio).epsilon(1e-5));  // as written in the file
    CHECK(problem.targets[0].tension.mean == Approx(problem.targets[0].peak.mean / problem.tension.ratio).epsilon(1e-12));
    CHECK(problem.targets[0].tension.n == 0);
    const cal::CalibrationResult r = cal::run_calibration(problem, *model);
    CHECK(value_of(problem, r, "cohesion_ratio") == Approx(kTruthRatio).epsilon(0.03));
    const nlohmann::json summary = report::summary_json(problem, r);
    CHECK(summary["tension_target"]["assumed"] == true);
    CHECK(summary["tension_target"]["basis"] == "the stand-in's own ratio (test)");
    for (const auto& row : summary["targets"])
        if (row["quantity"] == "tensile_strength") {
            CHECK(row["assumed"] == true);
            CHECK(row["compressive_to_tensile_ratio"].get<double>() == Approx(ratio).epsilon(0.02));
            CHECK(row["met"] == true);
        }
    const std::string md = report::summary_markdown(problem, r);
    CHECK_THAT(md, Catch::Contains("ASSUMED σc/σt") && Catch::Contains("the stand-in's own ratio (test)"));
    CHECK_THAT(report::brief_report(problem, r), Catch::Contains("sigc/sigt"));
}

TEST_CASE("a tension target reported only (weight 0): the path runs compression alone, the tension tests run once at its result",
          "[calibrate][tension]") {
    // Oracle: σt cannot move a fit it has no weight in, so the path and its result are those of the
    // same problem without a tension target; the result's σt is the stand-in's own at that point.
    auto model = cal::make_analytic_model(1, 0.001);
    TempDir without("cal-tension-none"), reported("cal-tension-reported");
    const cal::CalibrationProblem plain = cal::load_calibration_problem(one_sand_problem(without.path, *model, ""));
    const cal::CalibrationProblem problem =
        cal::load_calibration_problem(one_sand_problem(reported.path, *model, "tension = \"lab\"\ntension_weight = 0.0\n"));
    REQUIRE(problem.tension_at_result_only());
    const cal::CalibrationResult a = cal::run_calibration(plain, *model);
    const cal::CalibrationResult r = cal::run_calibration(problem, *model);

    const cal::SolveResult& best = r.stages.at(0).solution;
    CHECK(best.best == a.stages.at(0).solution.best);
    CHECK(best.best_objective == a.stages.at(0).solution.best_objective);
    REQUIRE(r.history.size() == a.history.size() + 1);
    for (std::size_t k = 0; k < a.history.size(); ++k) CHECK(r.history[k].tension_runs.empty());
    const cal::Evaluation& last = r.history.back();
    CHECK(last.label == "tension at the result");
    CHECK(last.values == best.best);
    REQUIRE(last.tension_runs.size() == problem.seeds.size());
    CHECK(r.runs_used == a.runs_used + static_cast<int>(problem.seeds.size()));  // the compression runs came from the ledger
    const cal::ParameterSpace space(problem.parameters, problem.base.material);
    double st = 0.0;
    for (std::uint64_t seed : problem.seeds) st += model->run({0, seed, space.material(best.best), cal::CubeTest::tension}, 0.0).peak_pa;
    CHECK(best.best_eval.sands.at(0).value(cal::Quantity::tension) == Approx(st / static_cast<double>(problem.seeds.size())).epsilon(1e-12));
    CHECK(r.stages.at(0).noise_floor[static_cast<int>(cal::Quantity::tension)] > 0.0);
}

TEST_CASE("a tension target reported only: the uncertainty's difference points run compression alone",
          "[calibrate][tension]") {
    // Oracle: σt of weight 0 is no residual of the linearisation, so the difference points (a
    // solver without the scaling path's closed form: one new point per free parameter) and the
    // standard errors are those of the same problem without a tension target; the only tension
    // tests of the job are the result's.
    auto model = cal::make_analytic_model(1, 0.001);
    TempDir without("cal-tension-fd-none"), reported("cal-tension-fd-reported");
    const cal::CalibrationProblem plain = cal::load_calibration_problem(one_sand_problem(without.path, *model, "", "bobyqa"));
    const cal::CalibrationProblem problem = cal::load_calibration_problem(
        one_sand_problem(reported.path, *model, "tension = \"lab\"\ntension_weight = 0.0\n", "bobyqa"));
    REQUIRE(problem.tension_at_result_only());
    const cal::CalibrationResult a = cal::run_calibration(plain, *model);
    const cal::CalibrationResult r = cal::run_calibration(problem, *model);

    const cal::Uncertainty& u = r.stages.at(0).uncertainty, &ua = a.stages.at(0).uncertainty;
    REQUIRE(ua.computed);
    REQUIRE(ua.fd_runs == 3 * static_cast<int>(plain.seeds.size()));  // E*, σ̄c, c̄/σ̄c: one point each
    REQUIRE(u.computed);
    CHECK(u.fd_runs == ua.fd_runs);
    CHECK(u.std_error_natural == ua.std_error_natural);
    std::size_t tension_runs = 0;
    for (const cal::Evaluation& e : r.history) {
        if (e.label == "uncertainty") CHECK(e.tension_runs.empty());
        tension_runs += e.tension_runs.size();
    }
    CHECK(tension_runs == problem.seeds.size());
    CHECK(r.runs_used == a.runs_used + static_cast<int>(problem.seeds.size()));
}

namespace {

const std::vector<std::string> kTwoSands = {"pre-blended", "Van Buren"};

/// Two sands, Van Buren with more seeds of its own, an assumed σc/σt of weight `weight`, the
/// scales free (the shape fixed at the truth, as in the main job); the extra [calibration] keys
/// (tension_seeds) in `calibration_keys`.
fs::path two_sand_problem(const fs::path& dir, const cal::CubeModel& model, const std::string& calibration_keys,
                          double weight, const std::string& tension = "assumed_ratio") {
    test::write_text(dir / "lab_results.json",
                     test::synthetic_lab_results(model, kTwoSands, truth_material(), {101, 102, 103, 104}).dump(1));
    return test::write_problem(dir, "seeds = [1, 2, 3]\nsand_seeds = { \"Van Buren\" = [1, 2, 3, 4, 5] }\n" + calibration_keys,
                               "strain_weight = 0.0\ntension = \"" + tension +
                                   "\"\ntension_ratio = 10.0\ntension_basis = \"test\"\n" +
                                   "tension_weight = " + std::to_string(weight) +
                                   "\n[parameters.strength_cv]\nfree = false\nstart = 0.25\n"
                                   "[parameters.cohesion_ratio]\nfree = false\nstart = 1.6\n"
                                   "[solver]\nmethod = \"scaling\"\nmax_runs = 400\ntolerance = 0.002\n[output]\ndir = \"out\"\n");
}

}  // namespace

// σt scatters a few per cent between cubes and its band is ±20 %, so [calibration]
// tension_seeds runs the direct-tension test on some fitted seeds only (each a seed of every
// sand). Oracle: with the tension reported only, the path and the result are those of the same
// problem with tension on every seed; σt is the stand-in's own on the tension seeds alone.
TEST_CASE("fitted tension seeds: the direct-tension tests run on those seeds of every sand alone", "[calibrate][tension]") {
    auto model = cal::make_analytic_model(2, 0.001);
    TempDir every_dir("cal-tension-seeds-every"), some_dir("cal-tension-seeds-some"), fitted_dir("cal-tension-seeds-fitted");
    const cal::CalibrationProblem every = cal::load_calibration_problem(two_sand_problem(every_dir.path, *model, "", 0.0));
    const cal::CalibrationProblem some =
        cal::load_calibration_problem(two_sand_problem(some_dir.path, *model, "tension_seeds = [2]\n", 0.0));
    REQUIRE(some.tension_seeds == std::vector<std::uint64_t>{2});
    CHECK(some.tension_runs_per_test({0, 1}) == 2);
    CHECK(every.tension_runs_per_test({0, 1}) == 8);
    const cal::CalibrationResult r_every = cal::run_calibration(every, *model);
    const cal::CalibrationResult r_some = cal::run_calibration(some, *model);

    const cal::SolveResult& best = r_some.stages.at(0).solution;
    CHECK(best.best == r_every.stages.at(0).solution.best);
    REQUIRE(r_some.history.back().label == "tension at the result");
    CHECK(r_some.history.back().tension_runs.size() == 2);
    CHECK(r_every.history.back().tension_runs.size() == 8);
    CHECK(r_some.runs_used == r_every.runs_used - 6);
    CHECK(cal::expected_runs(some).fitted == r_some.runs_used);
    const cal::ParameterSpace space(some.parameters, some.base.material);
    for (std::size_t s = 0; s < kTwoSands.size(); ++s) {
        const cal::SandOutcome& o = best.best_eval.sands.at(s);
        CHECK(o.tension_ok == 1);
        CHECK(o.value(cal::Quantity::tension) == model->run({s, 2, space.material(best.best), cal::CubeTest::tension}, 0.0).peak_pa);
        CHECK(o.value(cal::Quantity::modulus) == r_every.stages.at(0).solution.best_eval.sands.at(s).value(cal::Quantity::modulus));
    }
    const nlohmann::json summary = report::summary_json(some, r_some);
    CHECK(summary["tension_seeds_by_sand"]["Van Buren"] == nlohmann::json::array({2}));
    CHECK(report::summary_json(every, r_every)["tension_seeds_by_sand"]["Van Buren"] == nlohmann::json::array({1, 2, 3, 4, 5}));
    CHECK_THAT(report::summary_markdown(some, r_some), Catch::Contains("direct tension on seed 2 of each sand"));
    CHECK_THAT(report::summary_markdown(every, r_every), !Catch::Contains("direct tension on seed"));

    // A fitted tension target (weight 1): every evaluation runs the tension tests of those seeds alone.
    const cal::CalibrationProblem fitted =
        cal::load_calibration_problem(two_sand_problem(fitted_dir.path, *model, "tension_seeds = [1, 3]\n", 1.0));
    const cal::CalibrationResult r_fitted = cal::run_calibration(fitted, *model);
    for (const cal::Evaluation& e : r_fitted.history) {
        INFO(e.label);
        CHECK(e.runs.size() == 8);
        CHECK(e.tension_runs.size() == 4);
    }
}

TEST_CASE("bad fitted tension seeds are refused naming the key, line and rule", "[calibrate][tension]") {
    TempDir dir("cal-tension-seeds-bad");
    auto model = cal::make_analytic_model(2, 0.001);
    CHECK_THROWS_WITH(cal::load_calibration_problem(two_sand_problem(dir.path, *model, "tension_seeds = [4]\n", 0.0)),
                      Catch::Contains("problem.toml:5:") &&
                          Catch::Contains("'calibration.tension_seeds': seed 4 is not a seed of pre-blended (calibration.seeds)"));
    CHECK_THROWS_WITH(cal::load_calibration_problem(two_sand_problem(dir.path, *model, "tension_seeds = [1]\n", 0.0, "none")),
                      Catch::Contains("problem.toml:5:") &&
                          Catch::Contains("'calibration.tension_seeds' needs a direct-tension target"));
}

TEST_CASE("σt is homogeneous with the strengths: rescaling multiplies it by β, and its row pulls β as far as its weight says", "[calibrate][tension]") {
    cal::CalibrationProblem p;
    p.tension.source = cal::TensionSource::lab;
    p.targets = {{"a", {10e9, 1e9, 3}, {20e6, 1e6, 3}, {0.003, 1e-4, 3}, {2e6, 1e5, 3}}};
    p.weights = {1.0, 0.0, 0.0, 1.0};  // β is seen through σt alone
    cal::Evaluation e;
    cal::SandOutcome o;
    o.ok = o.tension_ok = 2;
    o.mean[0] = 10e9 / 1.7;
    o.mean[1] = 20e6;             // ignored (zero weight)
    o.mean[2] = 0.003;            // ignored
    o.mean[3] = 2e6 / 0.8;        // σt: strengths × 0.8 would fit it
    e.sands.push_back(o);
    e.tension_runs.push_back({});
    e.tension_runs.back().peak_pa = 2.5e6;
    const cal::Scales sc = cal::best_scales(e, p, true, true);
    CHECK(sc.alpha == Approx(1.7).epsilon(1e-12));
    CHECK(sc.beta == Approx(0.8).epsilon(1e-12));
    const cal::Evaluation scaled = cal::rescaled(e, sc.alpha, sc.beta);
    CHECK(scaled.sands[0].value(cal::Quantity::tension) == Approx(2e6).epsilon(1e-12));
    CHECK(scaled.tension_runs[0].peak_pa == Approx(2.5e6 * 0.8).epsilon(1e-12));
    CHECK(cal::objective(scaled, p) < 1e-24);
    // With the peak weighted too, σt pulls β between the peak's 1 and its own 0.8 ...
    p.weights = {1.0, 1.0, 0.0, 1.0};
    CHECK(cal::best_scales(e, p, true, true).beta == Approx(std::sqrt(0.8)).epsilon(1e-12));
    // ... and with a tension weight of 0 it does not pull at all: the peak sets β.
    p.weights = {1.0, 1.0, 0.0, 0.0};
    CHECK(cal::best_scales(e, p, true, true).beta == Approx(1.0).epsilon(1e-12));
    CHECK(cal::objective(cal::rescaled(e, 1.7, 1.0), p) < 1e-24);
    // Without the tension target the same outcome says nothing about β.
    p.weights = {1.0, 0.0, 0.0, 1.0};
    p.tension.source = cal::TensionSource::none;
    CHECK(cal::best_scales(e, p, true, true).beta == 1.0);
}

TEST_CASE("a run request's test travels on the wire", "[calibrate][tension]") {
    cal::wire::Run m;
    m.job = 7;
    m.request = {1, 3, truth_material(), cal::CubeTest::tension};
    const cal::wire::Run back = cal::wire::decode_run(cal::wire::encode(m));
    CHECK(back.request.test == cal::CubeTest::tension);
    m.request.test = cal::CubeTest::compression;
    CHECK(cal::wire::decode_run(cal::wire::encode(m)).request.test == cal::CubeTest::compression);
}

TEST_CASE("bad tension targets are refused naming the key, line and rule", "[calibrate][tension]") {
    TempDir dir("cal-tension-bad");
    auto model = cal::make_analytic_model(1, 0.001);
    auto refused = [&](const std::string& keys, const std::string& what) {
        INFO(keys);
        CHECK_THROWS_WITH(cal::load_calibration_problem(one_sand_problem(dir.path, *model, keys)),
                          Catch::Contains("problem.toml:") && Catch::Contains(what));
    };
    refused("tension = \"splitting\"\n", "key 'targets.tension' = \"splitting\": expected \"none\", \"lab\" or \"assumed_ratio\"");
    refused("tension = \"assumed_ratio\"\ntension_ratio = 0.5\ntension_basis = \"x\"\n", "'targets.tension_ratio' = 0.5 violates > 1");
    refused("tension = \"assumed_ratio\"\ntension_ratio_low = 11.0\ntension_basis = \"x\"\n", "violate 1 < low <= ratio <= high");
    refused("tension = \"assumed_ratio\"\ntension_ratio_high = 9.0\ntension_basis = \"x\"\n", "tension_ratio_high");
    refused("tension = \"lab\"\ntension_tolerance = 1.5\n", "'targets.tension_tolerance' = 1.5 violates in (0, 1)");
    refused("tension = \"assumed_ratio\"\n", "'targets.tension_basis' is required");
    refused("tension = \"lab\"\ntension_weight = -1.0\n", "'targets.tension_weight' must be >= 0");
    // A lab source with lab results that hold no tensile tests.
    test::write_problem(dir.path, "sands = [\"pre-blended\"]\n", "tension = \"lab\"\n[output]\ndir = \"out\"\n", "no_tensile.toml");
    test::write_text(dir.path / "lab_results.json",
                     test::synthetic_lab_results(*model, kOneSand, truth_material(), {1, 2}, false).dump(1));
    CHECK_THROWS_WITH(cal::load_calibration_problem(dir.path / "no_tensile.toml"),
                      Catch::Contains("no_tensile.toml:") && Catch::Contains("has no tensile_strength_mpa") &&
                          Catch::Contains("assumed_ratio"));
}

TEST_CASE("from lab files to the tension target: splitting and flexural exports become the calibration's σt", "[calibrate][tension]") {
    // The study's cubes and sieve analyses with the GENERATED tensile fixtures of tests/lab_data,
    // as one dataset: `gradem lab` reduces them, the calibration reads their direct equivalent.
    TempDir dir("cal-tension-from-files");
    const fs::path study = fs::path(GRADEM_SOURCE_DIR) / "lab_data" / "datasets" / "study";
    const fs::path tension = fs::path(GRADEM_SOURCE_DIR) / "tests" / "lab_data" / "fixtures" / "tension";
    std::string toml = "[dataset]\nname = \"cubes and tensile fixtures\"\nrepresentative = true\n";
    for (const auto& [sand, sieve, cubes, letter] :
         {std::tuple<std::string, std::string, std::string, std::string>{"pre-blended", "sieve_pre_blended.csv", "PB1", "A"},
          {"Van Buren", "sieve_van_buren.csv", "VB1", "B"}}) {
        toml += "[[sand]]\nname = \"" + sand + "\"\nsieve = \"" + (study / sieve).string() + "\"\n";
        toml += "  [[sand.batch]]\n  name = \"" + cubes + "\"\n  files = \"" + (study / "cubes" / (cubes + "-*.csv")).string() + "\"\n";
        toml += "  [[sand.tension]]\n  name = \"" + letter + "F\"\n  test = \"flexural\"\n  files = \"" +
                (tension / (letter + "-F*.csv")).string() + "\"\n";
    }
    test::write_text(dir.path / "dataset.toml", toml);
    const lab::LabStats stats = lab::analyse_lab_dataset(dir.path / "dataset.toml");
    test::write_text(dir.path / "lab_results.json", report::lab_stats_to_json(stats).dump(1));
    const cal::CalibrationProblem problem = cal::load_calibration_problem(
        test::write_problem(dir.path, "model = \"analytic\"\n", "tension = \"lab\"\n[output]\ndir = \"out\"\n"));
    REQUIRE(problem.targets.size() == 2);
    for (std::size_t s = 0; s < 2; ++s) {
        const lab::SandResult& sand = stats.sands.at(s);
        INFO(sand.name);
        REQUIRE(sand.tensile_stats.direct_pa.n > 0);
        CHECK(problem.targets[s].tension.n == static_cast<int>(sand.tensile_stats.direct_pa.n));
        CHECK(problem.targets[s].tension.mean == Approx(sand.tensile_stats.direct_pa.mean).epsilon(1e-9));
        CHECK(problem.targets[s].tension.mean > 0.5e6);
        CHECK(problem.targets[s].tension.mean < problem.targets[s].peak.mean);
    }
}
