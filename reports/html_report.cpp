#include "reports/html_report.hpp"

#include <fcntl.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstdlib>
#include <cstring>
#include <fstream>
#include <iostream>
#include <sstream>
#include <system_error>
#include <vector>

#include "common/atomic_file.hpp"
#include "reports/html_report_scripts.hpp"

extern char** environ;

namespace gradem::report {
namespace {

namespace fs = std::filesystem;

// Exit codes of reports/html/make_report.py besides 0 (written).
constexpr int kGeneratorBadInput = 2;      // an output file is missing or not what was expected
constexpr int kGeneratorNoMatplotlib = 3;  // matplotlib (or numpy) cannot be imported
constexpr const char* kInstallHint = "install it with: apt-get install python3-matplotlib (or run scripts/setup.sh)";

/// A fresh scratch folder under the system temp folder, removed when this goes out of scope.
struct ScratchDir {
    fs::path path;
    ScratchDir() {
        std::string pattern = (fs::temp_directory_path() / "gradem-report-XXXXXX").string();
        if (::mkdtemp(pattern.data()) == nullptr)
            throw std::runtime_error("cannot create a scratch folder in " + fs::temp_directory_path().string() + ": " +
                                     std::strerror(errno));
        path = pattern;
    }
    ~ScratchDir() {
        std::error_code ec;
        fs::remove_all(path, ec);
    }
    ScratchDir(const ScratchDir&) = delete;
    ScratchDir& operator=(const ScratchDir&) = delete;
};

/// The environment of the generator: ours, with matplotlib's config/cache in the scratch folder
/// (HOME may be read-only) and its non-interactive backend.
std::vector<std::string> generator_environment(const fs::path& scratch) {
    std::vector<std::string> env;
    for (char** e = environ; e != nullptr && *e != nullptr; ++e) {
        const std::string_view v(*e);
        if (v.starts_with("MPLCONFIGDIR=") || v.starts_with("MPLBACKEND=")) continue;
        env.emplace_back(v);
    }
    env.push_back("MPLCONFIGDIR=" + (scratch / "matplotlib").string());
    env.push_back("MPLBACKEND=Agg");
    return env;
}

std::vector<char*> c_strings(std::vector<std::string>& items) {
    std::vector<char*> out;
    for (std::string& s : items) out.push_back(s.data());
    out.push_back(nullptr);
    return out;
}

/// Runs `argv` with stdout and stderr going to `log`; returns the exit status (-1: not started,
/// 128 + n: killed by signal n).
int run_process(std::vector<std::string> argv, std::vector<std::string> env, const fs::path& log) {
    posix_spawn_file_actions_t actions;
    posix_spawn_file_actions_init(&actions);
    posix_spawn_file_actions_addopen(&actions, STDOUT_FILENO, log.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    posix_spawn_file_actions_adddup2(&actions, STDOUT_FILENO, STDERR_FILENO);
    posix_spawn_file_actions_addclose(&actions, STDIN_FILENO);
    std::vector<char*> args = c_strings(argv), envp = c_strings(env);
    pid_t pid = 0;
    const int rc = ::posix_spawn(&pid, args[0], &actions, nullptr, args.data(), envp.data());
    posix_spawn_file_actions_destroy(&actions);
    if (rc != 0) return -1;
    int status = 0;
    while (::waitpid(pid, &status, 0) < 0)
        if (errno != EINTR) return -1;
    if (WIFEXITED(status)) return WEXITSTATUS(status);
    return WIFSIGNALED(status) ? 128 + WTERMSIG(status) : -1;
}

/// The generator's own message: the last non-empty lines of its log (a traceback ends with the
/// exception), at most `max_lines`.
std::string log_tail(const fs::path& log, std::size_t max_lines = 6) {
    std::ifstream in(log);
    std::vector<std::string> lines;
    for (std::string line; std::getline(in, line);)
        if (!line.empty()) lines.push_back(line);
    std::ostringstream out;
    const std::size_t first = lines.size() > max_lines ? lines.size() - max_lines : 0;
    for (std::size_t i = first; i < lines.size(); ++i) out << (i > first ? "\n  " : "") << lines[i];
    return out.str();
}

HtmlReportOutcome failure(HtmlReportOutcome o, ReportStatus status, std::string problem) {
    o.status = status;
    o.problem = std::move(problem);
    std::error_code ec;
    if (fs::exists(o.path, ec) && fs::remove(o.path, ec)) o.problem += "; the report.html of an earlier run was removed";
    return o;
}

}  // namespace

fs::path report_python() {
    const char* override = std::getenv("GRADEM_PYTHON");
    return override != nullptr && *override != '\0' ? fs::path(override) : fs::path("/usr/bin/python3");
}

HtmlReportOutcome write_html_report(ReportKind kind, const fs::path& out_dir) {
    HtmlReportOutcome o;
    o.path = out_dir / "report.html";
    std::error_code ec;
    if (!fs::is_directory(out_dir, ec)) return failure(o, ReportStatus::bad_input, out_dir.string() + ": no such folder");
    const fs::path python = report_python();
    if (::access(python.c_str(), X_OK) != 0)
        return failure(o, ReportStatus::missing_dependency,
                       python.string() + " not found: the report needs python3 with matplotlib; " + kInstallHint);
    const fs::path temp = out_dir / ("report.html.tmp." + std::to_string(::getpid()));
    try {
        const ScratchDir scratch;
        for (const EmbeddedScript& s : html_report_scripts())
            common::write_file_atomically(scratch.path / std::string(s.name), std::string(s.text));
        const fs::path log = scratch.path / "generator.log";
        const int rc = run_process({python.string(), "-B", "-E", "-s", (scratch.path / "make_report.py").string(), to_string(kind),
                                    out_dir.string(), temp.string()},
                                   generator_environment(scratch.path), log);
        if (rc == 0 && fs::is_regular_file(temp, ec)) {
            fs::rename(temp, o.path, ec);
            if (ec) throw std::runtime_error(o.path.string() + ": cannot move the finished report into place: " + ec.message());
            o.status = ReportStatus::written;
            return o;
        }
        fs::remove(temp, ec);
        if (rc == kGeneratorNoMatplotlib) return failure(o, ReportStatus::missing_dependency, log_tail(log) + "; " + kInstallHint);
        if (rc == -1) return failure(o, ReportStatus::missing_dependency, "cannot run " + python.string() + "; " + kInstallHint);
        if (rc == kGeneratorBadInput) return failure(o, ReportStatus::bad_input, log_tail(log));
        return failure(o, ReportStatus::failed, "the report generator failed (exit " + std::to_string(rc) + "):\n  " + log_tail(log));
    } catch (const std::exception& e) {
        fs::remove(temp, ec);
        return failure(o, ReportStatus::failed, e.what());
    }
}

bool write_html_report_or_warn(ReportKind kind, const fs::path& out_dir, std::ostream& announce) {
    return write_html_report_or_warn(kind, out_dir, announce, std::cerr);
}

bool write_html_report_or_warn(ReportKind kind, const fs::path& out_dir, std::ostream& announce, std::ostream& warn) {
    const HtmlReportOutcome o = write_html_report(kind, out_dir);
    if (o.written()) {
        announce << "report: " << o.path.lexically_normal().string() << "\n";
        return true;
    }
    warn << "gradem: warning: no report.html in " << out_dir.string() << ": " << o.problem << "\n"
              << "gradem: the other results in " << out_dir.string() << " are complete; make the report later with: gradem report "
              << to_string(kind) << " " << out_dir.string() << "\n";
    return false;
}

}  // namespace gradem::report
