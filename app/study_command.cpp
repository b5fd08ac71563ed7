// `gradem study <study.toml> [--out DIR] [--workers N]`: runs a parameter study
// (calibrate/study_config.hpp lists the kinds) and writes study.json, study.md and runs.csv
// into its output folder. Milestones go to stderr, the answer to stdout.
// Exit codes: 0 done, 2 bad usage, input or ledger, 4 every run failed.
#include <cstdio>
#include <string>
#include <vector>

#include "app/commands.hpp"
#include "calibrate/study.hpp"

namespace gradem::app {
namespace {

struct StudyOptions {
    std::string file, out;
    int workers = 0;
};

StudyOptions parse_study(const std::vector<std::string>& args) {
    StudyOptions o;
    for (std::size_t k = 0; k < args.size(); ++k) {
        auto value = [&]() -> const std::string& {
            if (k + 1 >= args.size()) throw UsageError(args[k] + " needs a value");
            return args[++k];
        };
        if (args[k] == "--out") o.out = value();
        else if (args[k] == "--workers") o.workers = static_cast<int>(parse_int("--workers", value(), 1, 64));
        else if (!args[k].empty() && args[k][0] == '-') throw UsageError("unknown option '" + args[k] + "' for study");
        else if (o.file.empty()) o.file = args[k];
        else throw UsageError("study takes one study file, got '" + o.file + "' and '" + args[k] + "'");
    }
    if (o.file.empty()) throw UsageError("study needs a study file: gradem study <study.toml> [--out DIR] [--workers N]");
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
    const bool ran = result.runs_executed + result.runs_from_ledger > 0;
    return ran && result.runs_failed == result.runs_executed + result.runs_from_ledger ? 4 : 0;
}

}  // namespace gradem::app
