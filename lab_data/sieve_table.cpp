// ASTM C144 limit tables, read with fast-cpp-csv-parser: they have a fixed, named schema, which
// is what it is built for (sieve analyses come in the layouts labs write: sieve_analysis.cpp).
// The CSV_IO_NO_THREAD switch keeps it synchronous (files are tiny); this is the only
// translation unit that includes it.
#define CSV_IO_NO_THREAD
#if defined(__GNUC__) && !defined(__clang__)
// csv.h copies file names with strncpy into a fixed buffer (and terminates them itself);
// GCC's middle end reports that inside this file once inlined.
#pragma GCC diagnostic ignored "-Wstringop-truncation"
#endif
#include <libfccp/csv.h>

#include "lab_data/sieve_table.hpp"

#include <algorithm>

#include "common/input_error.hpp"
#include "lab_data/block_parser.hpp"
#include "lab_data/text.hpp"

namespace gradem::lab {
namespace {

using Reader = io::CSVReader<4, io::trim_chars<' ', '\t'>, io::double_quote_escape<',', '"'>, io::throw_on_overflow,
                             io::empty_line_comment>;

struct Preamble {
    std::string text;  // decoded file text
    std::size_t header_offset = 0;
    unsigned header_line = 1;
    std::vector<MetaEntry> metadata;
};

// Leading "# key: value" and blank lines are metadata; the first other line is the header.
Preamble split_preamble(std::string_view bytes) {
    Preamble p;
    p.text = decode_text(bytes).utf8;
    const auto lines = split_lines(p.text);
    std::size_t i = 0;
    for (; i < lines.size(); ++i) {
        if (is_blank(lines[i])) continue;
        if (trim(lines[i]).front() != '#') break;
        if (auto m = parse_meta_line(lines[i], static_cast<int>(i) + 1, Dialect{})) p.metadata.push_back(*m);
    }
    p.header_line = static_cast<unsigned>(i) + 1;
    p.header_offset = i < lines.size() ? static_cast<std::size_t>(lines[i].data() - p.text.data()) : p.text.size();
    return p;
}

// Runs `body` and converts fast-cpp-csv-parser's exceptions into InputError(file:line).
template <typename Body>
void with_csv_errors(const std::string& file, Reader& reader, Body&& body) {
    try {
        body();
    } catch (const io::error::base& e) {
        const int line = static_cast<int>(reader.get_file_line());
        std::string what = e.what();
        if (dynamic_cast<const io::error::too_few_columns*>(&e)) what = "truncated row: fewer cells than the header";
        else if (dynamic_cast<const io::error::too_many_columns*>(&e)) what = "more cells than the header";
        else if (dynamic_cast<const io::error::escaped_string_not_closed*>(&e)) what = "unterminated quote";
        else if (dynamic_cast<const io::error::header_missing*>(&e)) what = "no header row";
        else if (auto* d = dynamic_cast<const io::error::duplicated_column_in_header*>(&e))
            what = std::string("duplicated column '") + d->column_name + "' in the header";
        throw InputError(file, line, what);
    }
}

double number(const std::string& file, int line, const char* column, const std::string& cell) {
    const auto v = parse_number(cell, Dialect{}, true);
    if (!v) throw InputError(file, line, column_prefix(column) + "'" + cell + "' is not a number");
    return *v;
}

}  // namespace

C144Limits parse_c144_limits(std::string_view bytes, const std::string& file) {
    const Preamble p = split_preamble(bytes);
    C144Limits limits;
    limits.file = file;
    for (const auto& m : p.metadata)
        if (to_lower(m.key) == "provenance" || to_lower(m.key) == "source") limits.provenance = m.value;
    if (p.header_offset >= p.text.size()) throw InputError(file, 1, "file is empty: expected C144 limits (sieve, opening_mm, min_passing_pct, max_passing_pct)");
    Reader reader(file, p.text.data() + p.header_offset, p.text.data() + p.text.size());
    reader.set_file_line(p.header_line - 1);
    std::string sieve, opening, lo, hi;
    with_csv_errors(file, reader, [&] {
        reader.read_header(io::ignore_extra_column, "sieve", "opening_mm", "min_passing_pct", "max_passing_pct");
        while (reader.read_row(sieve, opening, lo, hi)) {
            const int line = static_cast<int>(reader.get_file_line());
            C144Limit l{trim(sieve), number(file, line, "opening_mm", opening) * 1e-3, number(file, line, "min_passing_pct", lo) / 100,
                        number(file, line, "max_passing_pct", hi) / 100, line};
            if (!(l.opening_m > 0) || !(l.min_passing >= 0 && l.min_passing <= l.max_passing && l.max_passing <= 1))
                throw InputError(file, line, "expected opening_mm > 0 and 0 <= min_passing_pct <= max_passing_pct <= 100");
            limits.sieves.push_back(l);
        }
    });
    if (limits.sieves.size() < 2) throw InputError(file, 0, "C144 limits need at least 2 sieves");
    std::sort(limits.sieves.begin(), limits.sieves.end(), [](const auto& a, const auto& b) { return a.opening_m > b.opening_m; });
    return limits;
}

C144Limits read_c144_limits(const std::filesystem::path& path) { return parse_c144_limits(read_file_bytes(path), path.string()); }

}  // namespace gradem::lab
