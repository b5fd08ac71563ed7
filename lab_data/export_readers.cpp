#include "lab_data/export_readers.hpp"

#include <array>

#include "common/input_error.hpp"
#include "lab_data/block_parser.hpp"

namespace gradem::lab {
namespace {

constexpr std::size_t kSniffLines = 60;

std::size_t first_nonblank(const Lines& lines) {
    std::size_t i = 0;
    while (i < lines.size() && is_blank(lines[i])) ++i;
    return i;
}

std::string unquoted(std::string_view s) {
    std::string t = trim(s);
    if (t.size() >= 2 && t.front() == '"' && t.back() == '"') t = t.substr(1, t.size() - 2);
    return trim(t);
}

bool is_raw_data_marker(std::string_view line) {
    std::string t = unquoted(line);
    while (!t.empty() && (t.back() == ',' || t.back() == ';' || t.back() == '\t')) t.pop_back();
    return to_lower(trim(t)) == "raw data";
}

bool looks_like_bluehill(const Lines& lines, const Dialect& d) {
    for (std::size_t i = 0; i < lines.size() && i < kSniffLines; ++i) {
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

bool looks_like_testsuite(const Lines& lines, const Dialect& d) {
    static constexpr std::array<const char*, 6> kKeys = {"file path", "test run", "test", "date", "specimen", "station"};
    const std::size_t first = first_nonblank(lines);
    if (first < lines.size()) {
        const std::string t = to_lower(unquoted(lines[first]));
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

void read_preamble(RawTable& t, const Lines& lines, std::size_t begin, std::size_t end) {
    for (std::size_t i = begin; i < end; ++i) {
        if (classify_row(lines[i], t.dialect) == RowKind::numeric) continue;
        if (auto m = parse_meta_line(lines[i], static_cast<int>(i) + 1, t.dialect)) t.metadata.push_back(*m);
    }
}

// MTS TestSuite, Bluehill and plain CSV share one layout: preamble, names (+ units), data.
void read_generic(RawTable& t, const Lines& lines) {
    t.dialect = sniff_dialect(lines);
    std::size_t start = 0;
    if (t.format == to_string(ExportFormat::bluehill)) {
        for (std::size_t i = 0; i < lines.size(); ++i)
            if (is_raw_data_marker(lines[i])) { start = i + 1; break; }
    }
    const std::size_t header = find_header(lines, start, t.dialect);
    read_preamble(t, lines, 0, header);
    read_blocks(t, lines, header);
}

char mts793_delimiter(const std::string& field, const std::string& file) {
    if (field == "0") return ' ';
    if (field == "1") return ',';
    if (field == "2") return '\t';
    throw InputError(file, 1, "MTS793 locale header: iDelim (5th field) = '" + field +
                                  "', expected 0 (space), 1 (comma) or 2 (tab)");
}

void read_mts793(RawTable& t, const Lines& lines) {
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
    read_preamble(t, lines, first_nonblank(lines) + 1, first);
    read_blocks(t, lines, first, BlockOptions{.strict_between_blocks = false});
    if (t.blocks > 1) t.notes.push_back(std::to_string(t.blocks) + " data blocks merged, columns matched by name");
}

}  // namespace

std::optional<ExportFormat> parse_format_name(std::string_view name) {
    const std::string n = to_lower(trim(name));
    return n.empty() ? ExportFormat::automatic : parse_enum<ExportFormat>(n);
}

ExportFormat detect_export_format(const std::vector<std::string_view>& lines) {
    const std::size_t first = first_nonblank(lines);
    if (first < lines.size() && lines[first].substr(0, 7) == "MTS793|") return ExportFormat::mts793;
    const Dialect d = sniff_dialect(lines);
    if (looks_like_bluehill(lines, d)) return ExportFormat::bluehill;
    if (looks_like_testsuite(lines, d)) return ExportFormat::mts_testsuite;
    return ExportFormat::plain_csv;
}

RawTable read_raw_export(std::string_view bytes, const std::string& file, ExportFormat format) {
    RawTable t;
    t.file = file;
    DecodedText text = decode_text(bytes);
    t.encoding = text.encoding;
    if (t.encoding != "utf-8" && t.encoding != "utf-8 (BOM)") t.notes.push_back("text decoded from " + t.encoding);
    const Lines lines = split_lines(text.utf8);
    if (first_nonblank(lines) >= lines.size()) throw InputError(file, 1, "file is empty: expected a load-frame export");
    if (format == ExportFormat::automatic) format = detect_export_format(lines);
    t.format = to_string(format);
    if (format == ExportFormat::mts793) read_mts793(t, lines);
    else read_generic(t, lines);
    return t;
}

}  // namespace gradem::lab
