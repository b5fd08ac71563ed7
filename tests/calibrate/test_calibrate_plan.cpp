// The cost before the run (calibrate/plan.hpp): the expected runs are the solver's own path on
// the analytic stand-in, and a DEM plan's specimens, time step and steps are those of the runs
// it plans; a study's plan prices the cases its kind asks for; planning writes nothing.
#include <catch2/catch.hpp>

#include "calibrate/parameters.hpp"
#include "calibrate/plan.hpp"
#include "calibrate/study/study_config.hpp"
#include "calibrate/study/study_plan.hpp"
#include "calibrate_fixture.hpp"
#include "experiments/virtual_tests/cube_specimen.hpp"
#include "experiments/virtual_tests/cube_test.hpp"
#include "experiments/specimen/grain_sampler.hpp"
#include "experiments/specimen/packing_cache.hpp"

namespace fs = std::filesystem;
using namespace gradem;
using gradem::test::TempDir;

namespace {

const std::vector<std::string> kSands = {"pre-blended", "Van Buren"};

/// A ~200-grain cube of the study's dataset (grains 0.4-1.0 mm in a 3 mm cube), loaded fast
/// (20 /s: ~10 000 steps; quasi-static or not does not matter to what is planned): genesis and a
/// cube test take a few seconds each.
fs::path write_tiny_base(const fs::path& dir, const std::string& material = "") {
    const std::string study = (fs::path(GRADEM_SOURCE_DIR) / "lab_data" / "datasets" / "study").string();
    test::write_text(dir / "base.toml", "[specimen]\ndataset = \"" + study +
                                            "\"\nsand = \"Van Buren\"\n[size_rule]\nmin_diameter_mm = 0.4\n"
                                            "max_diameter_mm = 1.0\n[genesis]\nedge_mm = 3.0\ntarget_solid_fraction = 0.55\n"
                                            "[test]\nstrain_rate_per_s = 20.0\n[output]\ncache_dir = \"cache\"\n" + material);
    return dir / "base.toml";
}

/// lab_results.json of both sands from the analytic stand-in at a known material.
void write_analytic_lab(const fs::path& dir) {
    auto truth_model = cal::make_analytic_model(2, 0.001);
    test::write_text(dir / "lab_results.json",
                     test::synthetic_lab_results(*truth_model, kSands, test::material_at({20.0, 12.0, 1.6, 0.25}), {101, 102, 103})
                         .dump(1));
}

}  // namespace

TEST_CASE("plan: the expected runs are the calibration's own on the analytic stand-in, and nothing is written", "[calibrate][plan]") {
    TempDir dir("cal-plan-analytic");
    write_analytic_lab(dir.path);
    const fs::path toml = test::write_problem(dir.path, "model = \"analytic\"\nseeds = [1, 2, 3]\n",
                                              "strain_weight = 1.0\n[solver]\nmax_runs = 40\n[validation]\nseeds = [21, 22]\n"
                                              "[output]\ndir = \"out\"\n");
    const cal::CalibrationProblem problem = cal::load_calibration_problem(toml);
    const cal::ExpectedRuns expected = cal::expected_runs(problem);
    CHECK_FALSE(fs::exists(dir.path / "out"));  // an in-memory ledger: nothing on disk
    const auto model = cal::make_model(problem);
    const cal::CalibrationResult r = cal::run_calibration(problem, *model);
    CHECK(expected.fitted == r.runs_used);
    CHECK(expected.evaluations == static_cast<int>(r.history.size()));
    CHECK(expected.validation == r.validation_runs);
    CHECK(expected.validation == 2 * 2);  // one stage, two sands, two validation seeds
    CHECK(expected.fitted > 2 * 3);       // more than the start point
    CHECK(expected.fitted <= 40);
}

