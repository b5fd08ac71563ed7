// `gradem report <lab|compress|calibrate|study> <folder>`: (re)makes report.html from the outputs of
// that command in <folder> — e.g. after installing python3-matplotlib, without re-running a long
// calibration. The commands themselves call the same writer when they finish.
// Exit codes: 0 written, 2 bad usage or a missing/garbled output file, 5 the report could not be
// made (python3 or matplotlib missing, or the generator failed).
#include <filesystem>
#include <iostream>
#include <string>
#include <vector>

#include "app/cli.hpp"
#include "app/commands.hpp"
#include "reports/html_report.hpp"

namespace gradem::app {

int run_report(const std::vector<std::string>& args) {
    std::string kind_name, folder;
    CLI::App app{"(Re)make report.html from the outputs of a command in a folder.", "gradem report"};
    app.add_option("kind", kind_name, "lab, compress, calibrate or study")->required();
    app.add_option("folder", folder, "the command's output folder")->required();
    parse_command(app, args);
    const auto kind = report::parse_report_kind(kind_name);
    if (!kind) throw UsageError("report kind '" + kind_name + "': expected lab, compress, calibrate or study");
    const report::HtmlReportOutcome o = report::write_html_report(*kind, folder);
    if (o.written()) {
        std::cout << "report: " << o.path.lexically_normal().string() << "\n";
        return 0;
    }
    std::cerr << "gradem report: " << o.problem << "\n";
    return o.status == report::ReportStatus::bad_input ? 2 : 5;
}

void write_lab_report(const std::filesystem::path& out_dir, std::ostream& announce) {
    report::write_html_report_or_warn(report::ReportKind::lab, out_dir, announce);
}

}  // namespace gradem::app
