// Calibration logic on the analytic stand-in: twin experiments (known parameters recovered),
// the homogeneity rescaling, resume after kill -9, and failures as values.
#include <signal.h>
#include <sqlite3.h>
#include <sys/wait.h>
#include <unistd.h>

#include <atomic>
#include <catch2/catch.hpp>
#include <chrono>
#include <cmath>
#include <set>
#include <sstream>
#include <thread>

#include "calibrate/evaluator.hpp"
#include "calibrate/execution/ledger.hpp"
#include "calibrate/objective.hpp"
#include "calibrate/parameters.hpp"
#include "calibrate/problem.hpp"
#include "calibrate_fixture.hpp"
#include "experiments/config/cube_config.hpp"
#include "reports/calibration_report.hpp"

namespace fs = std::filesystem;
using namespace gradem;
using gradem::test::TempDir;

namespace {

const std::vector<std::string> kSands = {"pre-blended", "Van Buren"};
const std::vector<double> kTruth = {20.0, 12.0, 1.6, 0.25};  // E* GPa, σ̄c MPa, c̄/σ̄c, cv (canonical order)

using test::material_at;

/// A twin problem: targets from the analytic model at kTruth over seeds 101-110.
fs::path twin_problem(const fs::path& dir, const cal::CubeModel& model, const std::string& method, int max_runs,
                      const std::string& extra = "") {
    std::vector<std::uint64_t> seeds;
    for (std::uint64_t s = 101; s <= 110; ++s) seeds.push_back(s);
    test::write_text(dir / "lab_results.json", test::synthetic_lab_results(model, kSands, material_at(kTruth), seeds).dump(1));
    return test::write_problem(dir, "seeds = [1, 2, 3]\n",
                               "strain_weight = 1.0\n[solver]\nmethod = \"" + method + "\"\nmax_runs = " + std::to_string(max_runs) +
                                   "\ntolerance = 0.002\n" + extra + "[output]\ndir = \"out\"\n");
}

std::vector<double> best_of(const cal::CalibrationResult& r) { return r.stages.at(0).solution.best; }

void check_recovered(const std::vector<double>& got, double tolerance) {
    REQUIRE(got.size() == kTruth.size());
    for (std::size_t k = 0; k < got.size(); ++k) {
        INFO("parameter " << k << ": " << got[k] << " vs truth " << kTruth[k]);
        CHECK(std::fabs(got[k] / kTruth[k] - 1.0) < tolerance);
    }
}

}  // namespace

TEST_CASE("closed-form rescaling recovers the exact moduli and strength factors", "[calibrate]") {
    cal::CalibrationProblem p;
    p.targets = {{"a", {10e9, 1e9, 3}, {20e6, 1e6, 3}, {0.003, 1e-4, 3}, {}}, {"b", {8e9, 1e9, 3}, {16e6, 1e6, 3}, {0.003, 1e-4, 3}, {}}};
    p.weights = {1.0, 1.0, 0.5};
    // Outputs that are the targets with moduli / 1.7 and strengths / 0.8: α = 1.7, β = 0.8 fit exactly.
    cal::Evaluation e;
    for (std::size_t s = 0; s < 2; ++s) {
        cal::SandOutcome o;
        o.sand = s;
        o.ok = 2;
        o.mean[0] = p.targets[s].modulus.mean / 1.7;
        o.mean[1] = p.targets[s].peak.mean / 0.8;
        o.mean[2] = p.targets[s].strain.mean * 1.7 / 0.8;
        e.sands.push_back(o);
    }
    const cal::Scales sc = cal::best_scales(e, p, true, true);
    CHECK(sc.alpha == Approx(1.7).epsilon(1e-12));
    CHECK(sc.beta == Approx(0.8).epsilon(1e-12));
    CHECK(cal::objective(cal::rescaled(e, sc.alpha, sc.beta), p) < 1e-24);
    // Only the strengths free: β from peak and strain rows, α stays 1.
    const cal::Scales only_strength = cal::best_scales(e, p, false, true);
    CHECK(only_strength.alpha == 1.0);
    CHECK(only_strength.beta < 1.0);
}