// A validation run on larger cubes costs what their grains and steps cost: the ETA counts it as
// (validation edge / fitted edge)^3 fitted runs of its sand, the ratio of the grains genesis
// samples for the two cubes of the same gradation, times the edge ratio again at the automatic
// rate (a fixed number of wave transits over the cube's height).
TEST_CASE("plan: the progress ETA counts a validation run by its cube's grains and steps", "[calibrate][plan]") {
    TempDir dir("cal-plan-eta");
    write_analytic_lab(dir.path);
    const auto problem_with = [&](const std::string& validation) {
        return cal::load_calibration_problem(test::write_problem(
            dir.path, "model = \"analytic\"\nseeds = [1, 2, 3]\n",
            "[solver]\nmax_runs = 40\n" + validation + "[output]\ndir = \"out\"\n"));
    };
    const cal::CalibrationProblem larger = problem_with("[validation]\nedge_mm = 3.75\nseeds = [21]\n");
    const cal::CalibrationProblem same = problem_with("[validation]\nseeds = [21]\n");
    const cal::ExpectedRuns e = cal::expected_runs(larger);
    const double fitted_edge = larger.base.specimen.genesis.edge;
    REQUIRE(larger.base.auto_strain_rate);
    CHECK(e.validation_grains_ratio == Approx(std::pow(3.75e-3 / fitted_edge, 3)));
    CHECK(e.validation_steps_ratio == Approx(3.75e-3 / fitted_edge));
    CHECK(e.validation_run_weight == Approx(e.validation_grains_ratio * e.validation_steps_ratio));
    CHECK(cal::expected_runs(same).validation_run_weight == 1.0);
    const cal::ExpectedRuns scaled = cal::expected_runs(problem_with("[scale_up]\nedge_mm = 3.75\nseeds = [11]\n[validation]\nseeds = [21]\n"));
    CHECK(scaled.scale_up_run_weight == Approx(e.validation_run_weight));  // the same edge, the same cost
    CHECK(scaled.validation_run_weight == 1.0);
    CHECK(scaled.scale_up == 2);  // one seed per sand

    // The steps' ratio is the automatic rate's: the same grains in a cube of 3.75 mm and of the
    // fitted edge (every coordinate scaled) are loaded at rates in the inverse ratio of the edges.
    exp::Packing small, big;
    const double k = 3.75e-3 / fitted_edge;
    for (int i = 0; i < 8; ++i) {
        const Vec3 x{0.25e-3 * (1 + i % 2), 0.25e-3 * (1 + i / 2 % 2), 0.25e-3 * (1 + i / 4)};
        small.position.push_back(x);
        small.radius.push_back(0.1e-3 + 0.01e-3 * i);
        big.position.push_back(x * k);
        big.radius.push_back(small.radius.back() * k);
    }
    small.density = big.density = 2650.0;
    small.box_hi = {fitted_edge, fitted_edge, fitted_edge};
    big.box_hi = small.box_hi * k;
    CHECK(exp::quasi_static_strain_rate(small, larger.base.material) / exp::quasi_static_strain_rate(big, larger.base.material) ==
          Approx(e.validation_steps_ratio).epsilon(1e-12));

    // The weight is the grains' ratio: genesis fills each cube with grains of the same curve.
    exp::CubeConfig config = larger.base;
    config.sand = kSands[0];
    const lab::GradationCurve curve = exp::load_gradation(config);
    const exp::SpecimenSpec& spec = config.specimen;
    const auto grains = [&](double edge) {
        return static_cast<double>(
            exp::sample_grains(curve, spec.size_rule, spec.genesis.target_solid_fraction * edge * edge * edge, 21).diameters.size());
    };
    CHECK(grains(3.75e-3) / grains(fitted_edge) == Approx(e.validation_grains_ratio).epsilon(0.05));

    // After 6 of 26 expected runs at 30 s each on 2 workers: 20 fitted runs and the validation's.
    cal::Progress p;
    p.runs_used = 6;
    p.max_runs = 40;
    p.mean_run_s = 30.0;
    p.workers = 2;
    cal::ExpectedRuns path = e;
    path.fitted = 26;
    CHECK(cal::eta_seconds(p, path) == Approx(15.0 * (20 + path.validation * e.validation_run_weight)));
    CHECK(cal::eta_seconds(p, path, true) == Approx(15.0 * (34 + path.validation * e.validation_run_weight)));
    p.mean_run_s = 0.0;  // every run so far from the ledger: no estimate
    CHECK(std::isnan(cal::eta_seconds(p, path)));
}

