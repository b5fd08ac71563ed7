#pragma once
// The commands of the `gradem` executable (rows of app/command_table.hpp), each made by its
// factory; `gradem lab`'s is in app/lab_command.hpp.
#include <filesystem>
#include <memory>
#include <ostream>
#include <string>
#include <string_view>

#include "app/cli.hpp"

namespace gradem::app {

std::unique_ptr<Command> make_quick_cube_command();
std::unique_ptr<Command> make_specimen_command();
std::unique_ptr<Command> make_compress_command();
std::unique_ptr<Command> make_tension_command();
std::unique_ptr<Command> make_calibrate_command();
std::unique_ptr<Command> make_study_command();
std::unique_ptr<Command> make_report_command();
/// `gradem lab`'s report.html, called by the lab command once its outputs are written.
void write_lab_report(const std::filesystem::path& out_dir, std::ostream& announce);

/// A command's name (as in the table) and its factory.
struct CommandFactory {
    std::string_view name;
    std::unique_ptr<Command> (*make)();
};

/// The factory of the command `name`, or nullptr.
const CommandFactory* find_command(std::string_view name);

/// The top-level usage (gradem --help, and on stderr for a bare `gradem`): every command of the
/// table with its summary and synopsis, the options every command takes, the exit status.
std::string top_level_usage();

}  // namespace gradem::app
