// The validation specimens of a calibration ([validation] edge_mm, seeds): the result is run
// on unseen seeds after the fit, reported first, and a result that does not hold there says so;
// the tension tests at the result share its batch, which starts the longest runs first; bad
// [validation] tables are refused before anything runs.
#include <catch2/catch.hpp>
#include <algorithm>
#include <cmath>
#include <regex>

#include "calibrate/plan.hpp"
#include "calibrate/problem.hpp"
#include "calibrate/validation.hpp"
#include "common/number_format.hpp"
#include "calibrate_fixture.hpp"
#include "experiments/config/cube_config.hpp"
#include "reports/calibration_report.hpp"

namespace fs = std::filesystem;
using namespace gradem;
using gradem::test::TempDir;

namespace {

const std::vector<std::string> kSands = {"pre-blended", "Van Buren"};

exp::MaterialParams truth_material() { return test::material_at({20.0, 12.0, 1.6, 0.25}); }

void write_lab(const fs::path& dir, const cal::CubeModel& model) {
    test::write_text(dir / "lab_results.json",
                     test::synthetic_lab_results(model, kSands, truth_material(), {101, 102, 103, 104, 105, 106}).dump(1));
}

fs::path problem_with(const fs::path& dir, const cal::CubeModel& model, const std::string& validation) {
    write_lab(dir, model);
    return test::write_problem(dir, "model = \"analytic\"\nseeds = [1, 2, 3]\n",
                               "strain_weight = 1.0\n[solver]\nmethod = \"scaling\"\nmax_runs = 300\ntolerance = 0.002\n" + validation +
                                   "\n[output]\ndir = \"out\"\n");
}

/// The first stage's statements on unmet targets that contain `what`.
std::vector<std::string> unmet_containing(const nlohmann::json& summary, const std::string& what) {
    std::vector<std::string> out;
    for (const auto& u : summary["stages"][0]["unmet_targets"])
        if (u.get<std::string>().find(what) != std::string::npos) out.push_back(u.get<std::string>());
    return out;
}

}  // namespace

TEST_CASE("validation on unseen seeds: run after the fit, apart from the budget, and reported first", "[calibrate][validation]") {
    TempDir dir("cal-validation");
    auto plain = cal::make_analytic_model(2, 0.001);
    const cal::CalibrationProblem problem =
        cal::load_calibration_problem(problem_with(dir.path, *plain, "[validation]\nseeds = [11, 12]\n"));
    REQUIRE(problem.validation.enabled());
    CHECK(problem.validation.edge == problem.base.specimen.genesis.edge);  // default: the fit's edge
    const auto model = cal::make_model(problem);
    REQUIRE(dynamic_cast<const cal::ValidatedModel*>(model.get()) != nullptr);
    const cal::CalibrationResult r = cal::run_calibration(problem, *model);
    const cal::CalibrationStage& st = r.stages.at(0);
    // Every sand on every validation seed, once: 2 sands x 2 seeds.
    CHECK(st.validation.runs == 4);
    CHECK(r.validation_runs == 4);
    // Its cost apart from the fit's: 4 stand-in runs of 1000 grains x 1 step.
    CHECK(r.validation_cost.executed == 4);
    CHECK(r.validation_cost.particle_steps == 4000.0);
    CHECK(r.fit_cost.executed == r.runs_executed);
    CHECK(r.fit_cost.particle_steps == 1000.0 * r.runs_executed);
    REQUIRE(st.validation.evaluation.runs.size() == 4);
    CHECK(st.validation.evaluation.values == st.solution.best);
    CHECK(r.runs_used <= problem.solver.max_runs);
    // The milestone line gives the seeds and the edge as a person writes them ("2.5 mm", not "2.500000").
    const std::string milestone = "validation on 2 unseen seeds, edge " +
                                  common::format_significant(problem.validation.edge * 1e3, 4) + " mm: 4 runs (0 from the ledger)";
    CHECK(std::count(r.log.begin(), r.log.end(), milestone) == 1);
    // The stand-in does not depend on the specimen, so the result holds on unseen seeds.
    const nlohmann::json summary = report::summary_json(problem, r);
    CHECK(summary["stages"][0]["validation"]["holds"] == true);
    int rows = 0;
    for (const auto& t : summary["targets"])
        if (t["role"] == "validation") {
            ++rows;
            CHECK(std::fabs(t["rel_error"].get<double>()) < 0.02);
        }
    CHECK(rows == 6);
    const std::string md = report::summary_markdown(problem, r);
    CHECK(md.find("**Validation**") < md.find("Solver path"));  // the validation leads the stage
    CHECK_THAT(md, Catch::Contains("every target holds on specimens the fit never saw"));
    CHECK_THAT(report::brief_report(problem, r), Catch::Contains("validation holds"));
    // A second run serves the validation from the ledger as well.
    const cal::CalibrationResult again = cal::run_calibration(problem, *model);
    CHECK(again.stages.at(0).validation.from_ledger == 4);
    CHECK(again.runs_executed == 0);
}