// The sands' runs differ in cost (a finer sand fills a cube with more grains) and in number
// (sand_seeds): the ETA prices each sand's share of the remaining runs at that sand's own mean
// run time, so a path that runs the cheap sand more than the validation does is not priced at
// the cheap sand's rate.
TEST_CASE("plan: the progress ETA prices each sand's runs at that sand's mean run time", "[calibrate][plan]") {
    TempDir dir("cal-plan-eta-sands");
    write_analytic_lab(dir.path);
    const cal::CalibrationProblem problem = cal::load_calibration_problem(test::write_problem(
        dir.path, "model = \"analytic\"\nseeds = [1, 2]\nsand_seeds = { \"Van Buren\" = [1, 2, 3, 4, 5, 6] }\n",
        "[solver]\nmax_runs = 80\n[validation]\nseeds = [21, 22, 23]\n[output]\ndir = \"out\"\n"));
    cal::ExpectedRuns e = cal::expected_runs(problem);
    REQUIRE(e.fitted_share.size() == 2);
    CHECK(e.fitted_share[0] == Approx(2.0 / 8.0));  // pre-blended: 2 of every evaluation's 8 runs
    CHECK(e.fitted_share[1] == Approx(6.0 / 8.0));
    CHECK(e.validation_share == std::vector<double>{0.5, 0.5});  // 3 seeds of each sand
    CHECK(e.validation == 6);

    // After the first evaluation: pre-blended 60 s a run, Van Buren 20 s (mean of the 8: 30 s).
    cal::Progress p;
    p.runs_used = 8;
    p.max_runs = 80;
    p.workers = 2;
    p.mean_run_s = (2 * 60.0 + 6 * 20.0) / 8.0;
    p.sand_mean_run_s = {60.0, 20.0};
    e.fitted = 16;
    e.validation_run_weight = 1.5;
    const double path = 8 * (0.25 * 60.0 + 0.75 * 20.0), validation = 6 * 1.5 * (0.5 * 60.0 + 0.5 * 20.0);
    CHECK(cal::eta_seconds(p, e) == Approx((path + validation) / 2.0));
    CHECK(cal::eta_seconds(p, e) > (8 + 6 * 1.5) * p.mean_run_s / 2.0);  // the mean of all runs prices it short
    cal::ExpectedRuns with_scale_up = e;  // two scale-up runs of twice a fitted run's cost, a sand each
    with_scale_up.scale_up = 2;
    with_scale_up.scale_up_run_weight = 2.0;
    CHECK(cal::eta_seconds(p, with_scale_up) == Approx((path + validation + 2 * 2.0 * (0.5 * 60.0 + 0.5 * 20.0)) / 2.0));
    // The evaluator reports each sand's mean: runs that take 60 s + seed of pre-blended and
    // 20 s + seed of Van Buren give 61.5 and 23.5 s after the first evaluation (seeds 1-2, 1-6).
    class TimedModel final : public cal::CubeModel {
    public:
        void prepare(const cal::PackingSeeds&, int, const std::function<void(const std::string&)>&) override {}
        cal::RunOutcome run(const cal::RunRequest& q, double t) const override {
            cal::RunOutcome o = inner_->run(q, t);
            o.wall_seconds = (q.sand == 0 ? 60.0 : 20.0) + static_cast<double>(q.seed);
            return o;
        }
        std::string fingerprint() const override { return inner_->fingerprint() + "; timed"; }
        std::string run_fingerprint(cal::CubeTest t) const override { return inner_->run_fingerprint(t) + "; timed"; }

    private:
        std::unique_ptr<cal::CubeModel> inner_ = cal::make_analytic_model(2, 0.001);
    } timed;
    const cal::CalibrationProblem unvalidated = cal::load_calibration_problem(test::write_problem(
        dir.path, "model = \"analytic\"\nseeds = [1, 2]\nsand_seeds = { \"Van Buren\" = [1, 2, 3, 4, 5, 6] }\n",
        "[solver]\nmax_runs = 80\n[output]\ndir = \"out\"\n", "unvalidated.toml"));
    std::vector<cal::Progress> seen;
    cal::run_calibration(unvalidated, timed, {}, [&](const cal::Progress& q) { seen.push_back(q); });
    REQUIRE(seen.size() >= 8);
    CHECK(seen[7].sand_mean_run_s == std::vector<double>{61.5, 23.5});
    CHECK(seen[7].mean_run_s == Approx((61 + 62 + 21 + 22 + 23 + 24 + 25 + 26) / 8.0));
    // A sand not timed yet is priced at the mean of every run so far.
    p.sand_mean_run_s = {60.0};
    CHECK(cal::eta_seconds(p, e) == Approx((8 * (0.25 * 60.0 + 0.75 * 30.0) + 6 * 1.5 * (0.5 * 60.0 + 0.5 * 30.0)) / 2.0));
}

