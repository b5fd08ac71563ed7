// MTS TestSuite (TW Elite/Essential) CSV: "Key: value" lines (maybe quoted), blank lines, quoted
// names with trailing spaces, a units row, UTF-8 BOM.
#include <array>

#include "lab_data/export_readers.hpp"
#include "lab_data/formats/export_format_parts.hpp"

namespace gradem::lab {
namespace {

bool detect(const Lines& lines, const Dialect& d) {
    static constexpr std::array<const char*, 6> kKeys = {"file path", "test run", "test", "date", "specimen", "station"};
    const std::size_t first = formats::first_nonblank(lines);
    if (first < lines.size()) {
        const std::string t = to_lower(formats::unquoted(lines[first]));
        for (const char* k : kKeys)
            if (t.rfind(k, 0) == 0 && t.find(':') != std::string::npos) return true;
    }
    const std::size_t h = find_header(lines, 0, d);
    if (h >= lines.size()) return false;
    const auto cells = split_cells(lines[h], d.delimiter).cells;
    for (const auto& c : cells)
        if (!is_blank(c.text) && !c.quoted) return false;
    return classify_row(lines[h + 1], d) == RowKind::text;  // quoted names + units row
}

void read(RawTable& t, const Lines& lines) { formats::read_generic(t, lines); }

}  // namespace

extern const ExportFormatSpec mts_testsuite_format = {detect, read};

}  // namespace gradem::lab
