// gradem: command-line entry point. Dispatches to the subcommands; every error ends with a
// message on stderr and a non-zero exit code (2 usage or input, 3 a diverged simulation; 5 gradem
// report could not make the report).
#include <cstdio>
#include <iostream>
#include <string>
#include <vector>

#include "app/cli.hpp"
#include "app/commands.hpp"
#include "app/lab_command.hpp"
#include "core/openmp_policy.hpp"

namespace {

constexpr const char* kUsage =
    "usage: gradem <command> [options]\n"
    "commands:\n"
    "  lab <dataset folder | export files...>   lab statistics from sieve and load-frame files\n"
    "  quick-cube [--particles N] [--seed S] [--strain-rate R] [--out DIR]\n"
    "                                          bonded cube compressed to past its peak\n"
    "  specimen <config.toml> [--show]         generate (or show the cached) packing of a config\n"
    "  compress <config.toml> [--out DIR] [--check-rate] [--vtk]\n"
    "                                          cube test of a config: load curve, cracks, macro.json\n"
    "  tension <config.toml> [--out DIR] [--compression MACRO_JSON] [--check-rate] [--vtk]\n"
    "                                          direct tension test of a config: σt, σc/σt (into DIR/tension)\n"
    "  calibrate <config.toml> [--out DIR] [--max-runs N] [--workers N]\n"
    "                                          micro-parameters from the lab targets: summary.json, ...\n"
    "  report <lab|compress|calibrate> <folder>\n"
    "                                          (re)make report.html from a command's outputs\n"
    "  study <study.toml> [--out DIR] [--workers N]\n"
    "                                          parameter study (gradation_effect, resolution, ...)\n"
    "  --help, --version                       (gradem <command> --help: that command's options)\n";

}  // namespace

namespace gradem::app {

std::int64_t parse_int(const std::string& option, const std::string& value, std::int64_t lo,
                       std::int64_t hi) {
    std::size_t used = 0;
    long long v = 0;
    try {
        v = std::stoll(value, &used);
    } catch (const std::exception&) {
        used = 0;
    }
    if (used != value.size() || v < lo || v > hi)
        throw UsageError(option + " = '" + value + "': expected an integer in [" +
                         std::to_string(lo) + ", " + std::to_string(hi) + "]");
    return v;
}

}  // namespace gradem::app

int main(int argc, char** argv) {
    gradem::use_sleeping_openmp_threads(argv);
    const std::vector<std::string> all(argv + 1, argv + argc);
    if (all.empty() || all[0] == "--help" || all[0] == "-h") {
        std::cout << kUsage;
        return all.empty() ? 2 : 0;
    }
    if (all[0] == "--version") {
        std::cout << "gradem " << GRADEM_VERSION << "\n";
        return 0;
    }
    const std::vector<std::string> rest(all.begin() + 1, all.end());
    try {
        if (all[0] == "lab") return gradem::lab::run_lab_command(rest, gradem::app::write_lab_report);
        if (all[0] == "quick-cube") return gradem::app::run_quick_cube(rest);
        if (all[0] == "specimen") return gradem::app::run_specimen(rest);
        if (all[0] == "compress") return gradem::app::run_compress(rest);
        if (all[0] == "calibrate") return gradem::app::run_calibrate(rest);
        if (all[0] == "report") return gradem::app::run_report(rest);
        if (all[0] == "tension") return gradem::app::run_tension(rest);
        if (all[0] == "study") return gradem::app::run_study(rest);
        std::cerr << "gradem: unknown command '" << all[0] << "'\n" << kUsage;
        return 2;
    } catch (const gradem::app::HelpRequested& help) {
        std::cout << help.text;
        return 0;
    } catch (const gradem::app::UsageError& e) {
        std::cerr << "gradem: " << e.what() << "\n";
        return 2;
    } catch (const std::exception& e) {
        std::cerr << "gradem: " << e.what() << "\n";
        return 2;
    }
}
