// The factories of the commands, in the order of app/command_table.hpp (checked at compile
// time), and the top-level usage made from the table and each command's declared options.
#include <iterator>
#include <sstream>

#include "app/commands.hpp"
#include "app/lab_command.hpp"

namespace gradem::app {
namespace {

constexpr CommandFactory kFactories[] = {
    {"lab", [] { return make_lab_command(write_lab_report); }},
    {"specimen", make_specimen_command},
    {"compress", make_compress_command},
    {"tension", make_tension_command},
    {"calibrate", make_calibrate_command},
    {"study", make_study_command},
    {"report", make_report_command},
    {"quick-cube", make_quick_cube_command},
};

constexpr bool factories_match_table() {
    if (std::size(kFactories) != std::size(kCommandTable)) return false;
    for (std::size_t k = 0; k < std::size(kFactories); ++k)
        if (kFactories[k].name != kCommandTable[k].name) return false;
    return true;
}
static_assert(factories_match_table(), "one factory per row of kCommandTable, in its order");

}  // namespace

const CommandFactory* find_command(std::string_view name) {
    for (const CommandFactory& f : kFactories)
        if (f.name == name) return &f;
    return nullptr;
}

std::string top_level_usage() {
    std::ostringstream out;
    out << "usage: gradem <command> [arguments] [options]\n\ncommands:\n";
    for (const CommandFactory& f : kFactories) {
        const CommandInfo& info = command_info(f.name);
        const std::string name(info.name);
        out << "  " << name << std::string(name.size() < 12 ? 12 - name.size() : 1, ' ') << info.summary << "\n";
        const std::string head = "              gradem " + name + " ";
        out << head << cli_detail::wrap(command_synopsis(info, *f.make()), head.size(), head.size()) << "\n";
    }
    out << "\nevery command also takes:\n"
           "  --quiet     print nothing but errors (and the JSON with --json)\n"
           "  --json      print the command's result document on stdout instead of the summary\n"
           "  -h, --help  the command's arguments and options\n"
           "gradem --help prints this text, gradem --version the version.\n\n"
        << common::exit_status_text("a run that failed (a simulation that diverged, a calibration or study whose every run\n"
                                    "  failed, a report that could not be made)");
    return out.str();
}

}  // namespace gradem::app