TEST_CASE("a result that does not hold on the validation specimens says so plainly", "[calibrate][validation]") {
    TempDir dir("cal-validation-miss");
    auto plain = cal::make_analytic_model(2, 0.001);
    const cal::CalibrationProblem problem =
        cal::load_calibration_problem(problem_with(dir.path, *plain, "[validation]\nseeds = [11, 12]\n"));
    // Validation specimens 15 % stiffer than the fitted ones (as a larger, better converged cube can be).
    cal::ValidatedModel model(cal::make_analytic_model(2, 0.001), std::make_unique<test::ScaledSpecimenModel>(1.15, 1.0), kSands.size(),
                                    problem.validation.seeds);
    const cal::CalibrationResult r = cal::run_calibration(problem, model);
    const nlohmann::json summary = report::summary_json(problem, r);
    CHECK(summary["stages"][0]["validation"]["holds"] == false);
    for (const auto& t : summary["targets"])
        if (t["role"] == "validation" && t["quantity"] == "modulus") {
            CHECK(t["rel_error"].get<double>() == Approx(0.15).margin(0.02));
            CHECK(t["met"] == false);
        }
    CHECK_THAT(report::summary_markdown(problem, r), Catch::Contains("does NOT hold on specimens the fit never saw"));
    const std::string brief = report::brief_report(problem, r);
    CHECK_THAT(brief, Catch::Contains("validation MISSES"));
    // The 15 % stiffer validation specimens miss in E, each sand's error marked; no peak is marked.
    INFO(brief);
    CHECK(std::regex_search(brief, std::regex(R"(validation MISSES pre-blended E \+1[45]\.[0-9] % \(miss\))")));
    CHECK(std::regex_search(brief, std::regex(R"(Van Buren E \+1[45]\.[0-9] % \(miss\))")));
    CHECK_FALSE(std::regex_search(brief, std::regex(R"(peak [-+][0-9.]+ % \(miss\))")));
    bool stated = false;
    for (const auto& u : summary["stages"][0]["unmet_targets"])
        stated = stated || u.get<std::string>().find("validation specimens") != std::string::npos;
    CHECK(stated);
}