TEST_CASE("twin experiment, analytic stand-in: the scaling path recovers known parameters to 1 %", "[calibrate]") {
    TempDir dir("cal-twin-scaling");
    auto model = cal::make_analytic_model(2, 0.001);
    const cal::CalibrationProblem problem = cal::load_calibration_problem(twin_problem(dir.path, *model, "scaling", 400));
    const cal::CalibrationResult r = cal::run_calibration(problem, *model);
    const cal::CalibrationStage& st = r.stages.at(0);
    INFO("runs " << r.runs_used << ", recovered " << best_of(r)[0] << " " << best_of(r)[1] << " " << best_of(r)[2] << " "
                 << best_of(r)[3]);
    CHECK(st.solution.homogeneity.holds);
    CHECK(st.solution.homogeneity.modulus_deviation < 1e-9);  // exactly homogeneous stand-in
    check_recovered(best_of(r), 0.01);
    CHECK(r.runs_used <= 400);
    REQUIRE(st.uncertainty.computed);
    CHECK(st.uncertainty.singular_values.size() == 4);
    for (const auto& row : report::summary_json(problem, r)["targets"]) CHECK(std::fabs(row["rel_error"].get<double>()) < 0.01);
}

TEST_CASE("scaling path with the shape fixed: a rescaled point already on target is the result, without a confirmation run",
          "[calibrate]") {
    TempDir dir("cal-twin-scaling-fixed-shape");
    auto model = cal::make_analytic_model(2, 0.001);
    // The shape at the truth, the scales started 30 % and 20 % off: the exactly homogeneous
    // stand-in puts the rescaled point on the fit, whose own rescaling is then x 1.
    const std::string shape_fixed = "[parameters.cohesion_ratio]\nfree = false\nstart = 1.6\n"
                                    "[parameters.strength_cv]\nfree = false\nstart = 0.25\n"
                                    "[parameters.effective_modulus_gpa]\nstart = 14.0\n"
                                    "[parameters.tensile_strength_mpa]\nstart = 14.4\n";
    const cal::CalibrationProblem problem =
        cal::load_calibration_problem(twin_problem(dir.path, *model, "scaling", 400, shape_fixed));
    const cal::CalibrationResult r = cal::run_calibration(problem, *model);
    const cal::CalibrationStage& st = r.stages.at(0);
    std::vector<std::string> labels;
    for (const cal::Evaluation& e : r.history) labels.push_back(e.label);
    INFO("runs " << r.runs_used);
    CHECK(labels == std::vector<std::string>{"start", "rescaled"});
    CHECK(r.runs_used == 2 * 2 * 3);  // two evaluations of 2 sands x 3 seeds
    const std::vector<double> best = best_of(r);
    CHECK(best[0] == Approx(kTruth[0]).epsilon(0.002));  // the stand-in's seed scatter: seeds 1-3 against the
    CHECK(best[1] == Approx(kTruth[1]).epsilon(0.002));  // targets' 101-110
    bool noted = false;
    for (const std::string& n : st.solution.notes) noted = noted || n.find("the rescaled point is on target") != std::string::npos;
    CHECK(noted);
}

TEST_CASE("twin experiment, analytic stand-in: Ceres LM recovers every parameter, BOBYQA closes in", "[calibrate]") {
    SECTION("ceres") {
        TempDir dir("cal-twin-ceres");
        auto model = cal::make_analytic_model(2, 0.001);
        const cal::CalibrationProblem problem = cal::load_calibration_problem(twin_problem(dir.path, *model, "ceres", 900));
        const cal::CalibrationResult r = cal::run_calibration(problem, *model);
        INFO("stop: " << r.stages[0].solution.stop_reason << ", runs " << r.runs_used);
        check_recovered(best_of(r), 0.01);
        CHECK(r.stages[0].solution.best_objective < 1e-5);
    }
    SECTION("bobyqa on all four parameters: the valley of the strength-stiffness trade-off is slow without the scaling laws") {
        TempDir dir("cal-twin-bobyqa");
        auto model = cal::make_analytic_model(2, 0.001);
        const cal::CalibrationProblem problem = cal::load_calibration_problem(twin_problem(dir.path, *model, "bobyqa", 900));
        const cal::CalibrationResult r = cal::run_calibration(problem, *model);
        const double start = cal::objective(r.history.front(), problem);
        INFO("stop: " << r.stages[0].solution.stop_reason << ", runs " << r.runs_used << ", objective " << start << " -> "
                      << r.stages[0].solution.best_objective);
        CHECK(r.stages[0].solution.best_objective < 0.02 * start);
        for (const auto& row : report::summary_json(problem, r)["targets"])
            if (row["quantity"] != "strain_at_peak") CHECK(std::fabs(row["rel_error"].get<double>()) < 0.05);
    }
}

