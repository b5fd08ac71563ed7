#include "lab_data/block_parser.hpp"

#include <algorithm>

#include "common/input_error.hpp"
#include "lab_data/units.hpp"

namespace gradem::lab {
namespace {

std::vector<Cell> drop_trailing_empty(std::vector<Cell> cells) {
    while (!cells.empty() && is_blank(cells.back().text)) cells.pop_back();
    return cells;
}

SplitLine split_checked(const RawTable& t, std::string_view line, int line_number) {
    SplitLine s = split_cells(line, t.dialect.delimiter);
    if (s.unterminated_quote) throw InputError(t.file, line_number, "unterminated quote (a '\"' without its closing '\"')");
    return s;
}

struct BlockHeader {
    std::vector<std::string> names, units, raw;
    int names_line = 0;
    std::size_t first_data = 0;
};

BlockHeader read_header(const RawTable& t, const Lines& lines, std::size_t i) {
    BlockHeader h;
    h.names_line = static_cast<int>(i) + 1;
    for (const Cell& c : drop_trailing_empty(split_checked(t, lines[i], h.names_line).cells)) {
        const NameAndUnit nu = split_name_unit(c.text);
        h.names.push_back(nu.unit.empty() ? trim(c.text) : nu.name);
        h.units.push_back(nu.unit);
        h.raw.push_back(trim(c.text));
    }
    h.first_data = i + 1;
    if (classify_row(lines[i + 1], t.dialect) != RowKind::text) return h;
    // A units row: "(sec),(mm),(N),," or "sec  mm  kN"; it wins over units inside the names.
    const int units_line = static_cast<int>(i) + 2;
    const auto units = drop_trailing_empty(split_checked(t, lines[i + 1], units_line).cells);
    if (units.size() > h.names.size())
        throw InputError(t.file, units_line, "units row has " + std::to_string(units.size()) +
                                                 " entries but the names row (line " + std::to_string(h.names_line) +
                                                 ") has " + std::to_string(h.names.size()));
    for (std::size_t k = 0; k < units.size(); ++k) {
        const std::string u = trim(units[k].text);
        if (!u.empty() && u != "()" && u != "[]") h.units[k] = u;
    }
    h.first_data = i + 2;
    return h;
}

// Index of the table column for (name, unit), creating it (filled with empty cells) if new.
std::size_t column_for(RawTable& t, const std::string& name, const std::string& unit, const std::string& raw, int line) {
    for (std::size_t c = 0; c < t.columns.size(); ++c)
        if (t.columns[c].name == name && t.columns[c].unit == unit) return c;
    RawColumn col{name, raw, unit, line, std::vector<Cell>(t.rows())};
    t.columns.push_back(std::move(col));
    return t.columns.size() - 1;
}

std::string names_list(const BlockHeader& h) {
    std::string s;
    for (const auto& n : h.names) s += (s.empty() ? "" : ", ") + n;
    return s;
}

// Appends the data rows of one block; returns the index of the first line after it.
std::size_t append_rows(RawTable& t, const BlockHeader& h, const Lines& lines, std::size_t i) {
    std::vector<std::size_t> target;
    for (std::size_t k = 0; k < h.names.size(); ++k) {
        if (h.names[k].empty()) { target.push_back(t.columns.size() + 1000000); continue; }  // unnamed: skip
        target.push_back(column_for(t, h.names[k], h.units[k], h.raw[k], h.names_line));
    }
    for (; i < lines.size() && classify_row(lines[i], t.dialect) == RowKind::numeric; ++i) {
        const int line_number = static_cast<int>(i) + 1;
        auto cells = split_checked(t, lines[i], line_number).cells;
        if (cells.size() > h.names.size()) {
            const bool extra_empty = std::all_of(cells.begin() + static_cast<std::ptrdiff_t>(h.names.size()), cells.end(),
                                                 [](const Cell& c) { return is_blank(c.text); });
            if (!extra_empty)
                throw InputError(t.file, line_number, "found " + std::to_string(cells.size()) + " cells, expected " +
                                                          std::to_string(h.names.size()) + " (columns: " + names_list(h) +
                                                          ", from line " + std::to_string(h.names_line) + ")");
            cells.resize(h.names.size());
        }
        if (cells.size() < h.names.size())
            throw InputError(t.file, line_number, "truncated row: found " + std::to_string(cells.size()) +
                                                      " cells, expected " + std::to_string(h.names.size()) +
                                                      " (columns: " + names_list(h) + ")");
        for (auto& col : t.columns) col.cells.emplace_back();
        for (std::size_t k = 0; k < cells.size(); ++k)
            if (target[k] < t.columns.size()) t.columns[target[k]].cells.back() = std::move(cells[k]);
        t.row_line.push_back(line_number);
    }
    ++t.blocks;
    return i;
}

}  // namespace

const MetaEntry* RawTable::find_meta(const std::string& lower_key_part) const {
    for (const auto& m : metadata)
        if (to_lower(m.key).find(lower_key_part) != std::string::npos) return &m;
    return nullptr;
}

RowKind classify_row(std::string_view line, const Dialect& dialect) {
    if (is_blank(line)) return RowKind::blank;
    std::size_t nonempty = 0, numeric = 0;
    for (const Cell& c : split_cells(line, dialect.delimiter).cells) {
        if (is_blank(c.text)) continue;
        ++nonempty;
        if (parse_number(c.text, dialect, c.quoted)) ++numeric;
    }
    if (nonempty == 0) return RowKind::blank;
    if (numeric == 0) return RowKind::text;
    return 2 * numeric > nonempty ? RowKind::numeric : RowKind::mixed;
}

bool is_header_at(const Lines& lines, std::size_t i, const Dialect& dialect) {
    if (i + 1 >= lines.size() || classify_row(lines[i], dialect) != RowKind::text) return false;
    std::size_t named = 0;
    for (const Cell& c : split_cells(lines[i], dialect.delimiter).cells) named += is_blank(c.text) ? 0 : 1;
    if (named < 2) return false;
    const RowKind next = classify_row(lines[i + 1], dialect);
    if (next == RowKind::numeric) return true;
    return next == RowKind::text && i + 2 < lines.size() && classify_row(lines[i + 2], dialect) == RowKind::numeric;
}

std::size_t find_header(const Lines& lines, std::size_t from, const Dialect& dialect) {
    for (std::size_t i = from; i < lines.size(); ++i)
        if (is_header_at(lines, i, dialect)) return i;
    return lines.size();
}

void read_blocks(RawTable& t, const Lines& lines, std::size_t first_header, const BlockOptions& options) {
    if (first_header >= lines.size())
        throw InputError(t.file, 0, "no data block found: expected a names row, an optional units row, then rows of numbers");
    std::size_t i = first_header;
    BlockHeader last = read_header(t, lines, i);
    i = append_rows(t, last, lines, last.first_data);
    while (i < lines.size()) {
        const RowKind kind = classify_row(lines[i], t.dialect);
        if (kind == RowKind::blank) { ++i; continue; }
        if (is_header_at(lines, i, t.dialect)) {
            last = read_header(t, lines, i);
            i = append_rows(t, last, lines, last.first_data);
        } else if (kind == RowKind::numeric) {  // data resumes after a blank line: same header
            t.notes.push_back("data resumed at line " + std::to_string(i + 1) + " after a blank line");
            i = append_rows(t, last, lines, i);
        } else if (options.strict_between_blocks) {
            throw InputError(t.file, static_cast<int>(i) + 1,
                             "row is not data: expected numbers in the columns " + names_list(last) +
                                 " (names row at line " + std::to_string(last.names_line) + ")");
        } else {
            ++i;  // marker or metadata line between blocks
        }
    }
    if (t.rows() == 0)
        throw InputError(t.file, last.names_line, "no data rows after the names row");
}

std::optional<MetaEntry> parse_meta_line(std::string_view raw, int line_number, const Dialect& dialect) {
    std::string line = trim(raw);
    const bool comment = !line.empty() && line.front() == '#';
    if (comment) line = trim(std::string_view(line).substr(1));
    if (line.empty()) return std::nullopt;
    if (comment) {  // "# key: value, more" is one cell: quote it for split_cells
        std::string quoted(1, '"');
        quoted.append(replace_all(line, "\"", "\"\"")).push_back('"');
        line.swap(quoted);
    }
    std::vector<Cell> cells = drop_trailing_empty(split_cells(line, dialect.delimiter).cells);
    cells.erase(std::remove_if(cells.begin(), cells.end(), [](const Cell& c) { return is_blank(c.text); }), cells.end());
    if (cells.empty()) return std::nullopt;
    MetaEntry m;
    m.line = line_number;
    if (cells.size() >= 2) {
        m.key = trim(cells[0].text);
        m.value = trim(cells[1].text);
        if (cells.size() >= 3) m.unit = trim(cells[2].text);
    } else {
        const std::string text = trim(cells[0].text);
        auto sep = text.find(':');
        if (sep == std::string::npos) sep = text.find('=');
        if (sep == std::string::npos) return std::nullopt;
        m.key = trim(std::string_view(text).substr(0, sep));
        m.value = trim(std::string_view(text).substr(sep + 1));
    }
    if (const auto cat = m.key.find(" : "); cat != std::string::npos) m.key = trim(std::string_view(m.key).substr(cat + 3));
    while (!m.key.empty() && (m.key.back() == ':' || m.key.back() == '=')) m.key = trim(std::string_view(m.key).substr(0, m.key.size() - 1));
    const NameAndUnit nu = split_name_unit(m.key);
    if (!nu.unit.empty() && m.unit.empty()) {
        m.key = nu.name;
        m.unit = nu.unit;
    }
    if (m.key.empty()) return std::nullopt;
    return m;
}

}  // namespace gradem::lab
