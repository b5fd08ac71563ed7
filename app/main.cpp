// gradem: command-line entry point. Dispatches to the commands of app/command_table.hpp; every
// error ends with a message on stderr and the exit status of common/exit_status.hpp (0 success,
// 1 bad input, 2 bad usage, 3 a failed run).
#include <iostream>
#include <string>
#include <vector>

#include "app/cli.hpp"
#include "app/commands.hpp"
#include "calibrate/execution/code_version.hpp"
#include "core/openmp_policy.hpp"

int main(int argc, char** argv) {
    using namespace gradem;
    use_sleeping_openmp_threads(argv);
    const std::vector<std::string> all(argv + 1, argv + argc);
    if (all.empty()) {
        std::cerr << app::top_level_usage();
        return common::exit_bad_usage;
    }
    if (all[0] == "--help" || all[0] == "-h") {
        std::cout << app::top_level_usage();
        return common::exit_success;
    }
    if (all[0] == "--version") {
        std::cout << "gradem " << GRADEM_VERSION << " (code " << cal::code_version() << ")\n";
        return common::exit_success;
    }
    const app::CommandFactory* factory = app::find_command(all[0]);
    if (factory == nullptr) {
        std::cerr << "gradem: unknown command '" << all[0] << "' (see gradem --help)\n";
        return common::exit_bad_usage;
    }
    const std::unique_ptr<app::Command> command = factory->make();
    return app::run_command(app::command_info(factory->name), *command, {all.begin() + 1, all.end()});
}
