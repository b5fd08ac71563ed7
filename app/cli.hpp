#pragma once
// Command-line parsing with CLI11 (Debian libcli11-dev, header-only): every subcommand builds a
// CLI::App with its options and help texts, and parses its arguments through parse_command().
// `--help` / `-h` throws HelpRequested carrying that command's help text (main prints it and
// exits 0); a bad option or value throws UsageError with CLI11's message (exit 2).
#include <CLI/CLI.hpp>
#include <algorithm>
#include <filesystem>
#include <string>
#include <vector>

#include "app/commands.hpp"

namespace gradem::app {

struct HelpRequested {
    std::string text;
};

/// Parses `args` (the words after the command name) with `app`, built as
/// `CLI::App app{"description", "gradem <command>"}` plus its options.
inline void parse_command(CLI::App& app, std::vector<std::string> args) {
    app.get_formatter()->column_width(28);
    std::reverse(args.begin(), args.end());  // CLI11 takes the arguments last-first
    try {
        app.parse(args);
    } catch (const CLI::CallForHelp&) {
        throw HelpRequested{app.help()};
    } catch (const CLI::ParseError& e) {
        throw UsageError(std::string(e.what()) + " (see " + app.get_name() + " --help)");
    }
}

/// `--out DIR` of calibrate and study: the results go to DIR (when given), and so does the
/// ledger unless the file named one of its own (`output.ledger`).
inline void apply_out_option(const std::string& out, std::filesystem::path& out_dir, std::filesystem::path& ledger) {
    if (out.empty()) return;
    const bool default_ledger = ledger == out_dir / "ledger.sqlite";
    out_dir = out;
    if (default_ledger) ledger = out_dir / "ledger.sqlite";
}

}  // namespace gradem::app