TEST_CASE("a repeated request is served from the ledger, not run again", "[calibrate]") {
    TempDir dir("cal-ledger-serve");
    auto model = cal::make_analytic_model(2, 0.001);
    const cal::CalibrationProblem problem = cal::load_calibration_problem(twin_problem(dir.path, *model, "scaling", 60));
    const cal::CalibrationResult first = cal::run_calibration(problem, *model);
    REQUIRE(first.runs_executed > 0);
    const cal::CalibrationResult again = cal::run_calibration(problem, *model);
    CHECK(again.runs_executed == 0);
    CHECK(again.runs_from_ledger == first.runs_used);
    CHECK(best_of(again) == best_of(first));  // bitwise: the ledger stores exact doubles
    // What the fit cost (summary.json "runs" "cost" "fit"): every stand-in run is 1000 grains x 1
    // step in 1 ms; the second calibration's runs are the first's, served, so it costs nothing.
    CHECK(first.fit_cost.executed == first.runs_executed);
    CHECK(first.fit_cost.particle_steps == 1000.0 * first.runs_executed);
    CHECK(std::fabs(first.fit_cost.worker_seconds - 1e-3 * first.runs_executed) < 1e-12);
    CHECK(first.fit_cost.from_ledger == 0);
    CHECK(again.fit_cost.executed == 0);
    CHECK(again.fit_cost.particle_steps == 0.0);
    CHECK(again.fit_cost.worker_seconds == 0.0);
    CHECK(again.fit_cost.from_ledger == first.runs_used);
    CHECK(again.fit_cost.ledger_particle_steps == 1000.0 * first.runs_used);
    const nlohmann::json cost = report::summary_json(problem, again)["runs"]["cost"];
    CHECK(cost["fit"]["runs_now"] == 0);
    CHECK(cost["fit"]["from_ledger"] == first.runs_used);
    CHECK(cost["validation"]["runs_now"] == 0);  // no [validation]
}

namespace {

/// The stand-in, slowed down so a calibration can be killed in the middle.
class SlowModel final : public cal::CubeModel {
public:
    explicit SlowModel(std::unique_ptr<cal::CubeModel> inner) : inner_(std::move(inner)) {}
    void prepare(const cal::PackingSeeds& s, int w, const std::function<void(const std::string&)>& l) override { inner_->prepare(s, w, l); }
    cal::RunOutcome run(const cal::RunRequest& q, double t) const override {
        std::this_thread::sleep_for(std::chrono::milliseconds(40));
        return inner_->run(q, t);
    }
    std::string fingerprint() const override { return inner_->fingerprint(); }
    std::string run_fingerprint(cal::CubeTest t) const override { return inner_->run_fingerprint(t); }

private:
    std::unique_ptr<cal::CubeModel> inner_;
};

std::int64_t ledger_rows(const fs::path& path) {
    sqlite3* db = nullptr;
    std::int64_t n = -1;
    // Read-write (no create): after kill -9 mid-commit only a writer may roll the hot journal back.
    if (sqlite3_open_v2(path.c_str(), &db, SQLITE_OPEN_READWRITE, nullptr) == SQLITE_OK) {
        sqlite3_busy_timeout(db, 2000);
        sqlite3_stmt* s = nullptr;
        if (sqlite3_prepare_v2(db, "SELECT COUNT(*) FROM runs", -1, &s, nullptr) == SQLITE_OK && sqlite3_step(s) == SQLITE_ROW)
            n = sqlite3_column_int64(s, 0);
        sqlite3_finalize(s);
    }
    sqlite3_close(db);
    return n;
}

bool ledger_exec(const fs::path& path, const char* sql) {
    sqlite3* db = nullptr;
    bool ok = sqlite3_open_v2(path.c_str(), &db, SQLITE_OPEN_READWRITE, nullptr) == SQLITE_OK &&
              sqlite3_exec(db, sql, nullptr, nullptr, nullptr) == SQLITE_OK;
    sqlite3_close(db);
    return ok;
}

}  // namespace

