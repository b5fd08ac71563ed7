// Sieve analyses in the layouts labs write (sieve_table.hpp): find the header by its content,
// read the sieve rows, then one analysis per sand from its value columns. Cell meanings
// (header aliases, units, designations) are sieve_layout.*; text, cells and numbers text.*.
#include <algorithm>
#include <cmath>
#include <fstream>
#include <limits>
#include <map>
#include <sstream>

#include "common/input_error.hpp"
#include "lab_data/block_parser.hpp"
#include "lab_data/sieve_layout.hpp"
#include "lab_data/sieve_table.hpp"
#include "lab_data/text.hpp"

namespace gradem::lab {
namespace {

namespace fs = std::filesystem;
using M = SieveMeasure;

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
/// A Total row must match the sum of its column (pan included) within this fraction of it.
constexpr double kTotalTolerance = 0.005;
/// ASTM C136 [check clause]: mass after sieving within 0.3 % of the initial dry mass.
constexpr double kInitialMassTolerance = 0.003;
/// Value columns of one sand must give the same passing within this fraction (1 percentage
/// point: the whole-percent rounding ASTM C136 reports).
constexpr double kColumnAgreement = 0.01;

std::string fmt(double v) {
    std::ostringstream os;
    os.precision(6);
    os << v;
    return os.str();
}

std::string pct(double fraction) { return fmt(fraction * 100) + " %"; }

std::string in_quotes(const std::string& s) { return "'" + s + "'"; }

// ---- The header -----------------------------------------------------------------------------

struct SieveHeader {
    std::size_t index = 0;  // into the lines
    Dialect dialect;
    std::vector<SieveColumn> columns;
    std::size_t cells = 0;  // cells of the header row up to the last non-empty one
    [[nodiscard]] int line() const { return static_cast<int>(index) + 1; }
};

// Sieve columns of line `i` split on `delimiter`; nullopt when it is not a header row (a
// comment, a row with numbers, a row without any sieve column).
std::optional<SieveHeader> columns_at(const Lines& lines, std::size_t i, char delimiter) {
    const std::string first = trim(lines[i]);
    if (first.empty() || first.front() == '#' || !may_hold_sieve_header(first)) return std::nullopt;
    if (classify_row(lines[i], Dialect{delimiter, '.'}) != RowKind::text) return std::nullopt;
    const auto cells = split_cells(lines[i], delimiter).cells;
    if (cells.size() < 2) return std::nullopt;
    SieveHeader h{i, Dialect{delimiter, '.'}, {}, 0};
    for (std::size_t k = 0; k < cells.size(); ++k) {
        if (is_blank(cells[k].text)) continue;
        h.cells = k + 1;
        if (auto c = classify_sieve_header(cells[k].text, k)) h.columns.push_back(*c);
    }
    if (h.columns.empty()) return std::nullopt;
    return h;
}

bool complete(const SieveHeader& h) {
    auto has = [&](auto&& pred) { return std::any_of(h.columns.begin(), h.columns.end(), pred); };
    return has([](auto& c) { return c.identifies_sieve(); }) && has([](auto& c) { return !c.identifies_sieve() && !c.limit; });
}

// A header naming a value column or a "sieve" column, even if the table lacks the rest.
bool sieve_like(const SieveHeader& h) {
    return std::any_of(h.columns.begin(), h.columns.end(), [](const SieveColumn& c) {
        return !c.identifies_sieve() || to_lower(c.header).find("sieve") != std::string::npos;
    });
}

struct HeaderSearch {
    std::optional<SieveHeader> complete, partial;  // the first complete and the first sieve-like header
};

/// From line `from` on, the first complete header (tab, ';' then ',' tried per line) and the
/// first sieve-like one before it; with `stop_at_partial`, stops at the first sieve-like one.
HeaderSearch find_sieve_header(const Lines& lines, std::size_t from, bool stop_at_partial = false) {
    HeaderSearch found;
    for (std::size_t i = from; i < lines.size(); ++i)
        for (char d : {'\t', ';', ','}) {
            auto h = columns_at(lines, i, d);
            if (!h) continue;
            if (!found.partial && sieve_like(*h)) found.partial = h;
            if (complete(*h)) { found.complete = std::move(h); return found; }
            if (stop_at_partial && found.partial) return found;
        }
    return found;
}

// Decimal separator sniffed (text.hpp) over the rows below the header that split like it.
void sniff_decimal(SieveHeader& h, const Lines& lines) {
    const std::size_t n = split_cells(lines[h.index], h.dialect.delimiter).cells.size();
    std::vector<std::string_view> table;
    for (std::size_t i = h.index; i < lines.size(); ++i)
        if (split_cells(lines[i], h.dialect.delimiter).cells.size() == n) table.push_back(lines[i]);
    const Dialect d = sniff_dialect(table);
    if (d.delimiter == h.dialect.delimiter) h.dialect.decimal = d.decimal;
}

// A units row right below the header ("", "(mm)", "(%)"): re-reads the columns with its units.
// Returns the index of the first data line.
std::size_t apply_units_row(SieveHeader& h, const Lines& lines) {
    const std::size_t next = h.index + 1;
    if (next >= lines.size() || classify_row(lines[next], h.dialect) != RowKind::text) return next;
    const auto units = split_cells(lines[next], h.dialect.delimiter).cells;
    std::size_t named = 0;
    auto no_unit = [](const Cell& u) { const std::string t = trim(u.text); return t.empty() || t == "-" || t == "()" || t == "[]"; };
    for (const Cell& u : units) {
        if (no_unit(u)) continue;
        if (!is_sieve_unit(u.text)) return next;
        ++named;
    }
    if (named == 0) return next;
    for (SieveColumn& c : h.columns)
        if (c.index < units.size() && !no_unit(units[c.index])) c = *classify_sieve_header(c.header, c.index, units[c.index].text);
    return next + 1;
}

// Columns the reader cannot use, and two columns for the same sieve role, are refused here.
void check_header(const SieveHeader& h, const std::string& file) {
    const SieveColumn* seen[2] = {nullptr, nullptr};  // designation, opening
    for (const SieveColumn& c : h.columns) {
        if (!c.problem.empty() && !c.limit) throw InputError(file, h.line(), column_prefix(c.header) + c.problem);
        if (!c.identifies_sieve()) continue;
        const SieveColumn*& other = seen[c.measure == M::opening ? 1 : 0];
        if (other)
            throw InputError(file, h.line(), "columns " + in_quotes(other->header) + " and " + in_quotes(c.header) +
                                                 " both name the sieves: keep one");
        other = &c;
    }
}

// ---- The rows -------------------------------------------------------------------------------

struct TableRow {
    SieveRowKind kind = SieveRowKind::sieve;
    double opening_m = 0;
    std::string designation;
    int line = 0;
    std::vector<Cell> cells;
    bool has_numbers = false;  // in a value column
};

struct SieveTable {
    std::string file;
    SieveHeader header;
    std::vector<MetaEntry> metadata;
    std::vector<TableRow> sieves;           // coarsest first
    std::optional<TableRow> pan, total;
    int last_line = 0;                      // last line of the table
    int end_line = 0;                       // the line that ends the table (0: the file does)
    std::vector<int> sieve_rows_after;      // lines below the end that name a sieve: not read
};

std::string cell_text(const std::vector<Cell>& cells, std::size_t k) { return k < cells.size() ? trim(cells[k].text) : ""; }

BareNumbers bare_numbers_of(const SieveColumn& c) {
    if (c.measure == M::opening) return {false, c.to_si};
    return {c.bare_numbers_are_us_sieves, 0};
}

struct RowIdentity {
    std::optional<SieveDesignation> id;
    std::string written;  // the sieve cell `id` comes from, as written (for messages)
    std::string label;    // the designation as written
    bool empty = true;    // no sieve cell holds text
};

// The sieve a row is for: the opening column's number, else a designation in either column;
// a Pan or Total in either wins.
RowIdentity identify_row(const std::vector<Cell>& cells, const SieveHeader& h) {
    RowIdentity r;
    std::vector<RowIdentity> read;  // per sieve column with text
    for (const SieveColumn& c : h.columns) {
        if (!c.identifies_sieve()) continue;
        const std::string text = cell_text(cells, c.index);
        if (text.empty()) continue;
        r.empty = false;
        const auto number = c.measure == M::opening ? parse_number(text, h.dialect, cells[c.index].quoted) : std::nullopt;
        if (c.measure == M::designation || (!number && r.label.empty())) r.label = text;
        RowIdentity one;
        one.id = number ? SieveDesignation{SieveRowKind::sieve, *number * c.to_si, {}} : parse_sieve_designation(text, h.dialect, bare_numbers_of(c));
        one.written = text;
        read.insert(c.measure == M::opening ? read.begin() : read.end(), one);  // the opening column first
    }
    auto usable = [](const RowIdentity& x) { return x.id && x.id->problem.empty(); };
    auto pick = [&](auto&& pred) { return std::find_if(read.begin(), read.end(), pred); };
    auto it = pick([&](const RowIdentity& x) { return usable(x) && x.id->kind != SieveRowKind::sieve; });
    if (it == read.end()) it = pick(usable);
    if (it == read.end()) it = pick([](const RowIdentity& x) { return x.id.has_value(); });
    if (it == read.end() && !read.empty()) it = read.begin();
    if (it != read.end()) r.id = it->id, r.written = it->written;
    return r;
}

bool holds_number(const std::vector<Cell>& cells, const SieveHeader& h) {
    for (const SieveColumn& c : h.columns) {
        if (c.identifies_sieve() || c.limit) continue;
        std::string t = cell_text(cells, c.index);
        if (!t.empty() && t.back() == '%') t.pop_back();
        if (parse_number(t, h.dialect, c.index < cells.size() && cells[c.index].quoted)) return true;
    }
    return false;
}

// Cells a sieve row must have (up to the last column read) and may have (up to the header's).
void check_cell_count(const std::vector<Cell>& cells, const SieveHeader& h, const std::string& file, int line) {
    std::size_t needed = 0;
    for (const SieveColumn& c : h.columns) needed = c.limit ? needed : std::max(needed, c.index + 1);
    if (cells.size() < needed)
        throw InputError(file, line, "truncated row: found " + std::to_string(cells.size()) + " cells, expected " +
                                         std::to_string(needed) + " (header at line " + std::to_string(h.line()) + ")");
    for (std::size_t k = h.cells; k < cells.size(); ++k)
        if (!is_blank(cells[k].text))
            throw InputError(file, line, "more cells than the header (line " + std::to_string(h.line()) + "): " +
                                             in_quotes(trim(cells[k].text)) + " has no column");
}

// One table row, or nullopt at the end of the table (a row naming no sieve, with no number).
std::optional<TableRow> read_row(const std::vector<Cell>& cells, const SieveHeader& h, const std::string& file, int line) {
    RowIdentity r = identify_row(cells, h);
    const bool numbers = holds_number(cells, h);
    if (!r.id && !numbers) return std::nullopt;
    if (r.empty) r.id = SieveDesignation{SieveRowKind::pan, 0, {}};  // a row without sieve name: the pan
    if (!r.id)
        throw InputError(file, line, in_quotes(r.written) + " is not a sieve: expected " + accepted_sieve_designations());
    if (!r.id->problem.empty()) throw InputError(file, line, in_quotes(r.written) + " " + r.id->problem);
    if (r.id->kind == SieveRowKind::sieve) {
        check_cell_count(cells, h, file, line);
        if (!(r.id->opening_m > 0)) throw InputError(file, line, "sieve " + in_quotes(r.written) + ": the opening must be > 0");
    }
    return TableRow{r.id->kind, r.id->opening_m, r.label, line, cells, numbers};
}

// Adds a row to the table; a second Pan or Total row is an error.
void add_row(SieveTable& t, TableRow row) {
    if (row.kind == SieveRowKind::sieve) { t.sieves.push_back(std::move(row)); return; }
    auto& slot = row.kind == SieveRowKind::pan ? t.pan : t.total;
    const char* name = row.kind == SieveRowKind::pan ? "Pan" : "Total";
    if (slot) throw InputError(t.file, row.line, std::string("a second '") + name + "' row (line " + std::to_string(slot->line) + " has one)");
    slot = std::move(row);
}

// Rows from `first` to the end of the table; returns the index of the first line after it.
std::size_t read_rows(SieveTable& t, const Lines& lines, std::size_t first) {
    std::size_t i = first;
    for (; i < lines.size(); ++i) {
        if (is_blank(lines[i])) continue;
        const int line = static_cast<int>(i) + 1;
        const SplitLine split = split_cells(lines[i], t.header.dialect.delimiter);
        if (split.unterminated_quote) throw InputError(t.file, line, "unterminated quote (a '\"' without its closing '\"')");
        if (std::all_of(split.cells.begin(), split.cells.end(), [](const Cell& c) { return is_blank(c.text); })) continue;
        auto row = read_row(split.cells, t.header, t.file, line);
        if (!row) break;
        if (row->kind != SieveRowKind::sieve && !row->has_numbers) continue;  // "Pan," or "Total mass: see below": nothing to read
        add_row(t, std::move(*row));
        t.last_line = line;
    }
    return i;
}

// Openings must differ: the same sieve twice ("No. 30" and "600 µm") is an error.
void sort_and_check_sieves(SieveTable& t) {
    std::stable_sort(t.sieves.begin(), t.sieves.end(), [](const auto& a, const auto& b) { return a.opening_m > b.opening_m; });
    for (std::size_t i = 1; i < t.sieves.size(); ++i) {
        const TableRow &a = t.sieves[i - 1], &b = t.sieves[i];
        if (std::abs(a.opening_m - b.opening_m) <= 1e-9 * a.opening_m) {
            const TableRow& later = a.line > b.line ? a : b;
            const TableRow& earlier = a.line > b.line ? b : a;
            throw InputError(t.file, later.line, "duplicate sieve: opening " + fmt(later.opening_m * 1e3) + " mm repeats line " +
                                                     std::to_string(earlier.line) + " (each sieve once)");
        }
    }
    if (t.sieves.size() < 2)
        throw InputError(t.file, t.last_line, "a sieve table needs at least 2 sieves, found " + std::to_string(t.sieves.size()));
}

// "key: value" lines above the header and below the table.
void read_metadata(SieveTable& t, const Lines& lines, std::size_t begin, std::size_t end) {
    for (std::size_t i = begin; i < end; ++i)
        if (!is_blank(lines[i]))
            if (auto m = parse_meta_line(lines[i], static_cast<int>(i) + 1, t.header.dialect)) t.metadata.push_back(*m);
}

// The header, or an error saying what a sieve table needs.
SieveHeader locate_header(const Lines& lines, const std::string& file) {
    if (std::all_of(lines.begin(), lines.end(), [](auto l) { return is_blank(l); }))
        throw InputError(file, 1, std::string("file is empty: expected a sieve table with ") + accepted_sieve_columns());
    const HeaderSearch found = find_sieve_header(lines, 0);
    if (found.complete) return *found.complete;
    const auto& partial = found.partial;
    std::string named, limits;
    auto add = [](std::string& list, const std::string& header) { list += (list.empty() ? "" : ", ") + in_quotes(header); };
    if (partial)
        for (const SieveColumn& c : partial->columns) add(c.limit ? limits : named, c.header);
    const std::string limit_note = limits.empty() ? "" : " (" + limits + " are specification limits, e.g. ASTM C144's: not a sand)";
    throw InputError(file, partial ? partial->line() : 1,
                     (partial ? "this row names " + named + limit_note + " but a" : std::string("no sieve-table header found: a")) +
                         " sieve table needs " + accepted_sieve_columns());
}

// Lines below the end of the table that name a sieve (a row the table's end cut off): they are
// not read, and the reader warns about them.
std::vector<int> sieve_rows_after(const SieveHeader& h, const Lines& lines, std::size_t end) {
    std::vector<int> found;
    for (std::size_t i = end + 1; i < lines.size(); ++i) {
        if (is_blank(lines[i])) continue;
        const RowIdentity r = identify_row(split_cells(lines[i], h.dialect.delimiter).cells, h);
        if (r.id && r.id->problem.empty() && r.id->kind == SieveRowKind::sieve && r.id->opening_m > 0) found.push_back(static_cast<int>(i) + 1);
    }
    return found;
}

SieveTable read_table(std::string_view bytes, const std::string& file) {
    const std::string text = decode_text(bytes).utf8;
    const Lines lines = split_lines(text);
    SieveTable t;
    t.file = file;
    t.header = locate_header(lines, file);
    sniff_decimal(t.header, lines);
    const std::size_t first = apply_units_row(t.header, lines);
    check_header(t.header, file);
    t.last_line = t.header.line();
    read_metadata(t, lines, 0, t.header.index);
    const std::size_t end = read_rows(t, lines, first);
    if (const auto second = find_sieve_header(lines, end).complete)
        throw InputError(file, second->line(), "a second sieve table starts here (the first has its header at line " +
                                                   std::to_string(t.header.line()) + "): one table per file");
    read_metadata(t, lines, end, lines.size());
    if (end < lines.size()) {
        t.end_line = static_cast<int>(end) + 1;
        t.sieve_rows_after = sieve_rows_after(t.header, lines, end);
    }
    sort_and_check_sieves(t);
    return t;
}

// ---- One value column -----------------------------------------------------------------------

// The number in `row`'s cell of column `c` (percent or mass in the file's unit); nullopt when
// empty. Percentages must lie in [0, 100] (a trailing '%' is allowed), masses must be >= 0.
std::optional<double> value_of(const SieveTable& t, const TableRow& row, const SieveColumn& c) {
    std::string text = cell_text(row.cells, c.index);
    if (c.basis == SieveBasis::percent && !text.empty() && text.back() == '%') text = trim(text.substr(0, text.size() - 1));
    if (text.empty()) return std::nullopt;
    const bool q = c.index < row.cells.size() && row.cells[c.index].quoted;
    const auto v = parse_number(text, t.header.dialect, q);
    if (!v) throw InputError(t.file, row.line, column_prefix(c.header) + in_quotes(text) + " is not a number");
    if (c.basis == SieveBasis::percent && !(*v >= 0 && *v <= 100))
        throw InputError(t.file, row.line, column_prefix(c.header) + text + " is outside [0, 100] (a percentage)");
    if (c.basis == SieveBasis::mass && *v < 0)
        throw InputError(t.file, row.line, column_prefix(c.header) + text + " is negative (masses retained are >= 0)");
    return v;
}

struct ColumnValues {
    std::vector<double> sieve;  // per sieve, coarsest first [% or g]
    double pan = kNaN, total = kNaN;
};

// Percentages as written, masses in grams. Pan and Total cells are read where they mean
// something: for masses and percentages retained (cumulative percentages end at 100 %).
ColumnValues values_of(const SieveTable& t, const SieveColumn& c) {
    const bool mass = c.basis == SieveBasis::mass;
    const double scale = mass ? c.to_si : 1.0;
    auto scaled = [&](const TableRow& r, double x) {
        if (!std::isfinite(x * scale)) throw InputError(t.file, r.line, column_prefix(c.header) + fmt(x) + " is too large");
        return x * scale;
    };
    ColumnValues v;
    for (const TableRow& r : t.sieves) {
        const auto x = value_of(t, r, c);
        if (!x) throw InputError(t.file, r.line, column_prefix(c.header) + "empty cell: every sieve needs a value");
        v.sieve.push_back(scaled(r, *x));
    }
    if (c.measure == M::passing || (c.measure == M::cumulative_retained && !mass)) return v;
    if (t.pan)
        if (const auto x = value_of(t, *t.pan, c)) v.pan = scaled(*t.pan, *x);
    if (t.total)
        if (const auto x = value_of(t, *t.total, c)) v.total = scaled(*t.total, *x);
    return v;
}

/// Passing and masses of one sand from one value column.
struct ColumnCurve {
    const SieveColumn* column = nullptr;
    std::vector<double> passing;     // fraction per sieve, coarsest first
    std::vector<double> retained_g;  // NaN without masses
    double pan_g = kNaN, total_g = kNaN;
};

// Passing must not increase (cumulative retained must not decrease) towards finer sieves.
void check_monotone(const SieveTable& t, const SieveColumn& c, const std::vector<double>& v, bool cumulative) {
    const std::string unit = c.basis == SieveBasis::mass ? " g" : " %";
    for (std::size_t i = 1; i < v.size(); ++i) {
        if (cumulative ? v[i] >= v[i - 1] : v[i] <= v[i - 1]) continue;
        const std::string coarse = "(line " + std::to_string(t.sieves[i - 1].line) + ")";
        throw InputError(t.file, t.sieves[i].line,
                         column_prefix(c.header) + fmt(v[i]) + unit +
                             (cumulative ? " retained down to the finer sieve is less than " : " through the finer sieve is more than ") +
                             fmt(v[i - 1]) + unit + (cumulative ? " down to the coarser one " : " through the coarser one ") + coarse +
                             (cumulative ? ": cumulative retained must not decrease" : ": percent passing must not increase") +
                             " as the opening gets smaller");
    }
}

// A stated Total must match `sum` (retained incl. pan) within kTotalTolerance.
void check_stated_total(const SieveTable& t, const SieveColumn& c, double stated, double sum, const char* unit) {
    if (std::isnan(stated) || std::abs(stated - sum) <= kTotalTolerance * std::abs(stated)) return;
    throw InputError(t.file, t.total->line, column_prefix(c.header) + "the Total row says " + fmt(stated) + unit + " but the sieves and pan add up to " +
                                                fmt(sum) + unit + " (difference " + pct((stated - sum) / stated) +
                                                ", at most 0.5 %): the values must add up to the stated Total");
}

// "# initial_dry_mass_g: 500.0" (or "Initial dry mass (g|kg): ..."): ASTM C136 loss on sieving.
void check_initial_mass(const SieveTable& t, double total_g) {
    for (const MetaEntry& m : t.metadata) {
        const std::string key = replace_all(to_lower(m.key), "_", " ");
        const bool grams = key == "initial dry mass g" || (key == "initial dry mass" && (m.unit.empty() || to_lower(m.unit) == "g"));
        if (!grams && !(key == "initial dry mass" && to_lower(m.unit) == "kg")) continue;
        const auto value = parse_number(m.value, t.header.dialect, true);
        if (!value) throw InputError(t.file, m.line, column_prefix(m.key) + in_quotes(m.value) + " is not a number");
        const double initial = *value * (grams ? 1.0 : 1e3);
        const double loss = (initial - total_g) / initial;
        if (initial > 0 && std::abs(loss) <= kInitialMassTolerance) continue;
        throw InputError(t.file, m.line, "masses retained incl. pan add up to " + fmt(total_g) + " g but the initial dry mass is " + fmt(initial) +
                                             " g (difference " + pct(loss) + ", at most 0.3 % allowed, ASTM C136 [check])");
    }
}

int pan_or_last_line(const SieveTable& t) { return t.pan ? t.pan->line : t.last_line; }

// Masses retained on each sieve, with the pan: passing = 1 − cumulative / total.
ColumnCurve from_masses(const SieveTable& t, const SieveColumn& c, const ColumnValues& v, bool one_sand) {
    if (std::isnan(v.pan))
        throw InputError(t.file, pan_or_last_line(t), column_prefix(c.header) + "masses retained need a 'Pan' row (mass passing the finest sieve) "
                                                                                "to compute percent passing");
    ColumnCurve k{&c, {}, v.sieve, v.pan, v.pan};
    for (double m : v.sieve) k.total_g += m;
    if (!std::isfinite(k.total_g)) throw InputError(t.file, t.last_line, column_prefix(c.header) + "masses retained add up to more than a double holds");
    if (!(k.total_g > 0)) throw InputError(t.file, t.last_line, column_prefix(c.header) + "masses retained add up to zero");
    check_stated_total(t, c, v.total, k.total_g, " g");
    if (one_sand) check_initial_mass(t, k.total_g);
    double cumulative = 0;
    for (double m : v.sieve) k.passing.push_back(std::max(0.0, 1.0 - (cumulative += m) / k.total_g));
    return k;
}

// Cumulative masses: the total is the Total row, else the pan row's (cumulative) value.
ColumnCurve from_cumulative_masses(const SieveTable& t, const SieveColumn& c, const ColumnValues& v, bool one_sand) {
    check_monotone(t, c, v.sieve, true);
    const double total = !std::isnan(v.total) ? v.total : v.pan;
    if (std::isnan(total))
        throw InputError(t.file, t.last_line, column_prefix(c.header) + "cumulative masses retained need a 'Pan' or 'Total' row (the total mass)");
    if (!std::isnan(v.pan) && !std::isnan(v.total)) check_stated_total(t, c, v.total, v.pan, " g");
    if (v.sieve.back() > total * (1 + kTotalTolerance))
        throw InputError(t.file, t.sieves.back().line, column_prefix(c.header) + fmt(v.sieve.back()) + " g retained down to the finest sieve is more than the total, " +
                                                           fmt(total) + " g");
    if (!(total > 0)) throw InputError(t.file, t.last_line, column_prefix(c.header) + "the total mass is zero");
    if (one_sand) check_initial_mass(t, total);
    ColumnCurve k{&c, {}, {}, total - v.sieve.back(), total};
    double previous = 0;
    for (double m : v.sieve) {
        k.retained_g.push_back(m - previous);
        k.passing.push_back(std::max(0.0, 1.0 - m / total));
        previous = m;
    }
    return k;
}

// Percent retained on each sieve: they add up to 100 % with the pan (and to a stated Total).
ColumnCurve from_percent_retained(const SieveTable& t, const SieveColumn& c, const ColumnValues& v) {
    double sum = std::isnan(v.pan) ? 0.0 : v.pan;
    for (double p : v.sieve) sum += p;
    const bool off = std::isnan(v.pan) ? sum > 100 * (1 + kTotalTolerance) : std::abs(sum - 100) > 100 * kTotalTolerance;
    if (off)
        throw InputError(t.file, pan_or_last_line(t), column_prefix(c.header) + "the percentages retained" + (std::isnan(v.pan) ? "" : " incl. pan") +
                                                          " add up to " + fmt(sum) + " %, not 100 % (at most 0.5 % off)");
    check_stated_total(t, c, v.total, sum, " %");
    ColumnCurve k{&c, {}, std::vector<double>(v.sieve.size(), kNaN), kNaN, kNaN};
    double cumulative = 0;
    for (double p : v.sieve) k.passing.push_back(std::clamp(1.0 - (cumulative += p) / 100, 0.0, 1.0));
    return k;
}

ColumnCurve curve_of(const SieveTable& t, const SieveColumn& c, bool one_sand) {
    const ColumnValues v = values_of(t, c);
    const bool mass = c.basis == SieveBasis::mass;
    if (c.measure == M::retained) return mass ? from_masses(t, c, v, one_sand) : from_percent_retained(t, c, v);
    if (c.measure == M::cumulative_retained && mass) return from_cumulative_masses(t, c, v, one_sand);
    const bool cumulative = c.measure == M::cumulative_retained;
    check_monotone(t, c, v.sieve, cumulative);
    ColumnCurve k{&c, {}, std::vector<double>(v.sieve.size(), kNaN), kNaN, kNaN};
    for (double p : v.sieve) k.passing.push_back(cumulative ? 1.0 - p / 100 : p / 100);
    return k;
}

// ---- Sands ----------------------------------------------------------------------------------

// Which column of a sand the reader uses: the most direct measurement first.
int priority(const SieveColumn& c) {
    const bool mass = c.basis == SieveBasis::mass;
    switch (c.measure) {
        case M::retained: return mass ? 0 : 2;
        case M::cumulative_retained: return mass ? 1 : 3;
        default: return 4;
    }
}

struct SandColumns {
    std::string name;
    std::vector<const SieveColumn*> columns;
};

// Value columns grouped by sand name (case-insensitive), in the order they first appear.
std::vector<SandColumns> sands_of(const SieveTable& t) {
    std::vector<SandColumns> sands;
    for (const SieveColumn& c : t.header.columns) {
        if (c.identifies_sieve() || c.limit) continue;
        auto it = std::find_if(sands.begin(), sands.end(), [&](auto& s) { return to_lower(s.name) == to_lower(c.sand); });
        if (it == sands.end()) it = sands.insert(sands.end(), SandColumns{c.sand, {}});
        for (const SieveColumn* other : it->columns)
            if (priority(*other) == priority(c) && other->measure == c.measure)
                throw InputError(t.file, t.header.line(), "columns " + in_quotes(other->header) + " and " + in_quotes(c.header) +
                                                              " hold the same quantity for " + (c.sand.empty() ? "the sample" : in_quotes(c.sand)) + ": keep one");
        it->columns.push_back(&c);
    }
    for (auto& s : sands) std::stable_sort(s.columns.begin(), s.columns.end(), [](auto* a, auto* b) { return priority(*a) < priority(*b); });
    return sands;
}

// Every other column of a sand must give the primary column's passing within kColumnAgreement.
void check_agreement(const SieveTable& t, const ColumnCurve& primary, const ColumnCurve& other) {
    for (std::size_t i = 0; i < primary.passing.size(); ++i) {
        if (std::abs(primary.passing[i] - other.passing[i]) <= kColumnAgreement + 1e-12) continue;
        throw InputError(t.file, t.sieves[i].line, "columns " + in_quotes(primary.column->header) + " and " + in_quotes(other.column->header) +
                                                       " disagree: " + pct(primary.passing[i]) + " and " + pct(other.passing[i]) +
                                                       " passing (columns of one sand must agree within 1 percentage point)");
    }
}

// "pre-blended (natural river sand ...)" -> "pre-blended", from a sand/sample/material line.
std::string sand_from_metadata(const std::vector<MetaEntry>& metadata) {
    for (const MetaEntry& m : metadata) {
        const std::string key = to_lower(m.key);
        if (key != "sand" && key != "sample" && key != "sample name" && key != "sample id" && key != "material") continue;
        const std::string v = trim(m.value);
        if (!v.empty()) return v.substr(0, v.find(" ("));
    }
    return {};
}

SieveAnalysis analysis_of(const SieveTable& t, const SandColumns& sand, bool one_sand) {
    std::vector<ColumnCurve> curves;
    for (const SieveColumn* c : sand.columns) curves.push_back(curve_of(t, *c, one_sand));
    for (std::size_t k = 1; k < curves.size(); ++k) check_agreement(t, curves.front(), curves[k]);
    const ColumnCurve& k = curves.front();
    SieveAnalysis s;
    s.file = t.file;
    s.metadata = t.metadata;
    for (const auto& m : t.metadata)
        if (to_lower(m.key) == "provenance" || to_lower(m.key) == "source") s.provenance = m.value;
    s.sand = !sand.name.empty() ? sand.name : sand_from_metadata(t.metadata);
    for (const SieveColumn* c : sand.columns) s.columns.push_back(c->header);
    s.header_line = t.header.line();
    s.from_masses = k.column->basis == SieveBasis::mass;
    s.pan_g = k.pan_g;
    s.total_g = k.total_g;
    std::vector<double> size, frac;
    std::vector<std::string> name;
    for (std::size_t i = 0; i < t.sieves.size(); ++i) {
        const TableRow& r = t.sieves[i];
        s.rows.push_back({r.designation, r.opening_m, k.passing[i], k.retained_g[i], r.line});
        size.push_back(r.opening_m), frac.push_back(k.passing[i]), name.push_back(r.designation);
    }
    s.curve = GradationCurve::from_points(size, frac, name);
    return s;
}

struct SievePath {
    fs::path file;
    std::string sand;
};

// "sieves.csv#Sand B" -> {sieves.csv, Sand B} when only the part before '#' names a file.
SievePath split_sand_selector(const fs::path& path) {
    std::error_code ec;
    if (fs::exists(path, ec)) return {path, {}};
    const std::string name = path.filename().string();
    const auto hash = name.rfind('#');
    if (hash == std::string::npos || hash == 0) return {path, {}};
    const fs::path base = path.parent_path() / name.substr(0, hash);
    if (!fs::exists(base, ec)) return {path, {}};
    return {base, name.substr(hash + 1)};
}

std::string sand_list(const std::vector<SieveAnalysis>& all) {
    std::string names;
    for (const auto& a : all) names += (names.empty() ? "" : ", ") + in_quotes(a.sand);
    return names;
}

}  // namespace

std::vector<SieveAnalysis> parse_sieve_csv_all(std::string_view bytes, const std::string& file) {
    const SieveTable t = read_table(bytes, file);
    const std::vector<SandColumns> sands = sands_of(t);
    std::vector<SieveAnalysis> all;
    for (const SandColumns& sand : sands) all.push_back(analysis_of(t, sand, sands.size() == 1));
    const LabWarning skipped = rows_skipped(file, t.sieve_rows_after, "they name a sieve but follow line " + std::to_string(t.end_line) +
                                                                          ", which ends the table");
    if (skipped.count() > 0) {
        warning_sink().add(skipped);
        for (SieveAnalysis& a : all) a.warnings.push_back(skipped);
    }
    return all;
}

SieveAnalysis parse_sieve_csv(std::string_view bytes, const std::string& file, std::string_view sand) {
    std::vector<SieveAnalysis> all = parse_sieve_csv_all(bytes, file);
    const std::string wanted = to_lower(trim(sand));
    if (!wanted.empty()) {
        for (SieveAnalysis& a : all)
            if (to_lower(a.sand) == wanted) return std::move(a);
        throw InputError(file, all.front().header_line, "no sand " + in_quotes(trim(sand)) + " in this file (sands: " + sand_list(all) + ")");
    }
    if (all.size() == 1) return std::move(all.front());
    std::string columns;
    for (const auto& a : all)
        for (const auto& c : a.columns) columns += (columns.empty() ? "" : ", ") + in_quotes(c);
    throw InputError(file, all.front().header_line, std::to_string(all.size()) + " sands in this file (columns " + columns +
                                                        "): name one after '#', e.g. \"" + fs::path(file).filename().string() + "#" +
                                                        all.front().sand + "\" (sands: " + sand_list(all) + ")");
}

SieveAnalysis read_sieve_csv(const fs::path& path) {
    const SievePath p = split_sand_selector(path);
    return parse_sieve_csv(read_file_bytes(p.file), p.file.string(), p.sand);
}

SieveAnalysis read_sieve_csv(const fs::path& path, std::string_view sand) {
    return parse_sieve_csv(read_file_bytes(path), path.string(), sand);
}

std::vector<SieveAnalysis> read_sieve_csv_all(const fs::path& path) {
    const SievePath p = split_sand_selector(path);
    if (!p.sand.empty()) return {parse_sieve_csv(read_file_bytes(p.file), p.file.string(), p.sand)};
    return parse_sieve_csv_all(read_file_bytes(p.file), p.file.string());
}

bool looks_like_sieve_csv(std::string_view bytes) {
    const std::string text = decode_text(bytes).utf8;
    const Lines lines = split_lines(text);
    return find_sieve_header(lines, 0, true).partial.has_value();
}

bool is_sieve_csv_file(const fs::path& path) {
    std::ifstream in(split_sand_selector(path).file, std::ios::binary);
    if (!in) return false;
    std::string head(64 * 1024, '\0');
    in.read(head.data(), static_cast<std::streamsize>(head.size()));
    head.resize(static_cast<std::size_t>(in.gcount()));
    return looks_like_sieve_csv(head);
}

}  // namespace gradem::lab
