#pragma once
// The commands of `gradem`, one row each: its name, the one-line summary, what --json prints
// and what exit status 3 means for it. The top-level usage (gradem --help) and every command's
// --help are made from these rows and the options each command declares (app/cli.hpp);
// README.md's command list is checked against them (tests/app/check_readme_commands.py).
#include <stdexcept>
#include <string>
#include <string_view>

namespace gradem::app {

struct CommandInfo {
    std::string_view name;
    std::string_view summary;     ///< one line
    std::string_view json;        ///< what --json prints on stdout
    std::string_view run_failed;  ///< what exit status 3 means
};

inline constexpr CommandInfo kCommandTable[] = {
    {"lab", "lab statistics from sieve analyses and load-frame exports (Table 2, Table 4)", "lab_results.json",
     "is not used (lab runs no simulation)"},
    {"specimen", "generate (or show the cached) packing of a cube config", "the packing's description",
     "genesis failed"},
    {"compress", "cube test of a config: load curve, cracks, macro.json", "macro.json",
     "the simulation diverged (its outputs are still written)"},
    {"tension", "direct tension test of a config: tensile strength, sigma_c/sigma_t (into DIR/tension)",
     "tension/macro.json", "the simulation diverged (its outputs are still written)"},
    {"calibrate", "micro-parameters from the lab targets: summary.json, summary.md, curves", "summary.json",
     "every cube test of the calibration failed (its outputs are still written)"},
    {"study", "parameter study of a calibration (its kinds: experiments/README.md): study.json, study.md", "study.json",
     "every run of the study failed (its outputs are still written)"},
    {"report", "(re)make report.html from a command's outputs", "{\"report\": path}",
     "the report could not be made (python3 or matplotlib missing, or the generator failed)"},
    {"quick-cube", "a bonded lattice cube compressed between platens past its peak (engine smoke run)",
     "the stress-strain summary", "the simulation diverged"},
};

/// The row of `name`; std::out_of_range if there is none.
inline const CommandInfo& command_info(std::string_view name) {
    for (const CommandInfo& c : kCommandTable)
        if (c.name == name) return c;
    throw std::out_of_range("no gradem command '" + std::string(name) + "'");
}

}  // namespace gradem::app
