// `gradem calibrate <config.toml> [--out DIR] [--max-runs N] [--workers N] [--plan]`: calibrates the
// problem of a config (calibrate/README.md) and writes summary.json, summary.md,
// convergence.csv and curves.csv into its output folder. Milestones and a progress line with
// an ETA go to stderr; the one-line brief report goes to stdout. --plan prints the cost
// (calibrate/plan.hpp) and stops.
// Under a launcher (mpirun -np N gradem calibrate ..., GRADEM_MPI builds) the cube tests run on
// that job's executor (calibrate/execution/launch.hpp; MPI: rank 0 runs the calibration, ranks
// 1..N-1 the cube tests); the answer is the same as with threads.
// Exit status: 0 done, 1 bad input (config, lab results, ledger: the ledger is left untouched;
// or MPI setup), 2 bad usage, 3 the calibration finished but every evaluation failed.
#include <unistd.h>

#include <cmath>
#include <cstdio>
#include <iostream>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include "app/cli.hpp"
#include "app/commands.hpp"
#include "calibrate/calibration.hpp"
#include "calibrate/execution/launch.hpp"
#include "calibrate/plan.hpp"
#include "common/clock_text.hpp"
#include "common/text_file.hpp"
#include "reports/calibration_report.hpp"
#include "reports/html_report.hpp"

namespace gradem::app {
namespace {

using common::clock_text;

struct CalibrateOptions {
    std::string config, out;
    int max_runs = 0, workers = 0;
    bool plan = false;
};

/// The progress line: rewritten in place on a terminal, one line per run otherwise. The ETA
/// (cal::eta_seconds) follows the plan's model (calibrate/plan.hpp): the runs still expected on
/// the solver's path, then the scale-up and validation runs weighted by their cubes' grains and
/// steps, each sand's share at its mean run time so far, `workers` at a time; the budget's
/// remaining runs give the upper bound.
void print_progress(const cal::Progress& p, const cal::ExpectedRuns& expected) {
    std::FILE* notes = console().notes();
    const bool tty = isatty(fileno(notes)) != 0;
    const double eta = cal::eta_seconds(p, expected), eta_max = cal::eta_seconds(p, expected, true);
    std::fprintf(notes, "%scalibrate: runs %d/%d (%d from ledger)  evaluations %d  best objective %.4g  elapsed %s  ETA %s (<= %s)%s",
                 tty ? "\r" : "", p.runs_used, p.max_runs, p.from_ledger, p.evaluations, p.best_objective,
                 clock_text(p.elapsed_s).c_str(), clock_text(eta).c_str(), clock_text(eta_max).c_str(), tty ? "   " : "\n");
}

cal::CalibrationProblem load_problem(const CalibrateOptions& o) {
    cal::CalibrationProblem problem = cal::load_calibration_problem(o.config);
    apply_out_option(o.out, problem.out_dir, problem.ledger);
    if (o.max_runs) problem.solver.max_runs = o.max_runs;
    if (o.workers) problem.workers = o.workers;
    return problem;
}

/// Runs the calibration on `executor`, writes the outputs and the brief report.
int calibrate_and_report(const cal::CalibrationProblem& problem, const cal::CubeModel& model, cal::RunExecutor& executor) {
    const Console& con = console();
    std::FILE* notes = con.notes();
    if (problem.representative)
        std::fprintf(notes, "calibrate: the lab data are REPRESENTATIVE, not measurements (see %s)\n", problem.lab_results.c_str());
    const bool tty = isatty(fileno(notes)) != 0;
    const cal::ExpectedRuns expected = cal::expected_runs(problem);
    const cal::CalibrationResult result = cal::run_calibration(
        problem, model, executor,
        [tty, notes](const std::string& line) { std::fprintf(notes, "%scalibrate: %s\n", tty ? "\r" : "", line.c_str()); },
        [&expected](const cal::Progress& p) { print_progress(p, expected); });
    if (tty) std::fprintf(notes, "\n");
    report::write_calibration_outputs(problem, result);
    std::fprintf(con.text(), "%s\n", report::brief_report(problem, result).c_str());
    std::fprintf(con.text(), "results in %s\n", problem.out_dir.c_str());
    report::write_html_report_or_warn(report::ReportKind::calibrate, problem.out_dir, con.announce(), con.notes_stream());
    std::fflush(stdout);
    if (con.json()) Console::print_json(common::read_file_bytes(problem.out_dir / "summary.json"));
    bool any_ok = false;
    for (const auto& st : result.stages) any_ok = any_ok || (!st.solution.best.empty() && !st.solution.best_eval.failed);
    if (!any_ok) {
        std::fprintf(stderr, "gradem calibrate: every cube test failed (results in %s)\n", problem.out_dir.c_str());
        return common::exit_run_failed;
    }
    return common::exit_success;
}

/// --plan: the cost of the calibration, on stdout (JSON with --json); no run, no output (the
/// packings it times on are made and cached where none is: calibrate/plan.hpp).
int print_plan(const cal::CalibrationProblem& problem) {
    const Console& con = console();
    if (!con.json()) std::fprintf(con.notes(), "calibrate: planning (engine timing on the specimens)\n");
    const cal::CalibrationPlan plan = cal::plan_calibration(problem);
    if (con.json()) Console::print_json(cal::plan_json(plan));
    else std::fprintf(con.text(), "%s", cal::plan_text(plan).c_str());
    return common::exit_success;
}

class CalibrateCommand final : public Command {
public:
    void declare(CLI::App& app) override {
        app.add_option("config", o_.config, "calibration problem TOML (e.g. calibrate/configs/joint.toml)")
            ->required()
            ->type_name("config.toml");
        app.add_option("--out", o_.out, "result folder (default: the problem's output.dir); the ledger moves with it unless set")
            ->type_name("DIR");
        app.add_option("--max-runs", o_.max_runs, "budget of DEM cube tests, 1 to 100000 (overrides solver.max_runs)")
            ->check(CLI::Range(1, 100000))
            ->type_name("N");
        app.add_option("--workers", o_.workers, "concurrent cube tests, one thread each, 1 to 64 (overrides run.workers)")
            ->check(CLI::Range(1, 64))
            ->type_name("N");
        app.add_flag("--plan", o_.plan,
                     "print the runs, particle-steps and estimated wall time (a few seconds of engine timing on the "
                     "specimens) and stop; genesis and runs are not started");
    }
    int run() override;

private:
    CalibrateOptions o_;
};

int CalibrateCommand::run() {
    const CalibrateOptions& o = o_;
    cal::CalibrationProblem problem;
    const auto make_job = [&](int) {
        problem = load_problem(o);
        auto model = cal::make_model(problem);
        inputs_checked();
        return cal::JobModel{std::move(model), problem.workers};
    };
    const auto calibrate = [&](cal::CubeModel& model, cal::RunExecutor& executor) { return calibrate_and_report(problem, model, executor); };
    if (const auto status = cal::run_on_launched_executor(make_job, calibrate)) return *status;
    problem = load_problem(o);
    if (o.plan) return print_plan(problem);
    auto model = cal::make_model(problem);
    inputs_checked();
    cal::ThreadExecutor threads(*model, problem.workers);
    return calibrate_and_report(problem, *model, threads);
}

}  // namespace

std::unique_ptr<Command> make_calibrate_command() { return std::make_unique<CalibrateCommand>(); }

}  // namespace gradem::app
