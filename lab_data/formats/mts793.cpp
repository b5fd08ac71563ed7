// MTS 793 specimen.dat: a locale header "MTS793|prog|lang|ver|iDelim|sDecimal|…" giving the
// delimiter and decimal separator, Windows code page text, an operator-information key/value
// block, several data blocks (names + units rows each) whose columns may differ.
#include <string>
#include <vector>

#include "common/input_error.hpp"
#include "lab_data/export_readers.hpp"
#include "lab_data/formats/export_format_parts.hpp"

namespace gradem::lab {
namespace {

using formats::first_nonblank;

bool detect(const Lines& lines, const Dialect&) {
    const std::size_t first = first_nonblank(lines);
    return first < lines.size() && lines[first].substr(0, 7) == "MTS793|";
}

char mts793_delimiter(const std::string& field, const std::string& file) {
    if (field == "0") return ' ';
    if (field == "1") return ',';
    if (field == "2") return '\t';
    throw InputError(file, 1, "MTS793 locale header: iDelim (5th field) = '" + field +
                                  "', expected 0 (space), 1 (comma) or 2 (tab)");
}

/// The '|'-separated fields of the locale header (InputError when it is not one).
std::vector<std::string> locale_fields(const RawTable& t, const Lines& lines) {
    std::vector<std::string> fields;
    std::string_view header = lines.at(first_nonblank(lines));
    if (header.substr(0, 7) != "MTS793|")
        throw InputError(t.file, static_cast<int>(first_nonblank(lines)) + 1,
                         "expected the MTS793 locale header 'MTS793|prog|lang|version|iDelim|sDecimal|...'");
    for (std::size_t start = 0;;) {
        const auto bar = header.find('|', start);
        fields.push_back(trim(header.substr(start, bar == std::string_view::npos ? std::string_view::npos : bar - start)));
        if (bar == std::string_view::npos) break;
        start = bar + 1;
    }
    if (fields.size() < 6)
        throw InputError(t.file, 1, "MTS793 locale header has " + std::to_string(fields.size()) +
                                        " fields, expected 12 (MTS793|prog|lang|version|iDelim|sDecimal|...)");
    return fields;
}

void read(RawTable& t, const Lines& lines) {
    const std::vector<std::string> fields = locale_fields(t, lines);
    t.dialect.delimiter = mts793_delimiter(fields[4], t.file);
    if (fields[5] != "." && fields[5] != ",")
        throw InputError(t.file, 1, "MTS793 locale header: sDecimal (6th field) = '" + fields[5] + "', expected '.' or ','");
    t.dialect.decimal = fields[5][0];
    if (t.dialect.decimal == t.dialect.delimiter)
        throw InputError(t.file, 1, "MTS793 locale header: decimal separator equals the delimiter");
    t.notes.push_back(std::string("MTS793 locale ") + (fields.size() > 2 ? fields[2] : "?") + ": delimiter " +
                      (t.dialect.delimiter == '\t' ? "tab" : t.dialect.delimiter == ' ' ? "space" : "comma") +
                      ", decimal '" + t.dialect.decimal + "'");
    const std::size_t first = find_header(lines, first_nonblank(lines) + 1, t.dialect);
    formats::read_preamble(t, lines, first_nonblank(lines) + 1, first);
    read_blocks(t, lines, first, BlockOptions{.strict_between_blocks = false});
    if (t.blocks > 1) t.notes.push_back(std::to_string(t.blocks) + " data blocks merged, columns matched by name");
}

}  // namespace

extern const ExportFormatSpec mts793_format = {detect, read};

}  // namespace gradem::lab