// Validation specimens whose curves bend more (D x 1.3, E and peak as fitted): the strain at
// peak misses there alone, and its statement gives the validation specimens' D beside the fit's
// and the fitted specimens' seed scatter (a miss there is not a compromise of the fit).
TEST_CASE("a strain-at-peak miss on the validation specimens is explained by their own shape index", "[calibrate][validation]") {
    TempDir dir("cal-validation-shape");
    auto plain = cal::make_analytic_model(2, 0.001);
    const cal::CalibrationProblem problem =
        cal::load_calibration_problem(problem_with(dir.path, *plain, "[validation]\nseeds = [11, 12]\n"));
    cal::ValidatedModel model(cal::make_analytic_model(2, 0.001), std::make_unique<test::ScaledSpecimenModel>(1.0, 1.0, 1.3),
                              kSands.size(), problem.validation.seeds);
    const cal::CalibrationResult r = cal::run_calibration(problem, model);
    const nlohmann::json summary = report::summary_json(problem, r);
    double fitted_d = 0.0, validation_d = 0.0;
    for (const auto& row : summary["stages"][0]["shape_index_d"])
        if (row["sand"] == kSands[0]) (row["role"] == "validation" ? validation_d : fitted_d) = row["simulated"].get<double>();
    REQUIRE(fitted_d > 0.0);
    CHECK(validation_d == Approx(1.3 * fitted_d).epsilon(0.02));
    const std::vector<std::string> strain_misses = unmet_containing(summary, "strain at peak");
    for (const std::string& text : strain_misses) {
        CHECK_THAT(text, Catch::Contains("(validation)"));
        if (text.rfind(kSands[0], 0) == 0)  // the validation cubes' D beside the fitted ones'
            CHECK_THAT(text, Catch::Contains("is " + common::format_significant(validation_d, 3) + " against " +
                                             common::format_significant(fitted_d, 3) + " on the fitted specimens"));
        // not fitted there, so not "the best compromise the weights allow"; the fitted cubes' seed scatter is given
        CHECK_THAT(text, !Catch::Contains("best compromise"));
        CHECK_THAT(text, Catch::Contains("(standard deviation) between their " + std::to_string(problem.seeds_of(0).size()) + " packing seeds"));
    }
    CHECK(strain_misses.size() == 2);  // one per sand, on the validation specimens only
}

namespace {

/// A problem of both sands with an assumed σc/σt target (reported, not fitted) and `validation`.
fs::path problem_with_tension(const fs::path& dir, const cal::CubeModel& model, const std::string& validation,
                              const std::string& mode = "joint") {
    write_lab(dir, model);
    return test::write_problem(dir, "model = \"analytic\"\nmode = \"" + mode + "\"\nseeds = [1, 2, 3]\n",
                               "strain_weight = 1.0\ntension = \"assumed_ratio\"\ntension_ratio = 10.0\ntension_ratio_low = 8.0\n"
                               "tension_ratio_high = 12.0\ntension_basis = \"test\"\ntension_weight = 0.0\n"
                               "[solver]\nmethod = \"scaling\"\nmax_runs = 300\ntolerance = 0.002\n" + validation +
                                   "\n[output]\ndir = \"out\"\n");
}

}  // namespace

// The strain at peak of one cube scatters more than σt does, so a validation may run the
// direct-tension test on some of its cubes only: [validation] tension_seeds. Every validation
// seed runs its compression test, the tension seeds their tension test too; the plan counts
// the same runs, and the summary names the seeds.
TEST_CASE("validation tension seeds: the direct-tension tests run on those validation cubes alone", "[calibrate][validation]") {
    TempDir all_dir("cal-validation-tension-all"), some_dir("cal-validation-tension-some");
    auto plain = cal::make_analytic_model(2, 0.001);
    const cal::CalibrationProblem every =
        cal::load_calibration_problem(problem_with_tension(all_dir.path, *plain, "[validation]\nseeds = [11, 12, 13]\n"));
    const cal::CalibrationProblem some = cal::load_calibration_problem(
        problem_with_tension(some_dir.path, *plain, "[validation]\nseeds = [11, 12, 13]\ntension_seeds = [12]\n"));
    REQUIRE(some.validation.tension_seeds == std::vector<std::uint64_t>{12});
    const cal::CalibrationResult r_every = cal::run_calibration(every, *cal::make_model(every));
    const cal::CalibrationResult r_some = cal::run_calibration(some, *cal::make_model(some));
    // 2 sands x 3 compression runs, and 2 x 3 or 2 x 1 tension runs.
    const cal::Evaluation& v_every = r_every.stages.at(0).validation.evaluation;
    const cal::Evaluation& v_some = r_some.stages.at(0).validation.evaluation;
    CHECK(r_every.validation_runs == 12);
    CHECK(r_some.validation_runs == 8);
    CHECK(v_every.runs.size() == 6);
    CHECK(v_every.tension_runs.size() == 6);
    CHECK(v_some.runs.size() == 6);
    CHECK(v_some.tension_runs.size() == 2);
    CHECK(cal::expected_runs(some).validation == 8);
    // The same fit, so the same point; σt of one cube (seed 12) against the mean of three.
    REQUIRE(v_some.values == v_every.values);
    for (std::size_t s = 0; s < kSands.size(); ++s) {
        CHECK(v_some.sands.at(s).tension_ok == 1);
        CHECK(v_some.sands.at(s).value(cal::Quantity::modulus) == v_every.sands.at(s).value(cal::Quantity::modulus));
        CHECK(v_some.tension_runs.at(s).peak_pa == v_every.tension_runs.at(3 * s + 1).peak_pa);  // seed 12 is the second
        CHECK(v_some.sands.at(s).value(cal::Quantity::tension) == v_every.tension_runs.at(3 * s + 1).peak_pa);
    }
    const nlohmann::json summary = report::summary_json(some, r_some);
    CHECK(summary["stages"][0]["validation"]["tension_seeds"] == nlohmann::json::array({12}));
    CHECK(report::summary_json(every, r_every)["stages"][0]["validation"]["tension_seeds"] == nlohmann::json::array({11, 12, 13}));
    CHECK_THAT(report::summary_markdown(some, r_some), Catch::Contains("packing seeds 11, 12, 13 (direct tension on 12)"));
}