TEST_CASE("kill -9 in the middle: the resumed calibration repeats no run and reaches the same answer", "[calibrate]") {
    TempDir dir("cal-resume");
    auto model = cal::make_analytic_model(2, 0.001);
    cal::CalibrationProblem problem = cal::load_calibration_problem(twin_problem(dir.path, *model, "scaling", 60));
    // The uninterrupted reference, in its own ledger.
    cal::CalibrationProblem reference = problem;
    reference.ledger = dir.path / "reference.sqlite";
    const cal::CalibrationResult uninterrupted = cal::run_calibration(reference, *model);

    // A child process calibrates slowly; it is killed with SIGKILL once the ledger holds runs.
    const pid_t child = fork();
    REQUIRE(child >= 0);
    if (child == 0) {
        SlowModel slow(cal::make_analytic_model(2, 0.001));
        try {
            cal::run_calibration(problem, slow);
        } catch (...) {
        }
        _exit(0);
    }
    std::int64_t rows = 0;
    for (int k = 0; k < 4000 && rows < 10; ++k) {
        std::this_thread::sleep_for(std::chrono::milliseconds(5));
        if (fs::exists(problem.ledger)) rows = std::max<std::int64_t>(rows, ledger_rows(problem.ledger));
    }
    kill(child, SIGKILL);
    int status = 0;
    waitpid(child, &status, 0);
    REQUIRE(WIFSIGNALED(status));
    const std::int64_t recorded = ledger_rows(problem.ledger);
    REQUIRE(recorded >= 10);
    REQUIRE(recorded < uninterrupted.runs_used);

    const cal::CalibrationResult resumed = cal::run_calibration(problem, *model);
    CHECK(resumed.runs_from_ledger == recorded);
    CHECK(resumed.runs_executed == uninterrupted.runs_used - recorded);
    CHECK(resumed.runs_used == uninterrupted.runs_used);
    CHECK(best_of(resumed) == best_of(uninterrupted));
}

TEST_CASE("a run recorded as timed out runs again once the timeout exceeds its recorded wall time", "[calibrate]") {
    TempDir dir("cal-timeout-rerun");
    auto model = cal::make_analytic_model(2, 0.001);
    cal::CalibrationProblem problem = cal::load_calibration_problem(twin_problem(dir.path, *model, "scaling", 60));
    const cal::ParameterSpace space(problem.parameters, problem.base.material);
    const std::vector<double> x = space.start();  // config units
    const std::vector<std::size_t> sands = {0, 1};
    const fs::path path = dir.path / "timeouts.sqlite";
    int runs = 0;
    {
        cal::Ledger ledger(path, "timeouts", "timeouts");
        cal::Evaluator evaluator(problem, space, *model, ledger);
        REQUIRE_FALSE(evaluator.evaluate(x, sands, "start").failed);
        runs = evaluator.runs_executed();
    }
    REQUIRE(runs == 2 * static_cast<int>(problem.seeds.size()));
    // Every run recorded as a timeout after 5 s.
    REQUIRE(ledger_exec(path, "UPDATE runs SET status = 'timeout', wall_seconds = 5"));
    cal::Ledger ledger(path, "timeouts", "timeouts");
    SECTION("a limit no longer than the recorded wall: served as the timeout it was") {
        problem.timeout_s = 5.0;
        cal::Evaluator evaluator(problem, space, *model, ledger);
        CHECK(evaluator.evaluate(x, sands, "again").failed);
        CHECK(evaluator.runs_from_ledger() == runs);
        CHECK(evaluator.runs_executed() == 0);
    }
    SECTION("a longer limit: run again, and the row replaced") {
        problem.timeout_s = 600.0;
        cal::Evaluator evaluator(problem, space, *model, ledger);
        CHECK_FALSE(evaluator.evaluate(x, sands, "again").failed);
        CHECK(evaluator.runs_executed() == runs);
        CHECK(evaluator.runs_from_ledger() == 0);
        CHECK(ledger_rows(path) == runs);
    }
}

