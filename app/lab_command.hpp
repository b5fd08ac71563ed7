#pragma once
// `gradem lab ...`: the command-line entry of the lab-data side (dispatched from app/main.cpp;
// the readers are lab_data's, the writers reports/lab_report.hpp's).

#include <filesystem>
#include <functional>
#include <ostream>
#include <string>
#include <vector>

namespace gradem::lab {

/// Called once the output files are written, with their folder and the stream for messages (the
/// app makes report.html there).
using AfterLabOutputs = std::function<void(const std::filesystem::path& out_dir, std::ostream& out)>;

/// Runs `gradem lab` with `args` (what follows "lab" on the command line). Prints to stdout,
/// errors to stderr as "gradem lab: file:line: what". Returns 0 on success, 1 on bad input,
/// 2 on bad usage. Never throws.
int run_lab_command(const std::vector<std::string>& args, const AfterLabOutputs& after_outputs = {});

/// The usage text printed by --help.
const char* lab_command_usage();

}  // namespace gradem::lab