TEST_CASE("plan: a DEM problem's specimens, time step and steps are those of the runs it plans", "[calibrate][plan]") {
    TempDir dir("cal-plan-dem");
    const exp::CubeConfig cube = exp::load_cube_config(write_tiny_base(dir.path));
    auto model = cal::make_dem_model(cube, {"Van Buren"});
    model->prepare({1, 2}, 2, {});
    test::write_text(dir.path / "lab_results.json", test::synthetic_lab_results(*model, {"Van Buren"}, cube.material, {1, 2}).dump(1));
    const fs::path toml = dir.path / "problem.toml";
    test::write_text(toml, "[calibration]\nbase = \"base.toml\"\nsands = [\"Van Buren\"]\nseeds = [1, 2]\n"
                           "[targets]\nlab_results = \"lab_results.json\"\n[solver]\nmax_runs = 8\n"
                           "[validation]\nseeds = [11, 12]\n[output]\ndir = \"out\"\n");
    const cal::CalibrationProblem problem = cal::load_calibration_problem(toml);
    const cal::CalibrationPlan plan = cal::plan_calibration(problem, 0.5);
    CHECK_FALSE(fs::exists(dir.path / "out"));

    // The fit's packings are cached: their own grain counts. The validation's are not: the
    // plan makes its first seed's for the engine timing (cached, so the run reads it), and
    // counts the grains genesis will sample for the other.
    REQUIRE(plan.specimens.size() == 4);
    const lab::GradationCurve curve = exp::load_gradation(cube);
    for (const cal::SpecimenPlan& s : plan.specimens) {
        exp::SpecimenSpec spec = cube.specimen;
        spec.seed = s.seed;
        const fs::path cached = exp::packing_cache_path(cube.cache_dir, exp::packing_key(curve, spec));
        INFO(s.set << " seed " << s.seed);
        const bool made = s.set == "validation" && s.seed == 11;
        CHECK(s.cached == (s.set == "fit" || made));
        CHECK((s.genesis_s > 0.0) == made);
        CHECK(fs::exists(cached) == s.cached);
        if (s.cached) CHECK(s.particles == static_cast<std::int64_t>(exp::load_packing(cached, exp::packing_key(curve, spec)).radius.size()));
    }
    const cal::SpecimenPlan& unseen = plan.specimens.back();
    const exp::Packing made = exp::load_or_generate(curve, [&] { auto s = cube.specimen; s.seed = unseen.seed; return s; }(), cube.cache_dir);
    CHECK(std::fabs(static_cast<double>(unseen.particles) / static_cast<double>(made.radius.size()) - 1.0) < 0.10);

    // The run the plan prices: seed 1 at the start material, as the calibration runs it.
    REQUIRE(plan.runs.size() == 2);
    const cal::RunCostPlan& fit = plan.runs.front();
    CHECK(fit.set == "fit");
    CHECK(fit.compression_runs + plan.runs.back().compression_runs == plan.expected_runs + plan.validation_runs);
    exp::CubeTestSpec spec = cube.test;
    exp::SpecimenSpec seed1 = cube.specimen;
    seed1.seed = 1;
    const exp::Packing packing = exp::load_or_generate(curve, seed1, cube.cache_dir);
    const exp::CubeTestResult run = exp::run_cube_test(packing, cube.material, spec);
    CHECK(fit.time_step_s == Approx(run.time_step).epsilon(1e-12));
    const double steps = static_cast<double>(run.test.steps + run.settle_steps);
    INFO("planned " << fit.compression_steps << " steps, ran " << steps);
    CHECK(std::fabs(fit.compression_steps / steps - 1.0) < 0.30);
    CHECK(fit.seconds_per_particle_step > 0.0);
    CHECK(plan.run_wall_s > 0.0);
    // The other validation packing still needs genesis, priced at the pace of the one made.
    CHECK(plan.genesis_wall_max_s == 0.0);
    CHECK(plan.genesis_wall_s == Approx(plan.specimens[2].genesis_s * static_cast<double>(unseen.particles) /
                                        static_cast<double>(plan.specimens[2].particles)));

    // What --plan prints: the same numbers for people and for programs.
    const nlohmann::json j = nlohmann::json::parse(cal::plan_json(plan));
    CHECK(j["expected_runs"] == plan.expected_runs);
    CHECK(j["runs"].size() == 2);
    CHECK(j["specimens"][2]["cached"] == true);
    CHECK(j["specimens"][2]["genesis_s"].get<double>() > 0.0);
    CHECK(j["specimens"][3]["cached"] == false);
    CHECK(j["wall_s"].get<double>() == plan.run_wall_s);
    const std::string text = cal::plan_text(plan);
    CHECK(text.find("estimated wall time") != std::string::npos);
    CHECK(text.find("Van Buren (validation), seed 11") != std::string::npos);
    CHECK(text.find("made now for the engine timing") != std::string::npos);
}

