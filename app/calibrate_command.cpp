// `gradem calibrate <config.toml> [--out DIR] [--max-runs N] [--workers N]`: calibrates the
// problem of a config (calibrate/README.md) and writes summary.json, summary.md,
// convergence.csv and curves.csv into its output folder. Milestones and a progress line with
// an ETA go to stderr; the one-line brief report goes to stdout.
// Under an MPI launcher (mpirun -np N gradem calibrate ..., GRADEM_MPI builds) rank 0 runs the
// calibration and ranks 1..N-1 run the cube tests (calibrate/mpi_executor.hpp); the answer is
// the same as with threads.
// Exit codes: 0 done, 2 bad usage, input, ledger (the ledger is left untouched) or MPI setup,
// 4 the calibration finished but every evaluation failed.
#include <unistd.h>

#include <cmath>
#include <cstdio>
#include <iostream>
#include <stdexcept>
#include <string>
#include <vector>

#include "app/cli.hpp"
#include "app/commands.hpp"
#include "app/mpi_launch.hpp"
#include "calibrate/calibration.hpp"
#ifdef GRADEM_HAVE_MPI
#include "calibrate/mpi_executor.hpp"
#endif
#include "common/clock_text.hpp"
#include "reports/calibration_report.hpp"
#include "reports/html_report.hpp"

namespace gradem::app {
namespace {

using common::clock_text;

struct CalibrateOptions {
    std::string config, out;
    int max_runs = 0, workers = 0;
};

CalibrateOptions parse_calibrate(const std::vector<std::string>& args) {
    CalibrateOptions o;
    CLI::App app{"Calibrate micro-parameters against the lab targets (calibrate/README.md lists the problem keys).", "gradem calibrate"};
    app.add_option("config", o.config, "calibration problem TOML (e.g. calibrate/configs/joint.toml)")->required();
    app.add_option("--out", o.out, "result folder (default: the problem's output.dir); the ledger moves with it unless set");
    app.add_option("--max-runs", o.max_runs, "budget of DEM cube tests (overrides solver.max_runs)")->check(CLI::Range(1, 100000));
    app.add_option("--workers", o.workers, "concurrent cube tests, one thread each (overrides run.workers)")->check(CLI::Range(1, 64));
    parse_command(app, args);
    return o;
}

/// The progress line: rewritten in place on a terminal, one line per run otherwise. The ETA
/// is an upper bound: the budget's remaining runs at the mean run time, `workers` at a time.
void print_progress(const cal::Progress& p) {
    const bool tty = isatty(fileno(stderr)) != 0;
    // No run timed yet (all from the ledger): no estimate.
    const double eta = p.mean_run_s > 0.0 ? p.mean_run_s * (p.max_runs - p.runs_used) / std::max(1, p.workers) : std::nan("");
    std::fprintf(stderr, "%scalibrate: runs %d/%d (%d from ledger)  evaluations %d  best objective %.4g  elapsed %s  ETA <= %s%s",
                 tty ? "\r" : "", p.runs_used, p.max_runs, p.from_ledger, p.evaluations, p.best_objective,
                 clock_text(p.elapsed_s).c_str(), clock_text(eta).c_str(), tty ? "   " : "\n");
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
    if (problem.representative)
        std::fprintf(stderr, "calibrate: the lab data are REPRESENTATIVE, not measurements (see %s)\n", problem.lab_results.c_str());
    const bool tty = isatty(fileno(stderr)) != 0;
    const cal::CalibrationResult result = cal::run_calibration(
        problem, model, executor,
        [tty](const std::string& line) { std::fprintf(stderr, "%scalibrate: %s\n", tty ? "\r" : "", line.c_str()); },
        print_progress);
    if (tty) std::fprintf(stderr, "\n");
    cal::write_calibration_outputs(problem, result);
    std::printf("%s\n", cal::brief_report(problem, result).c_str());
    std::printf("results in %s\n", problem.out_dir.c_str());
    report::write_html_report_or_warn(report::ReportKind::calibrate, problem.out_dir, std::cout);
    std::fflush(stdout);
    bool any_ok = false;
    for (const auto& st : result.stages) any_ok = any_ok || (!st.solution.best.empty() && !st.solution.best_eval.failed);
    return any_ok ? 0 : 4;
}

}  // namespace

int run_calibrate(const std::vector<std::string>& args) {
    const CalibrateOptions o = parse_calibrate(args);
#ifdef GRADEM_HAVE_MPI
    if (cal::mpi::launched()) {
        cal::CalibrationProblem problem;
        return cal::mpi::run_job(
            [&](int) {
                problem = load_problem(o);
                return cal::mpi::JobModel{cal::make_model(problem), problem.workers};
            },
            [&](cal::CubeModel& model, cal::mpi::MpiExecutor& executor) { return calibrate_and_report(problem, model, executor); });
    }
#else
    refuse_mpi_launch_without_mpi();
#endif
    const cal::CalibrationProblem problem = load_problem(o);
    auto model = cal::make_model(problem);
    cal::ThreadExecutor threads(*model, problem.workers);
    return calibrate_and_report(problem, *model, threads);
}

}  // namespace gradem::app
