#pragma once
// The exit status of every gradem command and bench program (README.md "Exit status"), and the
// line every --help ends with.
#include <string>

namespace gradem::common {

enum ExitStatus : int {
    exit_success = 0,
    exit_bad_input = 1,   ///< a file, a config key, a lab file: the message names it (InputError)
    exit_bad_usage = 2,   ///< an unknown option, a missing argument, a bad option value
    exit_run_failed = 3,  ///< the inputs were fine but the run did not complete
};

/// "exit status: 0 success, 1 bad input (...), 2 bad usage (...), 3 <run_failed>", wrapped for a
/// --help text; `run_failed` says what a failed run is for that program.
inline std::string exit_status_text(const std::string& run_failed) {
    return "exit status: 0 success; 1 bad input (a file, config key or lab file: the message names it,\n"
           "  with its line); 2 bad usage (unknown option, missing argument, bad option value);\n"
           "  3 " + run_failed + "\n";
}

}  // namespace gradem::common