TEST_CASE("plan: a flat joint's runs are priced with its law's PlatenTestCost", "[calibrate][plan]") {
    // The law's row (core/flat_joint_law.hpp) is measured on the main job's runs; here: that the
    // plan of a flat-joint problem takes it, and prices a run as its factor times the probe.
    TempDir dir("cal-plan-fj");
    const exp::CubeConfig cube = exp::load_cube_config(write_tiny_base(dir.path, "[material]\nmodel = \"flat_joint\"\n"));
    REQUIRE(cube.material.bond.model == BondModel::flat_joint);
    auto model = cal::make_dem_model(cube, {"Van Buren"});
    model->prepare({1}, 1, {});
    test::write_text(dir.path / "lab_results.json", test::synthetic_lab_results(*model, {"Van Buren"}, cube.material, {1}).dump(1));
    test::write_text(dir.path / "problem.toml", "[calibration]\nbase = \"base.toml\"\nsands = [\"Van Buren\"]\nseeds = [1]\n"
                                                "[targets]\nlab_results = \"lab_results.json\"\n[solver]\nmax_runs = 4\n"
                                                "[output]\ndir = \"out\"\n");
    const cal::CalibrationPlan plan = cal::plan_calibration(cal::load_calibration_problem(dir.path / "problem.toml"), 0.5);
    REQUIRE(plan.runs.size() == 1);
    const cal::RunCostPlan& fit = plan.runs.front();
    constexpr PlatenTestCost law = FlatJointLaw::kPlatenTestCost;
    // The run's mean factor lies between the law's before and after the peak.
    CHECK(fit.compression_cost_factor > law.pre_peak_cost_factor);
    CHECK(fit.compression_cost_factor < law.post_peak_cost_factor);
    CHECK(fit.tension_cost_factor == law.tension_cost_factor);
    REQUIRE(fit.compression_runs > 0);
    CHECK(fit.seconds() == Approx(fit.particles * fit.seconds_per_particle_step * fit.compression_cost_factor *
                                  fit.compression_runs * fit.compression_steps).epsilon(1e-12));
    CHECK(plan.run_wall_s == Approx(fit.seconds() / std::min(plan.workers, plan.cores)).epsilon(1e-12));
    CHECK(cal::plan_text(plan).find("flat_joint's PlatenTestCost") != std::string::npos);

    // Stopped at 0.85 x the peak, the tail after the peak is half as long: the loading ends at
    // peak + (end - peak) / 2 = (1.3 + 1.9 / 2) / 3.2 of its length at 0.7 (the half-cosine ramp
    // aside, a few per mille of these ends).
    test::write_text(dir.path / "early.toml", "[calibration]\nbase = \"base.toml\"\nsands = [\"Van Buren\"]\nseeds = [1]\n"
                                              "stop_fraction = 0.85\n[targets]\nlab_results = \"lab_results.json\"\n"
                                              "[solver]\nmax_runs = 4\n[output]\ndir = \"out\"\n");
    const cal::CalibrationPlan early = cal::plan_calibration(cal::load_calibration_problem(dir.path / "early.toml"), 0.5);
    const double loading = fit.compression_steps - fit.settle_steps;
    const double early_loading = early.runs.front().compression_steps - early.runs.front().settle_steps;
    CHECK(early_loading / loading == Approx((law.compression_peak_over_elastic + 0.5 * (law.compression_end_over_elastic -
                                                                                       law.compression_peak_over_elastic)) /
                                            law.compression_end_over_elastic)
                                         .epsilon(0.02));

    // With a strain stop at 1.2 x the strain at peak, the loading ends there: 1.2 x 1.5 / 4 of
    // its length at 0.7, and the plan says so.
    test::write_text(dir.path / "strain.toml", "[calibration]\nbase = \"base.toml\"\nsands = [\"Van Buren\"]\nseeds = [1]\n"
                                               "stop_strain_ratio = 1.2\n[targets]\nlab_results = \"lab_results.json\"\n"
                                               "[solver]\nmax_runs = 4\n[output]\ndir = \"out\"\n");
    const cal::CalibrationPlan strain = cal::plan_calibration(cal::load_calibration_problem(dir.path / "strain.toml"), 0.5);
    const double strain_loading = strain.runs.front().compression_steps - strain.runs.front().settle_steps;
    CHECK(strain_loading / loading ==
          Approx(1.2 * law.compression_peak_over_elastic / law.compression_end_over_elastic).epsilon(0.02));
    CHECK(cal::plan_text(strain).find("ends by 1.2 x its expected strain at peak") != std::string::npos);
}

