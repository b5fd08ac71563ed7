// Instron Bluehill 2/3 RawData: optional "Category : Name,value[,unit]" lines, a names row, a
// units row in parentheses, quoted numbers with thousands separators; Bluehill Universal: a
// "Raw Data" marker and "Name (unit)" names.
#include "lab_data/export_readers.hpp"
#include "lab_data/formats/export_format_parts.hpp"

namespace gradem::lab {
namespace {

bool is_raw_data_marker(std::string_view line) {
    std::string t = formats::unquoted(line);
    while (!t.empty() && (t.back() == ',' || t.back() == ';' || t.back() == '\t')) t.pop_back();
    return to_lower(trim(t)) == "raw data";
}

bool detect(const Lines& lines, const Dialect& d) {
    for (std::size_t i = 0; i < lines.size() && i < formats::kSniffLines; ++i) {
        if (is_raw_data_marker(lines[i])) return true;
        const auto cells = split_cells(lines[i], d.delimiter).cells;
        if (cells.size() >= 2 && cells[0].text.find(" : ") != std::string::npos) return true;
        std::size_t nonempty = 0, paren = 0;
        for (const auto& c : cells) {
            const std::string t = trim(c.text);
            if (t.empty()) continue;
            ++nonempty;
            if (t.front() == '(' && t.back() == ')') ++paren;
        }
        if (nonempty >= 2 && paren == nonempty) return true;  // "(sec),(mm),(N)"
    }
    return false;
}

// The table starts after a "Raw Data" marker when there is one.
void read(RawTable& t, const Lines& lines) {
    std::size_t start = 0;
    for (std::size_t i = 0; i < lines.size(); ++i)
        if (is_raw_data_marker(lines[i])) {
            start = i + 1;
            break;
        }
    formats::read_generic(t, lines, start);
}

}  // namespace

extern const ExportFormatSpec bluehill_format = {detect, read};

}  // namespace gradem::lab