namespace {

/// The thread executor, keeping every batch it is handed.
class RecordingExecutor final : public cal::RunExecutor {
public:
    RecordingExecutor(cal::CubeModel& model, int workers) : threads_(model, workers) {}
    void prepare(const cal::PackingSeeds& seeds, const Log& log) override { threads_.prepare(seeds, log); }
    void run(const std::vector<cal::RunRequest>& requests, double timeout_s, const RunDone& done) override {
        batches.push_back(requests);
        threads_.run(requests, timeout_s, done);
    }
    [[nodiscard]] int slots() const override { return threads_.slots(); }
    [[nodiscard]] std::string describe() const override { return threads_.describe(); }
    std::vector<std::vector<cal::RunRequest>> batches;

private:
    cal::ThreadExecutor threads_;
};

}  // namespace

// With the tension target reported only, the tension tests at the result wait for the
// validation and run in its batch (a worker the few tension tests would leave idle runs
// validation runs meanwhile). Oracle: the same problem without its validation table runs those
// tests alone, as the last batch of its fit; the merged job's fit, its result's evaluation
// (σt included), noise floor and uncertainty are the same, bit for bit, and its validation is
// that of a validation run alone at that result.
TEST_CASE("tension tests at the result join the validation's batch: the same results, one batch fewer",
          "[calibrate][validation][tension]") {
    TempDir with_dir("cal-validation-joined"), alone_dir("cal-validation-joined-alone");
    auto plain = cal::make_analytic_model(2, 0.001);
    const cal::CalibrationProblem joined =
        cal::load_calibration_problem(problem_with_tension(with_dir.path, *plain, "[validation]\nseeds = [11, 12]\n"));
    const cal::CalibrationProblem alone = cal::load_calibration_problem(problem_with_tension(alone_dir.path, *plain, ""));
    REQUIRE(joined.tension_at_result_only());
    auto joined_model = cal::make_model(joined);
    auto alone_model = cal::make_model(alone);
    RecordingExecutor joined_runs(*joined_model, 2), alone_runs(*alone_model, 2);
    const cal::CalibrationResult j = cal::run_calibration(joined, *joined_model, joined_runs);
    const cal::CalibrationResult a = cal::run_calibration(alone, *alone_model, alone_runs);

    // The fit and the result's evaluation, tension tests included.
    const cal::CalibrationStage &sj = j.stages.at(0), &sa = a.stages.at(0);
    REQUIRE(sa.solution.best_eval.label == "tension at the result");
    CHECK(sj.solution.best == sa.solution.best);
    CHECK(sj.solution.best_eval.label == "tension at the result");
    REQUIRE(sj.solution.best_eval.tension_runs.size() == sa.solution.best_eval.tension_runs.size());
    for (std::size_t s = 0; s < kSands.size(); ++s)
        for (cal::Quantity q : {cal::Quantity::modulus, cal::Quantity::peak, cal::Quantity::strain, cal::Quantity::tension})
            CHECK(sj.solution.best_eval.sands.at(s).value(q) == sa.solution.best_eval.sands.at(s).value(q));
    for (int q = 0; q < cal::kQuantityCount; ++q)
        CHECK((sj.noise_floor[q] == sa.noise_floor[q] || (std::isnan(sj.noise_floor[q]) && std::isnan(sa.noise_floor[q]))));
    CHECK(sj.uncertainty.computed == sa.uncertainty.computed);
    CHECK(sj.uncertainty.std_error_natural == sa.uncertainty.std_error_natural);
    CHECK(j.runs_used == a.runs_used);
    REQUIRE(j.history.size() == a.history.size());
    for (std::size_t k = 0; k < a.history.size(); ++k) CHECK(j.history[k].label == a.history[k].label);

    // One batch fewer: the one with the validation's runs (sands of its set, placed after the
    // fitted ones) also holds the result's tension tests (fitted sands), which the job without
    // a validation runs as a batch of their own.
    REQUIRE(joined_runs.batches.size() == alone_runs.batches.size());
    auto is_tension_at_result = [&](const cal::RunRequest& r) { return r.sand < kSands.size() && r.test == cal::CubeTest::tension; };
    std::size_t tension_at_result = 0;
    for (const auto& batch : alone_runs.batches)
        if (std::all_of(batch.begin(), batch.end(), is_tension_at_result)) tension_at_result = batch.size();
    REQUIRE(tension_at_result == kSands.size() * joined.seeds.size());
    std::size_t with_validation = 0;
    for (const auto& batch : joined_runs.batches) {
        if (std::none_of(batch.begin(), batch.end(), [&](const cal::RunRequest& r) { return r.sand >= kSands.size(); })) continue;
        ++with_validation;
        REQUIRE(batch.size() == static_cast<std::size_t>(j.validation_runs) + tension_at_result);
        CHECK(std::count_if(batch.begin(), batch.end(), is_tension_at_result) == static_cast<std::ptrdiff_t>(tension_at_result));
    }
    CHECK(with_validation == 1);

    // The validation is that of the result run on its own.
    TempDir again_dir("cal-validation-joined-again");
    cal::CalibrationProblem fresh = joined;
    fresh.ledger = again_dir.path / "ledger.sqlite";
    auto fresh_model = cal::make_model(fresh);
    cal::ThreadExecutor threads(*fresh_model, 2);
    threads.prepare(fresh.packing_seeds(), {});
    cal::Ledger ledger(fresh.ledger, "validation alone", "validation alone\n");
    const cal::StageValidation v = cal::validate_point(fresh, dynamic_cast<const cal::ValidatedModel&>(*fresh_model), threads,
                                                       ledger, sj.solution.best, sj.sands(), {});
    REQUIRE(v.evaluation.sands.size() == kSands.size());
    for (std::size_t s = 0; s < kSands.size(); ++s) {
        CHECK(v.evaluation.sands.at(s).value(cal::Quantity::modulus) == sj.validation.evaluation.sands.at(s).value(cal::Quantity::modulus));
        CHECK(v.evaluation.sands.at(s).value(cal::Quantity::tension) == sj.validation.evaluation.sands.at(s).value(cal::Quantity::tension));
    }
    CHECK(v.runs == j.validation_runs);
}

