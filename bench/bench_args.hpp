#pragma once
// The command-line reading the bench programs share (gradem-bench, gradem-model-sweep,
// gradem-mpi-bench): walk argv option by option, take an option's value from the next argument,
// and read comma lists of numbers, each failure a UsageError naming the option and the text;
// run_main() gives every program the exit status of gradem (common/exit_status.hpp), and
// be_quiet() is every program's --quiet.
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "common/exit_status.hpp"
#include "common/input_error.hpp"
#include "lab_data/lab_warning.hpp"

namespace gradem::bench {

/// Bad usage: an unknown option, a missing or bad value (exit status 2).
struct UsageError : std::invalid_argument {
    using std::invalid_argument::invalid_argument;
};

/// "a,b,,c" -> {"a", "b", "c"} (empty items dropped).
inline std::vector<std::string> split_list(const std::string& text, char separator = ',') {
    std::vector<std::string> out;
    std::stringstream in(text);
    for (std::string item; std::getline(in, item, separator);)
        if (!item.empty()) out.push_back(item);
    return out;
}

/// The whole of `text` as a number (strtod: "1e5", "0.25"); `what` names it in the error.
inline double parse_number(const std::string& text, const std::string& what) {
    char* end = nullptr;
    const double v = std::strtod(text.c_str(), &end);
    if (text.empty() || *end != '\0') throw UsageError(what + ": '" + text + "' is not a number");
    return v;
}

/// A comma list of numbers, each cast to T ("20000,2e5" -> {20000, 200000}).
template <class T>
std::vector<T> parse_number_list(const std::string& text, const std::string& what) {
    std::vector<T> out;
    for (const std::string& item : split_list(text)) out.push_back(static_cast<T>(parse_number(item, what)));
    if (out.empty()) throw UsageError(what + ": expected a comma-separated list of numbers, got '" + text + "'");
    return out;
}

/// Walks argv[1..]: `for (ArgReader args(argc, argv); args.next();)`, then arg() is the current
/// argument and value() consumes the next one as its value.
class ArgReader {
public:
    ArgReader(int argc, char** argv) : argc_(argc), argv_(argv) {}
    bool next() { return ++k_ < argc_ && (current_ = argv_[k_], true); }
    [[nodiscard]] const std::string& arg() const { return current_; }
    std::string value() {
        if (k_ + 1 >= argc_) throw UsageError(current_ + " needs a value");
        return argv_[++k_];
    }

private:
    int argc_;
    char** argv_;
    int k_ = 0;
    std::string current_;
};

/// "  --quiet               ..." for a program's --help; `results` says what is still printed.
inline std::string quiet_help_line(const std::string& results) {
    return "  --quiet               print nothing but errors" + (results.empty() ? std::string() : " and " + results) + "\n";
}

namespace detail {
inline bool& quiet_flag() {
    static bool quiet = false;
    return quiet;
}
}  // namespace detail

/// True after be_quiet().
inline bool quiet() { return detail::quiet_flag(); }

/// --quiet: from now on the program prints nothing but errors and, when `results_are_json`, its
/// JSON results on stdout. The lab readers' warnings (a config's sieve table) and the program's
/// own (warn()) are dropped; a table for people (stdout, `results_are_json` false) goes to
/// /dev/null.
inline void be_quiet(bool results_are_json) {
    detail::quiet_flag() = true;
    lab::warning_sink().start({});
    if (!results_are_json && !std::freopen("/dev/null", "w", stdout)) throw std::runtime_error("--quiet: cannot open /dev/null");
}

/// "<program>: warning: <text>" on stderr, nothing with --quiet.
inline void warn(const char* program, const std::string& text) {
    if (!quiet()) std::fprintf(stderr, "%s: warning: %s\n", program, text.c_str());
}

/// A program's main: returns what `body` returns; an error is "<program>: what" on stderr and
/// exit status 2 (UsageError, with a pointer to --help), 1 (common::InputError: a config or
/// file; std::invalid_argument: a value the work cannot start from) or 3 (any other: the run
/// failed).
template <class Body>
int run_main(const char* program, Body&& body) {
    try {
        return body();
    } catch (const UsageError& e) {
        std::fprintf(stderr, "%s: %s (see %s --help)\n", program, e.what(), program);
        return common::exit_bad_usage;
    } catch (const common::InputError& e) {
        std::fprintf(stderr, "%s: %s\n", program, e.what());
        return common::exit_bad_input;
    } catch (const std::invalid_argument& e) {  // a value the work cannot start from
        std::fprintf(stderr, "%s: %s\n", program, e.what());
        return common::exit_bad_input;
    } catch (const std::exception& e) {
        std::fprintf(stderr, "%s: the run failed: %s\n", program, e.what());
        return common::exit_run_failed;
    }
}

}  // namespace gradem::bench
