// `gradem study <study.toml> [--out DIR] [--workers N]`: runs a parameter study
// (calibrate/study_config.hpp lists the kinds) and writes study.json, study.md and runs.csv
// into its output folder, then report.html (reports/html/study_report.py). Milestones go to
// stderr, the answer and the report path to stdout.
// Exit codes: 0 done, 2 bad usage, input or ledger, 4 every run failed.
#include <cstdio>
#include <iostream>
#include <string>
#include <vector>

#include "app/cli.hpp"
#include "app/commands.hpp"
#include "calibrate/study.hpp"
#include "reports/html_report.hpp"
#include "reports/study_report.hpp"

namespace gradem::app {
namespace {

struct StudyOptions {
    std::string file, out;
    int workers = 0;
};

StudyOptions parse_study(const std::vector<std::string>& args) {
    StudyOptions o;
    CLI::App app{"Run a parameter study (experiments/studies/*.toml; kinds in experiments/README.md).", "gradem study"};
    app.add_option("study", o.file, "study TOML")->required();
    app.add_option("--out", o.out, "result folder (default: the study's output.dir)");
    app.add_option("--workers", o.workers, "concurrent cube tests, one thread each")->check(CLI::Range(1, 64));
    parse_command(app, args);
    return o;
}

}  // namespace

int run_study(const std::vector<std::string>& args) {
    const StudyOptions o = parse_study(args);
    cal::StudyConfig config = cal::load_study_config(o.file);
    if (!o.out.empty()) {
        const bool default_ledger = config.ledger == config.out_dir / "ledger.sqlite";
        config.out_dir = o.out;
        if (default_ledger) config.ledger = config.out_dir / "ledger.sqlite";
    }
    if (o.workers) config.workers = o.workers;
    const cal::StudyResult result =
        cal::run_study(config, [](const std::string& line) { std::fprintf(stderr, "study: %s\n", line.c_str()); });
    cal::write_study_outputs(result);
    if (result.representative) std::printf("(the lab data are REPRESENTATIVE, not measurements)\n");
    for (const std::string& v : result.verdict) std::printf("%s\n", v.c_str());
    std::printf("results in %s\n", config.out_dir.c_str());
    std::fflush(stdout);
    report::write_html_report_or_warn(report::ReportKind::study, config.out_dir, std::cout);
    const bool ran = result.runs_executed + result.runs_from_ledger > 0;
    return ran && result.runs_failed == result.runs_executed + result.runs_from_ledger ? 4 : 0;
}

}  // namespace gradem::app
