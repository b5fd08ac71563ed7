// `gradem study <study.toml> [--out DIR] [--workers N] [--plan]`: runs a parameter study
// (calibrate/study/study_kind.hpp lists the kinds) and writes study.json, study.md and runs.csv
// into its output folder, then report.html (reports/html/study_report.py). Milestones go to
// stderr, the answer and the report path to stdout. --plan prints the cost
// (calibrate/study/study_plan.hpp) and stops.
// Under a launcher (mpirun -np N gradem study ..., GRADEM_MPI builds) its cube tests run on that
// job's executor, as for gradem calibrate (calibrate/execution/launch.hpp,
// calibrate/study/study_models.hpp); the answer is the same as with threads.
// Exit status: 0 done, 1 bad input (study, ledger or MPI setup), 2 bad usage, 3 every run failed.
#include <cstdio>
#include <iostream>
#include <memory>
#include <string>
#include <vector>

#include "app/cli.hpp"
#include "app/commands.hpp"
#include "calibrate/execution/launch.hpp"
#include "calibrate/study/study.hpp"
#include "calibrate/study/study_models.hpp"
#include "calibrate/study/study_plan.hpp"
#include "common/text_file.hpp"
#include "reports/html_report.hpp"
#include "reports/study_report.hpp"

namespace gradem::app {
namespace {

struct StudyOptions {
    std::string file, out;
    int workers = 0;
    bool plan = false;
};

cal::StudyConfig load_config(const StudyOptions& o) {
    cal::StudyConfig config = cal::load_study_config(o.file);
    apply_out_option(o.out, config.out_dir, config.ledger);
    if (o.workers) config.workers = o.workers;
    return config;
}

void say(const std::string& line) { std::fprintf(console().notes(), "study: %s\n", line.c_str()); }

/// Runs the study (on `execution`'s executor if given), writes its outputs and the answer.
int study_and_report(const cal::StudyConfig& config, const cal::StudyExecution* execution) {
    const Console& con = console();
    const cal::StudyResult result = cal::run_study(config, say, execution);
    report::write_study_outputs(result);
    if (result.representative) std::fprintf(con.text(), "(the lab data are REPRESENTATIVE, not measurements)\n");
    for (const std::string& v : result.verdict) std::fprintf(con.text(), "%s\n", v.c_str());
    std::fprintf(con.text(), "results in %s\n", config.out_dir.c_str());
    std::fflush(stdout);
    report::write_html_report_or_warn(report::ReportKind::study, config.out_dir, con.announce(), con.notes_stream());
    if (con.json()) Console::print_json(common::read_file_bytes(config.out_dir / "study.json"));
    const bool ran = result.runs_executed + result.runs_from_ledger > 0;
    if (ran && result.runs_failed == result.runs_executed + result.runs_from_ledger) {
        std::fprintf(stderr, "gradem study: every run failed (results in %s)\n", config.out_dir.c_str());
        return common::exit_run_failed;
    }
    return common::exit_success;
}

/// --plan: the cost of the study, on stdout (JSON with --json); no run, no output (the
/// packings it times on are made and cached where none is: calibrate/plan.hpp).
int print_plan(const cal::StudyConfig& config) {
    const Console& con = console();
    if (!con.json()) std::fprintf(con.notes(), "study: planning (the kind's cases on the stand-in, engine timing on the specimens)\n");
    const cal::StudyPlan plan = cal::plan_study(config);
    if (con.json()) Console::print_json(cal::study_plan_json(plan));
    else std::fprintf(con.text(), "%s", cal::study_plan_text(plan).c_str());
    return common::exit_success;
}

class StudyCommand final : public Command {
public:
    void declare(CLI::App& app) override {
        app.add_option("study", o_.file, "study TOML (experiments/studies/*.toml; kinds in experiments/README.md)")
            ->required()
            ->type_name("study.toml");
        app.add_option("--out", o_.out, "result folder (default: the study's output.dir)")->type_name("DIR");
        app.add_option("--workers", o_.workers, "concurrent cube tests, one thread each, 1 to 64 (overrides run.workers)")->check(CLI::Range(1, 64))->type_name("N");
        app.add_flag("--plan", o_.plan,
                     "print the cases, runs, particle-steps and estimated wall time (a second of engine timing per "
                     "case) and stop; genesis and runs are not started");
    }
    int run() override;

private:
    StudyOptions o_;
};

int StudyCommand::run() {
    const StudyOptions& o = o_;
    // Every process reads the study and makes the models of all its cases; on a launched
    // executor the coordinating process prepares them once (packings into the shared cache).
    cal::StudyConfig config;
    cal::StudyModels* models = nullptr;
    const auto make_job = [&](int) {
        config = load_config(o);
        auto all = std::make_unique<cal::StudyModels>(cal::study_problems(config));
        models = all.get();
        inputs_checked();
        return cal::JobModel{std::move(all), config.workers};
    };
    const auto study = [&](cal::CubeModel&, cal::RunExecutor& executor) {
        say("runs on " + executor.describe());
        executor.prepare(config.seeds, say);
        const cal::StudyExecution execution{*models, executor};
        return study_and_report(config, &execution);
    };
    if (const auto status = cal::run_on_launched_executor(make_job, study)) return *status;
    config = load_config(o);
    if (o.plan) return print_plan(config);
    inputs_checked();
    return study_and_report(config, nullptr);
}

}  // namespace

std::unique_ptr<Command> make_study_command() { return std::make_unique<StudyCommand>(); }

}  // namespace gradem::app