TEST_CASE("a diverging evaluation is a penalty value: the calibration goes on", "[calibrate]") {
    TempDir dir("cal-diverge");
    // Every run with E* above 21 GPa diverges; BOBYQA's first step in E* (0.15 of the unit box
    // from 11 GPa) goes to 22 GPa. The truth, 20 GPa, is below the limit.
    auto model = cal::make_analytic_model(2, 0.001, 21.0);
    const cal::CalibrationProblem problem = cal::load_calibration_problem(twin_problem(dir.path, *model, "bobyqa", 600));
    const cal::CalibrationResult r = cal::run_calibration(problem, *model);
    CHECK(r.runs_failed > 0);
    bool saw_failed_evaluation = false;
    for (const auto& e : r.history) saw_failed_evaluation = saw_failed_evaluation || (e.failed && e.failure.find("diverged") != std::string::npos);
    CHECK(saw_failed_evaluation);
    CHECK_FALSE(r.stages[0].solution.best_eval.failed);
    CHECK(r.stages[0].solution.best_objective < 0.05 * cal::objective(r.history.front(), problem));
    // The failures are in the ledger with their reason.
    sqlite3* db = nullptr;
    REQUIRE(sqlite3_open_v2(problem.ledger.c_str(), &db, SQLITE_OPEN_READONLY, nullptr) == SQLITE_OK);
    sqlite3_stmt* s = nullptr;
    REQUIRE(sqlite3_prepare_v2(db, "SELECT COUNT(*) FROM runs WHERE status = 'diverged' AND reason LIKE 'diverged:%'", -1, &s, nullptr) == SQLITE_OK);
    REQUIRE(sqlite3_step(s) == SQLITE_ROW);
    CHECK(sqlite3_column_int64(s, 0) == r.runs_failed);
    sqlite3_finalize(s);
    sqlite3_close(db);
}

TEST_CASE("study protocol: calibrate on one sand, predict the other", "[calibrate]") {
    TempDir dir("cal-study");
    auto model = cal::make_analytic_model(2, 0.001);
    std::vector<std::uint64_t> seeds = {101, 102, 103};
    test::write_text(dir.path / "lab_results.json", test::synthetic_lab_results(*model, kSands, material_at(kTruth), seeds).dump(1));
    const fs::path cfg = test::write_problem(dir.path, "mode = \"study\"\ncalibrate_on = \"pre-blended\"\nseeds = [1, 2]\n",
                                             "[parameters.cohesion_ratio]\nfree = false\nstart = 1.6\n"
                                             "[parameters.strength_cv]\nfree = false\nstart = 0.25\n"
                                             "[solver]\nmax_runs = 40\n[output]\ndir = \"out\"\n");
    const cal::CalibrationProblem problem = cal::load_calibration_problem(cfg);
    const cal::CalibrationResult r = cal::run_calibration(problem, *model);
    const cal::CalibrationStage& st = r.stages.at(0);
    REQUIRE(st.predicted == std::vector<std::size_t>{1});
    REQUIRE(st.outcome(1) != nullptr);
    // With the true shape parameters fixed, the prediction of the other sand is right too.
    const nlohmann::json j = report::summary_json(problem, r);
    int predicted_rows = 0;
    for (const auto& row : j["targets"])
        if (row["role"] == "predicted") {
            ++predicted_rows;
            CHECK(std::fabs(row["rel_error"].get<double>()) < 0.01);
        }
    CHECK(predicted_rows == 3);
}

TEST_CASE("per sand, four parameters for three targets: the blind direction is named", "[calibrate]") {
    TempDir dir("cal-per-sand");
    auto model = cal::make_analytic_model(2, 0.001);
    test::write_text(dir.path / "lab_results.json",
                     test::synthetic_lab_results(*model, kSands, material_at(kTruth), {101, 102, 103}).dump(1));
    const fs::path cfg = test::write_problem(dir.path, "mode = \"per_sand\"\nseeds = [1, 2]\n", "[solver]\nmax_runs = 200\n[output]\ndir = \"out\"\n");
    const cal::CalibrationProblem problem = cal::load_calibration_problem(cfg);
    const cal::CalibrationResult r = cal::run_calibration(problem, *model);
    REQUIRE(r.stages.size() == 2);
    for (const cal::CalibrationStage& st : r.stages) {
        INFO(st.label << ": " << st.uncertainty.note);
        REQUIRE(st.uncertainty.computed);
        CHECK(st.uncertainty.singular_values.size() == 4);
        CHECK(st.uncertainty.singular_values.back() == 0.0);  // 3 targets cannot fix 4 parameters
        CHECK_FALSE(std::isfinite(st.uncertainty.condition));
        CHECK_FALSE(st.uncertainty.poorly_identified.empty());
        // A fit, not a test: every target of its own sand is met.
        CHECK(st.solution.best_objective < 1e-3);
    }
}