TEST_CASE("plan: the result's tension tests on the fitted tension seeds alone, the path's other runs compression",
          "[calibrate][plan][tension]") {
    TempDir dir("cal-plan-tension-seeds");
    const std::vector<std::string> sands = {"pre-blended", "Van Buren"};
    const exp::CubeConfig cube = exp::load_cube_config(write_tiny_base(dir.path));
    auto model = cal::make_dem_model(cube, sands);
    model->prepare({1}, 1, {});
    test::write_text(dir.path / "lab_results.json", test::synthetic_lab_results(*model, sands, cube.material, {1}).dump(1));
    const auto plan_with = [&](const std::string& tension_seeds) {
        test::write_text(dir.path / "problem.toml",
                         "[calibration]\nbase = \"base.toml\"\nseeds = [1, 2, 3]\n"
                         "sand_seeds = { \"Van Buren\" = [1, 2, 3, 4, 5] }\n" +
                             tension_seeds +
                             "[targets]\nlab_results = \"lab_results.json\"\ntension = \"assumed_ratio\"\ntension_basis = \"test\"\n"
                             "tension_weight = 0.0\n[parameters.cohesion_ratio]\nfree = false\n[parameters.strength_cv]\n"
                             "free = false\n[solver]\nmax_runs = 40\n[output]\ndir = \"out\"\n");
        return cal::plan_calibration(cal::load_calibration_problem(dir.path / "problem.toml"), 0.2);
    };
    const cal::CalibrationPlan every = plan_with(""), one = plan_with("tension_seeds = [2]\n");
    // The scales alone free: the same path, start and rescaled, of 3 + 5 compression runs each;
    // then the result's tension tests on every seed, or on seed 2 of each sand alone.
    REQUIRE(every.runs.size() == 2);
    REQUIRE(one.runs.size() == 2);
    CHECK(every.expected_runs == 16 + 8);
    CHECK(one.expected_runs == 16 + 2);
    for (std::size_t s = 0; s < 2; ++s) {
        INFO(sands[s]);
        const int seeds = s == 0 ? 3 : 5;
        CHECK(every.runs[s].compression_runs == 2 * seeds);
        CHECK(every.runs[s].tension_runs == seeds);
        CHECK(one.runs[s].compression_runs == 2 * seeds);
        CHECK(one.runs[s].tension_runs == 1);
    }
}

