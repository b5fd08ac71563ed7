#pragma once
// Where a command's output goes, set by --quiet and --json (every command takes both):
//   text()     the summary a command prints for people: stdout; nothing with --json or --quiet
//   notes()    progress lines, milestones and warnings: stderr; nothing with --quiet
//   announce() "report: <path>" and "wrote ...": with the summary, on stderr with --json
//   print_json() the command's result document (--json): stdout, also with --quiet
// Errors are not the console's: run_command() prints them on stderr, always.
#include <cstdio>
#include <iostream>
#include <ostream>
#include <string>

namespace gradem::app {

/// --quiet and --json.
struct OutputOptions {
    bool quiet = false;
    bool json = false;
};

class Console {
public:
    void configure(OutputOptions o) { options_ = o; }
    [[nodiscard]] const OutputOptions& options() const { return options_; }
    [[nodiscard]] bool json() const { return options_.json; }
    [[nodiscard]] bool quiet() const { return options_.quiet; }

    [[nodiscard]] std::FILE* text() const { return options_.quiet || options_.json ? null_file() : stdout; }
    [[nodiscard]] std::FILE* notes() const { return options_.quiet ? null_file() : stderr; }
    [[nodiscard]] std::ostream& text_stream() const { return options_.quiet || options_.json ? null_stream() : std::cout; }
    [[nodiscard]] std::ostream& notes_stream() const { return options_.quiet ? null_stream() : std::cerr; }
    [[nodiscard]] std::ostream& announce() const {
        if (options_.quiet) return null_stream();
        return options_.json ? std::cerr : std::cout;
    }

    /// The result document on stdout (ends with a newline).
    static void print_json(const std::string& document) {
        std::fflush(stdout);
        std::cout << document;
        if (document.empty() || document.back() != '\n') std::cout << '\n';
        std::cout.flush();
    }

private:
    static std::FILE* null_file() {
        static std::FILE* f = std::fopen("/dev/null", "w");
        return f;
    }
    static std::ostream& null_stream() {
        static std::ostream s(nullptr);  // no buffer: every write is dropped
        return s;
    }

    OutputOptions options_;
};

/// The console of the running command.
inline Console& console() {
    static Console c;
    return c;
}

}  // namespace gradem::app
