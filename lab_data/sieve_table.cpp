// fast-cpp-csv-parser does the row splitting and header mapping here: these tables have a fixed,
// named schema, which is what it is built for. The CSV_IO_NO_THREAD switch keeps it synchronous
// (files are tiny); this is the only translation unit that includes it.
#define CSV_IO_NO_THREAD
#if defined(__GNUC__) && !defined(__clang__)
// csv.h copies file names with strncpy into a fixed buffer (and terminates them itself);
// GCC's middle end reports that inside this file once inlined.
#pragma GCC diagnostic ignored "-Wstringop-truncation"
#endif
#include <libfccp/csv.h>

#include "lab_data/sieve_table.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <fstream>
#include <limits>
#include <sstream>

#include "common/input_error.hpp"
#include "lab_data/block_parser.hpp"
#include "lab_data/text.hpp"

namespace gradem::lab {
namespace {

using Reader = io::CSVReader<4, io::trim_chars<' ', '\t'>, io::double_quote_escape<',', '"'>, io::throw_on_overflow,
                             io::empty_line_comment>;

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

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

std::string pct(double fraction) {
    std::ostringstream os;
    os.precision(4);
    os << fraction * 100 << " %";
    return os.str();
}

// Percent passing from masses retained (ASTM C136: cumulative retained over total incl. pan).
void passing_from_masses(SieveAnalysis& s, int last_line) {
    if (std::isnan(s.pan_g))
        throw InputError(s.file, last_line, "masses retained need a 'Pan' row (mass passing the finest sieve) "
                                            "to compute percent passing");
    s.total_g = s.pan_g;
    for (const auto& r : s.rows) s.total_g += r.retained_g;
    if (!(s.total_g > 0)) throw InputError(s.file, last_line, "masses retained add up to zero");
    for (const auto& m : s.metadata) {
        if (to_lower(m.key) != "initial_dry_mass_g") continue;
        const double initial = number(s.file, m.line, "initial_dry_mass_g", m.value);
        const double loss = (initial - s.total_g) / initial;
        if (!(initial > 0) || std::abs(loss) > 0.003) {
            std::ostringstream os;
            os << "masses retained incl. pan add up to " << s.total_g << " g but initial_dry_mass_g = " << initial
               << " g (difference " << pct(loss) << ", at most 0.3 % allowed, ASTM C136 [check])";
            throw InputError(s.file, m.line, os.str());
        }
    }
    double cumulative = 0;
    for (auto& r : s.rows) {
        cumulative += r.retained_g;
        r.passing = std::max(0.0, 1.0 - cumulative / s.total_g);
    }
}

void check_monotonic(const SieveAnalysis& s) {
    for (std::size_t i = 1; i < s.rows.size(); ++i) {
        const auto& coarse = s.rows[i - 1];
        const auto& fine = s.rows[i];
        if (fine.opening_m == coarse.opening_m)
            throw InputError(s.file, fine.line, "opening " + std::to_string(fine.opening_m * 1e3) + " mm repeats line " +
                                                    std::to_string(coarse.line));
        if (fine.passing > coarse.passing + 1e-12)
            throw InputError(s.file, fine.line, "column 'percent_passing': " + pct(fine.passing) + " through the finer sieve is more than " +
                                                    pct(coarse.passing) + " through the coarser one (line " + std::to_string(coarse.line) +
                                                    "): percent passing must not increase as the opening gets smaller");
    }
}

}  // namespace

SieveAnalysis parse_sieve_csv(std::string_view bytes, const std::string& file) {
    const Preamble p = split_preamble(bytes);
    SieveAnalysis s;
    s.file = file;
    s.metadata = p.metadata;
    for (const auto& m : p.metadata)
        if (to_lower(m.key) == "provenance" || to_lower(m.key) == "source") s.provenance = m.value;
    if (p.header_offset >= p.text.size()) throw InputError(file, 1, "file is empty: expected a sieve table (opening_mm, percent_passing or mass_retained_g)");
    Reader reader(file, p.text.data() + p.header_offset, p.text.data() + p.text.size());
    reader.set_file_line(p.header_line - 1);
    std::string sieve, opening, passing, mass;
    int last_line = static_cast<int>(p.header_line);
    s.pan_g = kNaN;
    with_csv_errors(file, reader, [&] {
        reader.read_header(io::ignore_extra_column | io::ignore_missing_column, "sieve", "opening_mm", "percent_passing", "mass_retained_g");
        if (!reader.has_column("opening_mm")) throw InputError(file, static_cast<int>(p.header_line), "missing column 'opening_mm'");
        if (reader.has_column("percent_passing") == reader.has_column("mass_retained_g"))
            throw InputError(file, static_cast<int>(p.header_line), "expected exactly one of the columns 'percent_passing' and 'mass_retained_g'");
        s.from_masses = reader.has_column("mass_retained_g");
        while (true) {
            sieve.clear(), opening.clear(), passing.clear(), mass.clear();
            if (!reader.read_row(sieve, opening, passing, mass)) break;
            const int line = last_line = static_cast<int>(reader.get_file_line());
            const bool pan = to_lower(trim(sieve)) == "pan" || trim(opening).empty();
            SieveRow r{trim(sieve), 0, kNaN, kNaN, line};
            if (s.from_masses) {
                r.retained_g = number(file, line, "mass_retained_g", mass);
                if (r.retained_g < 0) throw InputError(file, line, column_prefix("mass_retained_g") + mass + " is negative");
                if (pan) { s.pan_g = r.retained_g; continue; }
            } else if (pan) {
                continue;  // a pan row carries no percent passing
            } else {
                const double pp = number(file, line, "percent_passing", passing);
                if (!(pp >= 0 && pp <= 100))
                    throw InputError(file, line, column_prefix("percent_passing") + trim(passing) + " is outside [0, 100]");
                r.passing = pp / 100;
            }
            r.opening_m = number(file, line, "opening_mm", opening) * 1e-3;
            if (!(r.opening_m > 0)) throw InputError(file, line, column_prefix("opening_mm") + trim(opening) + " must be > 0");
            s.rows.push_back(r);
        }
    });
    std::stable_sort(s.rows.begin(), s.rows.end(), [](const auto& a, const auto& b) { return a.opening_m > b.opening_m; });
    if (s.from_masses) passing_from_masses(s, last_line);
    if (s.rows.size() < 2) throw InputError(file, last_line, "a sieve table needs at least 2 sieves, found " + std::to_string(s.rows.size()));
    check_monotonic(s);
    std::vector<double> size, frac;
    std::vector<std::string> name;
    for (const auto& r : s.rows) { size.push_back(r.opening_m); frac.push_back(r.passing); name.push_back(r.designation); }
    s.curve = GradationCurve::from_points(size, frac, name);
    return s;
}

SieveAnalysis read_sieve_csv(const std::filesystem::path& path) { return parse_sieve_csv(read_file_bytes(path), path.string()); }

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

bool looks_like_sieve_csv(std::string_view bytes) {
    const Preamble p = split_preamble(bytes);
    const std::string_view rest = std::string_view(p.text).substr(p.header_offset);
    std::string header(rest.substr(0, rest.find('\n')));
    std::transform(header.begin(), header.end(), header.begin(), [](unsigned char c) { return std::tolower(c); });
    const bool opening = header.find("opening_mm") != std::string::npos;
    const bool passing = header.find("percent_passing") != std::string::npos ||
                         header.find("mass_retained_g") != std::string::npos;
    return opening && passing;
}

bool is_sieve_csv_file(const std::filesystem::path& path) {
    std::ifstream in(path, std::ios::binary);
    if (!in) return false;
    std::string head(64 * 1024, '\0');
    in.read(head.data(), static_cast<std::streamsize>(head.size()));
    head.resize(static_cast<std::size_t>(in.gcount()));
    return looks_like_sieve_csv(head);
}

}  // namespace gradem::lab