// Per sand, each stage's tension tests wait for its own validation while the next stage solves:
// their runs stay held back from the budget until then. Oracle: the same stages and budget as
// the problem without a validation, each stage's σt the same.
TEST_CASE("per sand: each stage's tension tests at the result run with its validation", "[calibrate][validation][tension]") {
    TempDir with_dir("cal-validation-per-sand"), alone_dir("cal-validation-per-sand-alone");
    auto plain = cal::make_analytic_model(2, 0.001);
    const cal::CalibrationProblem joined = cal::load_calibration_problem(
        problem_with_tension(with_dir.path, *plain, "[validation]\nseeds = [11, 12]\n", "per_sand"));
    const cal::CalibrationProblem alone = cal::load_calibration_problem(problem_with_tension(alone_dir.path, *plain, "", "per_sand"));
    const cal::CalibrationResult j = cal::run_calibration(joined, *cal::make_model(joined));
    const cal::CalibrationResult a = cal::run_calibration(alone, *cal::make_model(alone));
    REQUIRE(j.stages.size() == 2);
    REQUIRE(a.stages.size() == 2);
    CHECK(j.runs_used == a.runs_used);
    for (std::size_t k = 0; k < 2; ++k) {
        const cal::CalibrationStage &sj = j.stages[k], &sa = a.stages[k];
        CHECK(sj.solution.best == sa.solution.best);
        CHECK(sj.solution.best_eval.label == "tension at the result");
        REQUIRE(sj.solution.best_eval.sands.size() == 1);
        CHECK(sj.solution.best_eval.sands[0].tension_ok == static_cast<int>(joined.seeds.size()));
        CHECK(sj.solution.best_eval.sands[0].value(cal::Quantity::tension) == sa.solution.best_eval.sands[0].value(cal::Quantity::tension));
        CHECK(sj.uncertainty.std_error_natural == sa.uncertainty.std_error_natural);
        CHECK(sj.validation.evaluation.sands.size() == 1);
    }
}

