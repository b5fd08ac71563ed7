#pragma once
// The command-line contract of every gradem command. A command is a class (Command) that
// declares its arguments and options on a CLI::App (CLI11, Debian libcli11-dev, header-only)
// and runs once they are parsed; run_command() adds what every command takes (--quiet, --json,
// -h/--help), parses, runs, and turns every error into a message on stderr and the exit status
// of common/exit_status.hpp: 1 bad input (common::InputError, std::invalid_argument, or any
// error before the command said its inputs were checked), 2 bad usage (UsageError, CLI11's parse
// errors), 3 a failed run (the command's own status, or another error after its inputs were
// checked, e.g. genesis diverged). The lab readers' warnings go to the console's notes (stderr,
// none with --quiet). The --help text and
// the top-level usage are made here from the command table (app/command_table.hpp) and the
// declared options, in one style.
#include <CLI/CLI.hpp>
#include <algorithm>
#include <cctype>
#include <filesystem>
#include <iostream>
#include <memory>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "app/command_table.hpp"
#include "app/console.hpp"
#include "common/exit_status.hpp"
#include "common/input_error.hpp"
#include "lab_data/lab_warning.hpp"

namespace gradem::app {

struct UsageError : std::runtime_error {
    using std::runtime_error::runtime_error;
};

class Command {
public:
    virtual ~Command() = default;
    /// Adds the command's arguments and options to `app`, bound to the command's members.
    virtual void declare(CLI::App& app) = 0;
    /// More text for --help, after the options (empty: none).
    [[nodiscard]] virtual std::string details() const { return {}; }
    /// Runs the parsed command; returns its exit status.
    virtual int run() = 0;

