#pragma once
// The subcommands of the `gradem` executable. Each takes the arguments after its name and
// returns the process exit code; bad usage throws UsageError (exit 2).
#include <cstdint>
#include <filesystem>
#include <ostream>
#include <stdexcept>
#include <string>
#include <vector>

namespace gradem::app {

struct UsageError : std::runtime_error {
    using std::runtime_error::runtime_error;
};

/// Parses an integer option value in [lo, hi]; UsageError naming the option otherwise.
std::int64_t parse_int(const std::string& option, const std::string& value, std::int64_t lo,
                       std::int64_t hi);

int run_quick_cube(const std::vector<std::string>& args);
int run_specimen(const std::vector<std::string>& args);
int run_compress(const std::vector<std::string>& args);
int run_calibrate(const std::vector<std::string>& args);
int run_study(const std::vector<std::string>& args);
int run_report(const std::vector<std::string>& args);
/// `gradem lab`'s report.html, called by the lab command once its outputs are written.
void write_lab_report(const std::filesystem::path& out_dir, std::ostream& announce);
int run_tension(const std::vector<std::string>& args);

}  // namespace gradem::app