TEST_CASE("study plan: the cases the kind asks for, priced on their own specimens, and nothing is written",
          "[calibrate][plan][study]") {
    TempDir dir("study-plan-dem");
    const exp::CubeConfig cube = exp::load_cube_config(write_tiny_base(dir.path));
    auto model = cal::make_dem_model(cube, {"Van Buren"});
    model->prepare({1}, 1, {});
    test::write_text(dir.path / "lab_results.json", test::synthetic_lab_results(*model, {"Van Buren"}, cube.material, {1}).dump(1));
    const fs::path toml = dir.path / "problem.toml";
    test::write_text(toml, "[calibration]\nbase = \"base.toml\"\nsands = [\"Van Buren\"]\nseeds = [1]\n"
                           "[targets]\nlab_results = \"lab_results.json\"\n[output]\ndir = \"cal\"\n");
    const cal::CalibrationProblem problem = cal::load_calibration_problem(toml);
    // The calibration studied, as gradem calibrate writes its summary: every parameter at its start.
    nlohmann::json summary{{"schema", "gradem-calibration/1"},
                           {"config", toml.string()},
                           {"sands", {"Van Buren"}},
                           {"lab_results", problem.lab_results.string()},
                           {"parameters", nlohmann::json::array()}};
    for (const cal::ParameterSpec& p : problem.parameters) summary["parameters"].push_back({{"name", p.name}, {"value", p.start}});
    fs::create_directories(dir.path / "cal");
    test::write_text(dir.path / "cal" / "summary.json", summary.dump(1));
    test::write_text(dir.path / "study.toml", "[study]\nkind = \"sensitivity\"\ncalibration = \"" +
                                                  (dir.path / "cal" / "summary.json").string() + "\"\nseeds = [1, 3]\n[output]\ndir = \"" +
                                                  (dir.path / "study-out").string() + "\"\n");
    const cal::StudyConfig config = cal::load_study_config(dir.path / "study.toml");
    const cal::StudyPlan plan = cal::plan_study(config, 0.5);
    CHECK_FALSE(fs::exists(dir.path / "study-out"));  // no ledger, no outputs

    // Sensitivity asks for the calibrated point and one step per free parameter, on both seeds.
    const cal::ParameterSpace space(problem.parameters, problem.base.material);
    const int points = 1 + static_cast<int>(space.size());
    CHECK(plan.kind == "sensitivity");
    CHECK(plan.cases == points);
    CHECK(plan.compression_runs == 2 * points);
    CHECK(plan.tension_runs == 0);
    REQUIRE(plan.runs.size() == 1);
    CHECK(plan.runs[0].compression_runs == plan.compression_runs);

    // Seed 1 is cached (its own grain count), seed 3 still needs genesis (a bound on its cost).
    REQUIRE(plan.specimens.size() == 2);
    CHECK(plan.specimens[0].cached);
    CHECK_FALSE(plan.specimens[1].cached);
    CHECK(plan.genesis_wall_max_s > 0.0);
    CHECK(plan.run_wall_s > 0.0);

    // Timed on seed 1 at the calibrated point: the time step of that specimen.
    exp::SpecimenSpec seed1 = cube.specimen;
    seed1.seed = 1;
    const exp::Packing packing = exp::load_or_generate(exp::load_gradation(cube), seed1, cube.cache_dir);
    World specimen = exp::bonded_cube_specimen(packing, space.material(space.start()));
    CHECK(plan.runs[0].time_step_s == Approx(specimen.time_step()).epsilon(1e-12));
    CHECK(plan.specimens[0].particles == static_cast<std::int64_t>(packing.radius.size()));

    const nlohmann::json j = nlohmann::json::parse(cal::study_plan_json(plan));
    CHECK(j["cases"] == points);
    CHECK(j["runs"].size() == 1);
    CHECK(j["wall_s"].get<double>() == plan.run_wall_s);
    CHECK(cal::study_plan_text(plan).find("study sensitivity: " + std::to_string(points) + " cases") == 0);
}