/// A soft-bond twin problem: truth = the PB twin's parameters and ζ = 0.25 (γ fixed at 0.2). In
/// the stand-in ζ raises D = Eε/σ per sand, by a different amount for each, so 6 targets pin
/// down 5 parameters; ζ is the one shape parameter of the scaling path.
static fs::path soft_twin_problem(const fs::path& dir, const cal::CubeModel& model, const std::string& solver_keys,
                                  const std::string& parameter_keys = "") {
    exp::MaterialParams truth = material_at(kTruth);
    truth.bond.model = BondModel::soft_bond;
    truth.bond.law<SoftBondLaw>().softening_factor = 0.25;
    truth.bond.law<SoftBondLaw>().cut_fraction = 0.2;
    std::vector<std::uint64_t> seeds;
    for (std::uint64_t s = 101; s <= 110; ++s) seeds.push_back(s);
    test::write_text(dir / "lab_results.json", test::synthetic_lab_results(model, kSands, truth, seeds).dump(1));
    return test::write_problem(dir, "seeds = [1, 2, 3]\nbond_model = \"soft_bond\"\n",
                               "strain_weight = 1.0\n[parameters.softening_factor]\nfree = true\nstart = 0.6\n"
                               "[parameters.cut_fraction]\nfree = false\nstart = 0.2\n" + parameter_keys +
                               "[solver]\nmethod = \"scaling\"\nmax_runs = 500\n" + solver_keys + "[output]\ndir = \"out\"\n");
}

TEST_CASE("twin experiment, soft bond: the shape search moves the softening factor and recovers it, D is reported", "[calibrate]") {
    TempDir dir("cal-twin-soft");
    auto model = cal::make_analytic_model(2, 0.001);
    const cal::CalibrationProblem problem = cal::load_calibration_problem(soft_twin_problem(dir.path, *model, "tolerance = 0.002\n"));
    REQUIRE(problem.bond_model() == BondModel::soft_bond);
    const cal::ParameterSpace space(problem.parameters, problem.base.material);
    const auto zeta = space.index_of("softening_factor");
    REQUIRE(zeta.has_value());
    CHECK(space.free(*zeta).role() == cal::Role::shape);
    CHECK(space.free(*zeta).log_scale);  // the table's default scale

    const cal::CalibrationResult r = cal::run_calibration(problem, *model);
    const cal::CalibrationStage& st = r.stages.at(0);
    CHECK(st.solution.homogeneity.holds);
    std::set<double> tried;
    for (const cal::Evaluation& e : r.history)
        if (e.label == "shape") tried.insert(e.values[*zeta]);
    CHECK(tried.size() >= 4);  // BOBYQA's shape search varies ζ
    INFO("runs " << r.runs_used << ", ζ " << best_of(r)[*zeta]);
    CHECK(best_of(r)[*zeta] == Approx(0.25).epsilon(0.03));
    const nlohmann::json j = report::summary_json(problem, r);
    CHECK(j["bond_model"] == "soft_bond");
    CHECK(j["bond_model_parameters"]["cut_fraction"].get<double>() == 0.2);
    CHECK(j["bond_model_parameters"]["softening_factor"].get<double>() == best_of(r)[*zeta]);
    REQUIRE(j["shape_index_d"].size() == 2);
    for (std::size_t s = 0; s < 2; ++s) {
        const auto& d = j["shape_index_d"][s];
        const cal::SandTargets& t = problem.targets[s];
        CHECK(d["sand"] == kSands[s]);
        CHECK(d["lab"].get<double>() == Approx(t.modulus.mean * t.strain.mean / t.peak.mean).epsilon(1e-12));
        const cal::SandOutcome* o = st.outcome(s);
        REQUIRE(o != nullptr);
        CHECK(d["simulated"].get<double>() == Approx(o->mean[0] * o->mean[2] / o->mean[1]).epsilon(1e-12));
        CHECK(std::fabs(d["rel_error"].get<double>()) < 0.02);  // the soft bond reaches the lab's D
        CHECK(d["lab"].get<double>() > 1.5);                      // and it is far above the parallel bond's
    }
    const std::string md = report::summary_markdown(problem, r);
    CHECK(md.find("bond model **soft_bond** (bond_replaces_contact = 1, cut_fraction = 0.2, softening_factor = 0.25") != std::string::npos);
    CHECK(md.find("D = E·ε_peak/σ_peak lab") != std::string::npos);
}

