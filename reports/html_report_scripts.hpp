#pragma once
// The Python files of the HTML report generator (reports/html/*.py), embedded at build time by
// reports/embed_scripts.cmake: write_html_report() writes them to a scratch folder and runs them.
#include <string_view>
#include <vector>

namespace gradem::report {

struct EmbeddedScript {
    std::string_view name;  ///< file name, e.g. "make_report.py"
    std::string_view text;  ///< the file's content
};

const std::vector<EmbeddedScript>& html_report_scripts();

}  // namespace gradem::report
