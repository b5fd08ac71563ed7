#pragma once
// `gradem lab ...`: the command-line entry of the lab-data side (dispatched from app/main.cpp;
// the readers are lab_data's, the writers reports/lab_report.hpp's).

#include <filesystem>
#include <functional>
#include <memory>
#include <ostream>
#include <string>
#include <vector>

namespace gradem::app {

class Command;

/// Called once the output files are written, with their folder and the stream for messages (the
/// app makes report.html there).
using AfterLabOutputs = std::function<void(const std::filesystem::path& out_dir, std::ostream& out)>;

/// Runs `gradem lab` with `args` (what follows "lab" on the command line). Prints to stdout,
/// errors to stderr as "gradem lab: file:line: what". Returns the exit status of
/// common/exit_status.hpp: 0 success, 1 bad input, 2 bad usage. Never throws.
int run_lab_command(const std::vector<std::string>& args, const AfterLabOutputs& after_outputs = {});

/// The lab command for the command table (app/command_table.cpp).
std::unique_ptr<Command> make_lab_command(AfterLabOutputs after_outputs);

}  // namespace gradem::app