TEST_CASE("the uncertainty of a shape parameter reuses a shape-search evaluation: no new runs, the same standard error",
          "[calibrate]") {
    // With the homogeneity verified, a shape-search trial rescaled to the best point's moduli and
    // strengths is a point on the shape column: its secant replaces a new difference point. The
    // oracle: the standard error of ζ from a tiny new forward difference (the derivative), against
    // the one from the reused trial; the stand-in is smooth, so they differ only by curvature.
    // ζ is the only shape parameter (c̄/σ̄c and the scatter fixed at the truth), so every trial
    // lies on its column.
    auto model = cal::make_analytic_model(2, 0.001);
    const std::string fixed = "[parameters.cohesion_ratio]\nfree = false\nstart = 1.6\n[parameters.strength_cv]\nfree = false\nstart = 0.25\n";
    TempDir fresh_dir("cal-reuse-fresh");
    const cal::CalibrationProblem fresh = cal::load_calibration_problem(soft_twin_problem(fresh_dir.path, *model, "fd_step = 1e-4\n", fixed));
    const cal::CalibrationResult r_fresh = cal::run_calibration(fresh, *model);
    const cal::Uncertainty& u_fresh = r_fresh.stages.at(0).uncertainty;
    REQUIRE(u_fresh.computed);
    REQUIRE(u_fresh.reused.empty());  // no trial within [h/2, 3h] of a 1e-4 step
    const int per_eval = static_cast<int>(kSands.size() * 3);
    CHECK(u_fresh.fd_runs == per_eval);

    // The trial nearest the best point, and a difference step of exactly that distance.
    const cal::ParameterSpace space(fresh.parameters, fresh.base.material);
    const std::size_t zeta = *space.index_of("softening_factor");
    const std::vector<double> best = best_of(r_fresh);
    double nearest = 1.0;
    for (const cal::Evaluation& e : r_fresh.history)
        if (e.label == "shape") {
            const double d = std::fabs(space.to_unit(e.values)[zeta] - space.to_unit(best)[zeta]);
            if (d > 1e-6) nearest = std::min(nearest, d);
        }
    REQUIRE(nearest < 0.3);
    const cal::ParameterSpec& spec = space.free(zeta);
    REQUIRE(spec.log_scale);
    const double fd_step = std::expm1(nearest * std::log(spec.upper / spec.lower));  // unit step = nearest

    TempDir reuse_dir("cal-reuse");
    std::ostringstream keys;
    keys.precision(17);
    keys << "fd_step = " << fd_step << "\n";
    const cal::CalibrationProblem reuse = cal::load_calibration_problem(soft_twin_problem(reuse_dir.path, *model, keys.str(), fixed));
    const cal::CalibrationResult r_reuse = cal::run_calibration(reuse, *model);
    const cal::Uncertainty& u_reuse = r_reuse.stages.at(0).uncertainty;
    REQUIRE(u_reuse.computed);
    CHECK(best_of(r_reuse) == best);  // fd_step does not touch the scaling path's solve
    CHECK(u_reuse.fd_runs == 0);
    REQUIRE(u_reuse.reused.size() == 1);
    INFO(u_reuse.reused[0]);
    CHECK(u_reuse.reused[0].rfind("softening_factor: difference point from evaluation ", 0) == 0);
    CHECK(r_reuse.runs_used == r_fresh.runs_used - per_eval);
    INFO("se(ln zeta): derivative " << u_fresh.std_error_natural[zeta] << ", reused secant over " << nearest << " of the box "
                                    << u_reuse.std_error_natural[zeta]);
    CHECK(u_reuse.std_error_natural[zeta] == Approx(u_fresh.std_error_natural[zeta]).epsilon(0.05));
    for (std::size_t k = 0; k < space.size(); ++k)
        if (k != zeta) CHECK(u_reuse.std_error_natural[k] == Approx(u_fresh.std_error_natural[k]).epsilon(0.15));
}