    /// From inputs_checked() on, an error other than InputError is a failed run (exit 3).
    [[nodiscard]] bool running() const { return running_; }

protected:
    /// Called once the inputs are read and checked, before the long work.
    void inputs_checked() { running_ = true; }

private:
    bool running_ = false;
};

namespace cli_detail {

inline bool is_help(const CLI::Option& o) { return o.get_name() == "--help"; }
inline bool is_common(const CLI::Option& o) { return o.get_name() == "--quiet" || o.get_name() == "--json"; }

/// "<config.toml>", "<inputs>...", "--out DIR", "--vtk", "--column ROLE=NAME".
inline std::string usage_word(const CLI::Option& o) {
    if (o.get_positional()) {
        const std::string shown = o.get_type_name().empty() || o.get_type_name() == "TEXT" ? o.get_name() : o.get_type_name();
        return "<" + shown + ">" + (o.get_items_expected_max() > 1 ? "..." : "");
    }
    std::string word = o.get_name();
    if (o.get_items_expected_max() > 0) {
        const std::string type = o.get_type_name();  // "N:INT in [1 - 64]" with a check: "N"
        word += " " + type.substr(0, type.find(':'));
    }
    return word;
}

/// Joins the words of one synopsis item so that wrap() keeps them on one line.
constexpr char kGlue = '\x01';

/// `text` wrapped at `width` columns, continuation lines indented by `indent` spaces; words
/// joined with kGlue stay together.
inline std::string wrap(const std::string& text, std::size_t indent, std::size_t first_column, std::size_t width = 100) {
    std::istringstream words(text);
    std::string out, word;
    std::size_t column = first_column;
    bool first = true;
    while (words >> word) {
        if (!first && column + 1 + word.size() > width) {
            out += "\n" + std::string(indent, ' ');
            column = indent;
        } else if (!first) {
            out += ' ';
            ++column;
        }
        out += word;
        column += word.size();
        first = false;
    }
    std::replace(out.begin(), out.end(), kGlue, ' ');
    return out;
}

/// An unknown option among `args` is named before CLI11 would complain about a missing
/// argument instead. ("-1" and the like are values, "--" ends the options.)
inline void refuse_unknown_options(const CLI::App& app, const std::vector<std::string>& args) {
    for (const std::string& a : args) {
        if (a == "--") return;
        const bool option = a.rfind("--", 0) == 0 || (a.size() > 1 && a[0] == '-' && std::isalpha(static_cast<unsigned char>(a[1])));
        if (!option) continue;
        const std::string name = a.substr(0, a.find('='));
        bool known = false;
        for (const CLI::Option* o : app.get_options())
            known = known || o->check_name(name);
        if (!known) throw std::invalid_argument("unknown option '" + name + "'");
    }
}

}  // namespace cli_detail

/// The arguments and options of `app` on one line: "<config.toml> [--out DIR] [--vtk]"; with
/// `common`, --quiet and --json too. The words of one item are joined with kGlue: print it
/// through wrap().
inline std::string synopsis(const CLI::App& app, bool common = false) {
    std::string out;
    for (const CLI::Option* o : app.get_options()) {
        if (cli_detail::is_help(*o) || (!common && cli_detail::is_common(*o))) continue;
        std::string word = cli_detail::usage_word(*o);
        if (!o->get_positional()) {
            const bool repeated = o->get_items_expected_max() > 1;
            if (!o->get_required()) word = "[" + word + "]";
            if (repeated) word += "...";
        }
        std::replace(word.begin(), word.end(), ' ', cli_detail::kGlue);
        out += (out.empty() ? "" : " ") + word;
    }
    return out;
}

/// The app of one command, its options declared: the command's own, then --quiet, --json and
/// -h/--help.
inline std::unique_ptr<CLI::App> make_app(const CommandInfo& info, Command& command, OutputOptions& output) {
    auto app = std::make_unique<CLI::App>(std::string(info.summary), "gradem " + std::string(info.name));
    app->set_help_flag("-h,--help", "show this text");
    command.declare(*app);
    app->add_flag("--quiet", output.quiet, "print nothing but errors (and the JSON with --json)");
    app->add_flag("--json", output.json, "print " + std::string(info.json) + " on stdout instead of the summary");
    return app;
}

/// `gradem <name> --help`: usage line, summary, arguments, options, details, exit status.
inline std::string help_text(const CommandInfo& info, const CLI::App& app, const std::string& details) {
    constexpr std::size_t kColumn = 24;
    std::ostringstream out;
    const std::string head = "usage: gradem " + std::string(info.name) + " ";
    out << head << cli_detail::wrap(synopsis(app, true), head.size(), head.size()) << "\n\n"
        << cli_detail::wrap(std::string(info.summary), 0, 0) << "\n";
    std::string arguments, options, help;
    for (const CLI::Option* o : app.get_options()) {
        std::string left = "  " + (cli_detail::is_help(*o) ? "-h, --help" : cli_detail::usage_word(*o));
        left += left.size() + 2 <= kColumn ? std::string(kColumn - left.size(), ' ') : "\n" + std::string(kColumn, ' ');
        const std::string line = left + cli_detail::wrap(o->get_description(), kColumn, kColumn) + "\n";
        (o->get_positional() ? arguments : cli_detail::is_help(*o) ? help : options) += line;
    }
    options += help;
    if (!arguments.empty()) out << "\narguments:\n" << arguments;
    out << "\noptions:\n" << options;
    if (!details.empty()) out << "\n" << details << (details.back() == '\n' ? "" : "\n");
    out << "\n" << common::exit_status_text(std::string(info.run_failed));
    return out.str();
}

/// The synopsis of a command as the top-level usage shows it (its options declared on a
/// throw-away app).
inline std::string command_synopsis(const CommandInfo& info, Command& command) {
    OutputOptions ignored;
    const auto app = make_app(info, command, ignored);
    return synopsis(*app);
}

/// The lab readers' warnings (rows skipped, nominal specimen dimensions) as notes: one line each
/// on stderr, none with --quiet; each once per command.
inline void route_lab_warnings() {
    lab::warning_sink().start([](const lab::LabWarning& w) { console().notes_stream() << w.line() << '\n'; });
}

/// Parses `args` (the words after the command's name) into `command` and runs it; prints help
/// on stdout and every error on stderr ("gradem <name>: ..."); returns the exit status.
/// Never throws.
inline int run_command(const CommandInfo& info, Command& command, std::vector<std::string> args) {
    const std::string who = "gradem " + std::string(info.name);
    try {
        OutputOptions output;
        const auto app = make_app(info, command, output);
        try {
            cli_detail::refuse_unknown_options(*app, args);
        } catch (const std::invalid_argument& e) {
            throw UsageError(e.what());
        }
        std::reverse(args.begin(), args.end());  // CLI11 takes the arguments last-first
        try {
            app->parse(args);
        } catch (const CLI::CallForHelp&) {
            std::cout << help_text(info, *app, command.details());
            return common::exit_success;
        } catch (const CLI::ParseError& e) {
            throw UsageError(e.what());
        }
        console().configure(output);
        route_lab_warnings();
        return command.run();
    } catch (const UsageError& e) {
        std::cerr << who << ": " << e.what() << " (see " << who << " --help)\n";
        return common::exit_bad_usage;
    } catch (const common::InputError& e) {
        std::cerr << who << ": " << e.what() << "\n";
        return common::exit_bad_input;
    } catch (const std::invalid_argument& e) {  // a value the work cannot start from (e.g. genesis' target)
        std::cerr << who << ": " << e.what() << "\n";
        return common::exit_bad_input;
    } catch (const std::exception& e) {
        std::cerr << who << ": " << (command.running() ? "the run failed: " : "") << e.what() << "\n";
        return command.running() ? common::exit_run_failed : common::exit_bad_input;
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
