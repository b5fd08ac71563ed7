#pragma once
// HTML reports: the commands of GRADEM_REPORT_KINDS below end by writing
// report.html next to their CSV/JSON files — one self-contained page (inline SVG figures, inline
// CSS, no external files, opens offline). The page is made from those files only, by the Python
// generator in reports/html/ (matplotlib, run on /usr/bin/python3; embedded in the binary at
// build time, see reports/README.md).
//
// The report is optional: when python3 or matplotlib is missing, or the generator fails, the
// command's other outputs are complete and valid, so the command prints a warning naming what to
// install and keeps its exit status. No report.html is left that does not belong to the files
// next to it: it is written to a temporary file and renamed into place, and a stale one from an
// earlier run is removed when a new one cannot be made.
#include <array>
#include <filesystem>
#include <optional>
#include <ostream>
#include <string>
#include <string_view>
#include <vector>

#include "common/named_enum.hpp"

namespace gradem::report {

// THE list of report kinds: one row each, KIND(<kind>), where <kind> is the command whose output
// folder the report shows and the name `gradem report` takes. A kind is this row plus its
// generator module reports/html/<kind>_report.py (build(out_dir) -> the page; make_report.py
// loads it by name, the build embeds every module of reports/html/), and the command calls
// write_html_report_or_warn(ReportKind::<kind>, ...) (docs/extending.md "A report kind").
// clang-format off
#define GRADEM_REPORT_KINDS(KIND) \
    KIND(lab)                     \
    KIND(compress)                \
    KIND(calibrate)               \
    KIND(study)
// clang-format on

#define GRADEM_REPORT_KIND_ENUMERATOR(name) name,
/// Which command's outputs a report shows, one enumerator per row of GRADEM_REPORT_KINDS.
enum class ReportKind { GRADEM_REPORT_KINDS(GRADEM_REPORT_KIND_ENUMERATOR) };
#undef GRADEM_REPORT_KIND_ENUMERATOR

#define GRADEM_REPORT_KIND_ROW(name) EnumName<ReportKind>{ReportKind::name, #name},
/// The kinds' names (common/named_enum.hpp: to_string, parse_enum<ReportKind>, enum_names).
constexpr auto enum_name_table(ReportKind) { return std::to_array({GRADEM_REPORT_KINDS(GRADEM_REPORT_KIND_ROW)}); }
#undef GRADEM_REPORT_KIND_ROW

/// The interpreter that runs the generator: $GRADEM_PYTHON if set (tests use it to simulate a
/// missing interpreter or library), else /usr/bin/python3.
std::filesystem::path report_python();

enum class ReportStatus {
    written,
    bad_input,           ///< the folder or one of its output files is missing or not as expected
    missing_dependency,  ///< python3 or matplotlib is not installed
    failed,              ///< the generator failed otherwise (a bug: its traceback is in `problem`)
};

struct HtmlReportOutcome {
    ReportStatus status = ReportStatus::failed;
    std::filesystem::path path;  ///< <out_dir>/report.html
    std::string problem;         ///< why no report was written (for people); empty when written
    [[nodiscard]] bool written() const { return status == ReportStatus::written; }
};

/// Makes <out_dir>/report.html from the `kind` command's output files in `out_dir`. Never
/// throws; the outcome says what happened.
HtmlReportOutcome write_html_report(ReportKind kind, const std::filesystem::path& out_dir);

/// The end of a command: writes the report and prints "report: <path>" on `announce`, or a
/// warning on `warn` (stderr unless given) saying why there is none and what to install. Returns
/// whether it was written.
bool write_html_report_or_warn(ReportKind kind, const std::filesystem::path& out_dir, std::ostream& announce);
bool write_html_report_or_warn(ReportKind kind, const std::filesystem::path& out_dir, std::ostream& announce,
                               std::ostream& warn);

}  // namespace gradem::report
