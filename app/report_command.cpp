// `gradem report <kind> <folder>`: (re)makes report.html from the outputs of
// that command in <folder> — e.g. after installing python3-matplotlib, without re-running a long
// calibration. The commands themselves call the same writer when they finish.
// Exit status: 0 written, 1 a missing folder or a missing/garbled output file, 2 bad usage, 3 the
// report could not be made (python3 or matplotlib missing, or the generator failed).
#include <cstdio>
#include <filesystem>
#include <memory>
#include <nlohmann/json.hpp>
#include <iostream>
#include <string>
#include <vector>

#include "app/cli.hpp"
#include "app/commands.hpp"
#include "reports/html_report.hpp"

namespace gradem::app {

namespace {

class ReportCommand final : public Command {
public:
    void declare(CLI::App& app) override {
        app.add_option("kind", kind_, "which command made the folder: " + enum_names_text<report::ReportKind>())
            ->required()
            ->type_name(enum_names_text<report::ReportKind>(NameList::bar));
        app.add_option("folder", folder_, "the command's output folder")->required()->type_name("folder");
    }

    int run() override {
        const Console& con = console();
        const auto kind = parse_enum<report::ReportKind>(kind_);
        if (!kind)
            throw UsageError("report kind '" + kind_ + "': expected one of " + enum_names_text<report::ReportKind>(NameList::bar));
        inputs_checked();
        const report::HtmlReportOutcome o = report::write_html_report(*kind, folder_);
        if (o.written()) {
            const std::string path = o.path.lexically_normal().string();
            std::fprintf(con.text(), "report: %s\n", path.c_str());
            if (con.json()) Console::print_json(nlohmann::ordered_json{{"report", path}}.dump(2));
            return common::exit_success;
        }
        std::fprintf(stderr, "gradem report: %s\n", o.problem.c_str());
        return o.status == report::ReportStatus::bad_input ? common::exit_bad_input : common::exit_run_failed;
    }

private:
    std::string kind_, folder_;
};

}  // namespace

std::unique_ptr<Command> make_report_command() { return std::make_unique<ReportCommand>(); }

void write_lab_report(const std::filesystem::path& out_dir, std::ostream& announce) {
    report::write_html_report_or_warn(report::ReportKind::lab, out_dir, announce);
}

}  // namespace gradem::app