// run_together hands the executor the runs of several evaluators as one batch, the longest
// expected first (a long run started last keeps the other worker waiting). Oracle: the order is
// the stable sort of the requests by their expected seconds, and each evaluator's evaluation is
// the one it makes of the same point alone.
TEST_CASE("run_together: the longest expected runs first, each outcome to the evaluator that queued it",
          "[calibrate][validation]") {
    TempDir dir("cal-run-together");
    auto plain = cal::make_analytic_model(2, 0.001);
    const cal::CalibrationProblem problem = cal::load_calibration_problem(problem_with_tension(dir.path, *plain, ""));
    const cal::ParameterSpace space(problem.parameters, problem.base.material);
    auto model = cal::make_model(problem);
    RecordingExecutor runs(*model, 2);
    runs.prepare(problem.packing_seeds(), {});
    cal::Ledger ledger(dir.path / "together.sqlite", "together", "together\n");
    cal::Evaluator first(problem, space, runs, ledger, *model), second(problem, space, runs, ledger, *model);
    const std::vector<double> p1 = space.start();
    std::vector<double> p2 = p1;
    p2[0] *= 1.1;
    cal::QueuedRuns a{&first, first.queue({p1}, {0}, "first"), 0, {}};
    cal::QueuedRuns b{&second, second.queue({p2}, {1}, "second"), 0, {}};
    REQUIRE(a.requests.size() >= 3);
    for (std::size_t k = 0; k < a.requests.size(); ++k) a.expected_seconds.push_back(static_cast<double>(k % 3));  // 0 1 2 0 1 2 ...
    b.expected_seconds.assign(b.requests.size(), 1.5);
    cal::run_together(runs, {a, b}, problem.timeout_s);

    // The order: a's 2 s runs, b's 1.5 s, a's 1 s, a's 0 s, each group in queue order.
    std::vector<cal::RunRequest> expected;
    for (double group : {2.0, 1.5, 1.0, 0.0})
        for (const cal::QueuedRuns* q : {&a, &b})
            for (std::size_t k = 0; k < q->requests.size(); ++k)
                if (q->expected_seconds[k] == group) expected.push_back(q->requests[k]);
    REQUIRE(runs.batches.size() == 1);
    const std::vector<cal::RunRequest>& sent = runs.batches.front();
    REQUIRE(sent.size() == expected.size());
    for (std::size_t k = 0; k < sent.size(); ++k) {
        CHECK(sent[k].sand == expected[k].sand);
        CHECK(sent[k].seed == expected[k].seed);
        CHECK(sent[k].test == expected[k].test);
    }

    // Each evaluator got its own outcomes: the evaluations of its point made alone.
    const cal::Evaluation ea = first.collect().front(), eb = second.collect().front();
    cal::ThreadExecutor threads(*model, 1);
    cal::Ledger alone_ledger(dir.path / "alone.sqlite", "alone", "alone\n");
    cal::Evaluator alone(problem, space, threads, alone_ledger, *model);
    const cal::Evaluation ra = alone.evaluate(p1, {0}, "first"), rb = alone.evaluate(p2, {1}, "second");
    for (cal::Quantity q : {cal::Quantity::modulus, cal::Quantity::peak, cal::Quantity::strain}) {
        CHECK(ea.sands.at(0).value(q) == ra.sands.at(0).value(q));
        CHECK(eb.sands.at(0).value(q) == rb.sands.at(0).value(q));
    }
    CHECK(ea.runs.size() + ea.tension_runs.size() == a.requests.size());
    CHECK(first.runs_used() == static_cast<int>(a.requests.size()));
    CHECK(second.runs_used() == static_cast<int>(b.requests.size()));
}

