// The format registry's dispatch (detection in row order, then the format's reader) and the
// pieces the formats share (formats/export_format_parts.hpp).
#include "lab_data/export_readers.hpp"

#include "common/input_error.hpp"
#include "lab_data/block_parser.hpp"
#include "lab_data/formats/export_format_parts.hpp"

namespace gradem::lab {

#define GRADEM_EXPORT_FORMAT_SPEC(format, name, alias) extern const ExportFormatSpec format##_format;
GRADEM_EXPORT_FORMATS(GRADEM_EXPORT_FORMAT_SPEC)
#undef GRADEM_EXPORT_FORMAT_SPEC

namespace {

/// The rows of GRADEM_EXPORT_FORMATS, in order.
struct FormatRow {
    ExportFormat format;
    const ExportFormatSpec* spec;
};
#define GRADEM_EXPORT_FORMAT_ROW(format, name, alias) FormatRow{ExportFormat::format, &format##_format},
const auto kFormats = std::to_array({GRADEM_EXPORT_FORMATS(GRADEM_EXPORT_FORMAT_ROW)});
#undef GRADEM_EXPORT_FORMAT_ROW

const ExportFormatSpec& spec_of(ExportFormat format) {
    for (const FormatRow& row : kFormats)
        if (row.format == format) return *row.spec;
    throw std::invalid_argument(std::string("no reader for export format ") + to_string(format));
}

}  // namespace

namespace formats {

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

void read_preamble(RawTable& t, const Lines& lines, std::size_t begin, std::size_t end) {
    for (std::size_t i = begin; i < end; ++i) {
        if (classify_row(lines[i], t.dialect) == RowKind::numeric) continue;
        if (auto m = parse_meta_line(lines[i], static_cast<int>(i) + 1, t.dialect)) t.metadata.push_back(*m);
    }
}

void read_generic(RawTable& t, const Lines& lines, std::size_t start) {
    t.dialect = sniff_dialect(lines);
    const std::size_t header = find_header(lines, start, t.dialect);
    read_preamble(t, lines, 0, header);
    read_blocks(t, lines, header);
}

}  // namespace formats

std::optional<ExportFormat> parse_format_name(std::string_view name) {
    const std::string n = to_lower(trim(name));
    return n.empty() ? ExportFormat::automatic : parse_enum<ExportFormat>(n);
}

ExportFormat detect_export_format(const std::vector<std::string_view>& lines) {
    const Dialect d = sniff_dialect(lines);
    for (const FormatRow& row : kFormats)
        if (row.spec->detect(lines, d)) return row.format;
    return kFormats.back().format;
}

RawTable read_raw_export(std::string_view bytes, const std::string& file, ExportFormat format) {
    RawTable t;
    t.file = file;
    DecodedText text = decode_text(bytes);
    t.encoding = text.encoding;
    if (t.encoding != "utf-8" && t.encoding != "utf-8 (BOM)") t.notes.push_back("text decoded from " + t.encoding);
    const Lines lines = split_lines(text.utf8);
    if (formats::first_nonblank(lines) >= lines.size()) throw InputError(file, 1, "file is empty: expected a load-frame export");
    if (format == ExportFormat::automatic) format = detect_export_format(lines);
    t.format = to_string(format);
    spec_of(format).read(t, lines);
    return t;
}

}  // namespace gradem::lab
