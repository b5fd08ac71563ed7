// `gradem report <lab|compress|calibrate> <folder>`: (re)makes report.html from the outputs of
// that command in <folder> — e.g. after installing python3-matplotlib, without re-running a long
// calibration. The commands themselves call the same writer when they finish.
// Exit codes: 0 written, 2 bad usage or a missing/garbled output file, 5 the report could not be
// made (python3 or matplotlib missing, or the generator failed).
#include <filesystem>
#include <iostream>
#include <string>
#include <vector>

#include "app/commands.hpp"
#include "reports/html_report.hpp"

namespace gradem::app {

int run_report(const std::vector<std::string>& args) {
    constexpr const char* usage = "report needs a kind and a folder: gradem report <lab|compress|calibrate> <folder>";
    if (args.size() != 2) throw UsageError(usage);
    const auto kind = report::parse_report_kind(args[0]);
    if (!kind) throw UsageError("report kind '" + args[0] + "': expected lab, compress or calibrate");
    const report::HtmlReportOutcome o = report::write_html_report(*kind, args[1]);
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