TEST_CASE("bad [validation] tables are refused naming the key, line and rule", "[calibrate][validation]") {
    TempDir dir("cal-validation-bad");
    auto model = cal::make_analytic_model(2, 0.001);
    auto refused = [&](const std::string& table, const std::string& what) {
        INFO(table);
        CHECK_THROWS_WITH(cal::load_calibration_problem(problem_with(dir.path, *model, table)),
                          Catch::Contains("problem.toml:") && Catch::Contains(what));
    };
    refused("[validation]\nseeds = [2, 11]\n", "seed 2 is also a fitted seed");
    refused("[validation]\nedge_mm = 1.0\nseeds = [11]\n", "'validation.edge_mm' = 1.0 violates >= 3 x the largest grain (0.8 mm)");
    refused("[validation]\nedge_mm = 5.0\n", "'validation.seeds' is required");
    refused("[validation]\nseeds = [11]\nedges = 5.0\n", "unknown key 'validation.edges'");
    // tension seeds: validation seeds, and only with a direct-tension target
    refused("[validation]\nseeds = [11]\ntension_seeds = [11]\n", "'validation.tension_seeds' needs a direct-tension target");
    INFO("tension seed not a validation seed");
    CHECK_THROWS_WITH(cal::load_calibration_problem(
                          problem_with_tension(dir.path, *model, "[validation]\nseeds = [11, 12]\ntension_seeds = [13]\n")),
                      Catch::Contains("problem.toml:") && Catch::Contains("'validation.tension_seeds': seed 13 is not a validation seed"));
}

// A fitted strain-at-peak miss with every shape parameter fixed and the strain weight 0 (as in
// the main job): the scales cannot move D, so the statement says the shape is fixed and the
// strain reported, not fitted; it does not call the miss a compromise of the weights.
TEST_CASE("a fitted strain-at-peak miss with the shape fixed is reported, not called a compromise", "[calibrate][validation]") {
    TempDir dir("cal-fixed-shape");
    auto plain = cal::make_analytic_model(2, 0.001);
    write_lab(dir.path, *plain);
    const cal::CalibrationProblem problem = cal::load_calibration_problem(test::write_problem(
        dir.path, "model = \"analytic\"\nbond_model = \"flat_joint\"\nseeds = [1, 2, 3]\n",
        "strain_weight = 0.0\n[solver]\nmethod = \"scaling\"\nmax_runs = 300\ntolerance = 0.002\n"
        "[parameters.cohesion_ratio]\nfree = false\nstart = 2.0\n[parameters.strength_cv]\nfree = false\nstart = 0.2\n"
        "[output]\ndir = \"out\"\n"));
    test::ScaledSpecimenModel bent(1.0, 1.0, 1.3);  // D x 1.3 against the lab's, E and peak as the lab's model
    const cal::CalibrationResult r = cal::run_calibration(problem, bent);
    const nlohmann::json summary = report::summary_json(problem, r);
    const std::vector<std::string> strain_misses = unmet_containing(summary, "strain at peak (fitted)");
    for (const std::string& text : strain_misses) {
        CHECK_THAT(text, Catch::Contains("as the problem fixes them (none is free"));
        CHECK_THAT(text, Catch::Contains("the strain weight is 0, so it is reported, not fitted"));
        CHECK_THAT(text, !Catch::Contains("best compromise"));
    }
    CHECK(strain_misses.size() == 2);
    for (const auto& t : summary["targets"])  // the scales still meet E and peak
        if (t["quantity"] != "strain_at_peak") CHECK(std::fabs(t["rel_error"].get<double>()) < 0.05);
}
