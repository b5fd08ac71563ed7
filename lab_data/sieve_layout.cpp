#include "lab_data/sieve_layout.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <vector>

#include "lab_data/units.hpp"

namespace gradem::lab {
namespace {

using M = SieveMeasure;
using B = SieveBasis;

constexpr double kInch = 0.0254;  // m (exact)

// ---- Column headers -------------------------------------------------------------------------

// One row per accepted header alias. Phrases are written as the header's words normalised: lower
// case, "percent"/"pct" as '%', without '.', '#', '_' and brackets. The longest phrase found in a
// header wins; the words around it name the sand.
struct HeaderAlias {
    const char* phrase;
    SieveMeasure measure;
    SieveBasis basis = B::none;  // none: decided by the unit
    bool bare_us = false;        // designation column whose bare numbers are US sieve numbers
};

constexpr HeaderAlias kHeaderAliases[] = {
    {"sieve", M::designation},
    {"sieve designation", M::designation},
    {"designation", M::designation},
    {"sieve no", M::designation, B::none, true},
    {"sieve number", M::designation, B::none, true},
    {"us sieve", M::designation, B::none, true},
    {"us sieve no", M::designation, B::none, true},
    {"sieve size", M::opening},
    {"sieve opening", M::opening},
    {"opening", M::opening},
    {"opening size", M::opening},
    {"aperture", M::opening},
    {"particle size", M::opening},
    {"grain size", M::opening},
    {"size", M::opening},
    {"passing", M::passing, B::percent},
    {"% passing", M::passing, B::percent},
    {"cumulative passing", M::passing, B::percent},
    {"cumulative % passing", M::passing, B::percent},
    {"finer", M::passing, B::percent},
    {"% finer", M::passing, B::percent},
    {"retained", M::retained},
    {"% retained", M::retained, B::percent},
    {"individual retained", M::retained},
    {"individual % retained", M::retained, B::percent},
    {"mass retained", M::retained, B::mass},
    {"weight retained", M::retained, B::mass},
    {"wt retained", M::retained, B::mass},
    {"individual mass retained", M::retained, B::mass},
    {"cumulative retained", M::cumulative_retained},
    {"cum retained", M::cumulative_retained},
    {"cumulative % retained", M::cumulative_retained, B::percent},
    {"cum % retained", M::cumulative_retained, B::percent},
    {"cumulative mass retained", M::cumulative_retained, B::mass},
    {"cumulative weight retained", M::cumulative_retained, B::mass},
};

// Words that make a value column a specification limit, not a sand ("C144 min % passing").
constexpr std::array<const char*, 14> kLimitWords = {"min",   "max",   "minimum",  "maximum",       "limit",
                                                     "limits", "spec", "specification", "lower", "upper",
                                                     "envelope", "requirement", "band", "tolerance"};

// A header holds an alias and at most this many other words (the sand's name); more is prose.
constexpr std::size_t kMaxSandWords = 5;

// Mass units [g per unit]; lengths come from units.hpp.
struct MassUnit {
    const char* spelling;
    double grams;
};
constexpr MassUnit kMassUnits[] = {{"g", 1.0},     {"gm", 1.0},         {"gms", 1.0},          {"gram", 1.0},
                                   {"grams", 1.0}, {"kg", 1e3},         {"kgs", 1e3},          {"kilogram", 1e3},
                                   {"kilograms", 1e3}, {"lb", 453.59237}, {"lbs", 453.59237}};

struct SieveUnit {
    enum Kind { length, mass, percent } kind;
    double factor;  // metres or grams per unit; 1 for percent
};

std::string unbracketed(std::string_view text) {
    std::string s = trim(text);
    while (s.size() >= 2 && ((s.front() == '(' && s.back() == ')') || (s.front() == '[' && s.back() == ']')))
        s = trim(std::string_view(s).substr(1, s.size() - 2));
    return s;
}

std::optional<SieveUnit> read_sieve_unit(std::string_view text) {
    const std::string s = to_lower(unbracketed(text));
    if (s.empty()) return std::nullopt;
    if (s == "%" || s == "pct" || s == "percent") return SieveUnit{SieveUnit::percent, 1.0};
    for (const auto& m : kMassUnits)
        if (s == m.spelling) return SieveUnit{SieveUnit::mass, m.grams};
    if (const auto u = parse_unit(s); u && u->dimension == Dimension::length) return SieveUnit{SieveUnit::length, u->to_si};
    return std::nullopt;
}

struct NameUnit {
    std::string name, unit;
};

// "Opening (mm)" -> {Opening, mm}; "mass_retained_g" -> {mass_retained, g}; "% Passing (Sand A)"
// keeps its bracket (not a unit).
NameUnit split_unit(std::string_view header) {
    const std::string h = trim(header);
    if (!h.empty() && (h.back() == ')' || h.back() == ']')) {
        const auto open = h.rfind(h.back() == ')' ? '(' : '[');
        if (open != std::string::npos && read_sieve_unit(h.substr(open))) return {trim(h.substr(0, open)), h.substr(open)};
    }
    const auto underscore = h.rfind('_');
    if (underscore != std::string::npos && underscore > 0 && read_sieve_unit(h.substr(underscore + 1)))
        return {h.substr(0, underscore), h.substr(underscore + 1)};
    return {h, {}};
}

struct Word {
    std::string text;  // as written
    std::string norm;  // as the alias phrases are written
};

std::string normalise_word(std::string_view w) {
    std::string n;
    for (char c : to_lower(w))
        if (c != '.' && c != '#' && c != '(' && c != ')' && c != '[' && c != ']' && c != ':' && c != ',' && c != '-') n += c;
    if (n == "percent" || n == "pct") n.assign(1, '%');
    return n;
}

// Words of a header; '%' is a word of its own ("%Passing" -> "%", "Passing").
std::vector<Word> header_words(std::string_view name) {
    std::vector<Word> words;
    std::string cur;
    auto flush = [&] {
        const std::string n = normalise_word(cur);
        if (!n.empty()) words.push_back({cur, n});
        cur.clear();
    };
    for (char c : name) {
        if (c == ' ' || c == '\t' || c == '_') flush();
        else if (c == '%') { flush(); words.push_back({"%", "%"}); }
        else cur += c;
    }
    flush();
    return words;
}

// The alias phrases as words, in the order of kHeaderAliases (split once).
const std::vector<std::vector<std::string>>& alias_words() {
    static const auto words = [] {
        std::vector<std::vector<std::string>> all;
        for (const HeaderAlias& a : kHeaderAliases) {
            all.emplace_back();
            for (const Word& w : header_words(a.phrase)) all.back().push_back(w.norm);
        }
        return all;
    }();
    return words;
}

// The longest word of each alias phrase: a header cell with that alias contains it.
const std::vector<std::string>& alias_key_words() {
    static const auto keys = [] {
        std::vector<std::string> all;
        for (const auto& words : alias_words()) {
            const auto longest = std::max_element(words.begin(), words.end(), [](auto& a, auto& b) { return a.size() < b.size(); });
            if (std::find(all.begin(), all.end(), *longest) == all.end()) all.push_back(*longest);
        }
        return all;
    }();
    return keys;
}

struct AliasMatch {
    const HeaderAlias* alias = nullptr;
    std::size_t begin = 0, end = 0;  // word range of the phrase
};

// The longest alias phrase that occurs as consecutive words of `words`.
AliasMatch best_alias(const std::vector<Word>& words) {
    AliasMatch best;
    std::size_t best_len = 0;
    for (std::size_t a = 0; a < std::size(kHeaderAliases); ++a) {
        const auto& p = alias_words()[a];
        for (std::size_t i = 0; i + p.size() <= words.size(); ++i) {
            bool match = true;
            for (std::size_t k = 0; k < p.size() && match; ++k) match = words[i + k].norm == p[k];
            if (match && p.size() > best_len) {
                best = {&kHeaderAliases[a], i, i + p.size()};
                best_len = p.size();
            }
        }
    }
    return best;
}

// Unit and basis of a column from its alias and unit; sets `problem` when they do not fit.
void resolve_unit(SieveColumn& c, const std::optional<SieveUnit>& unit, const std::string& unit_text) {
    std::string quoted(1, '\'');  // built in steps: GCC 12 misreports "'" + s + "'" (-Wrestrict)
    quoted.append(trim(unit_text)).push_back('\'');
    if (c.identifies_sieve()) {
        if (unit && unit->kind != SieveUnit::length) c.problem = "unit " + quoted + " is not a length; a sieve size needs mm, µm or in";
        if (unit && unit->kind == SieveUnit::length) { c.measure = M::opening; c.to_si = unit->factor; }
        else if (c.measure == M::opening) c.to_si = 1e-3;  // bare sizes are mm
        return;
    }
    if (unit && unit->kind == SieveUnit::length) { c.problem = "unit " + quoted + " is a length; expected %, g or kg"; return; }
    const SieveBasis from_unit = !unit ? B::none : unit->kind == SieveUnit::mass ? B::mass : B::percent;
    // "Weight Retained (%)" is a percentage by weight; "% Retained (g)" contradicts itself.
    if (from_unit == B::mass && c.basis == B::percent) { c.problem = "unit " + quoted + " is a mass but the column is a percentage"; return; }
    if (from_unit != B::none) c.basis = from_unit;
    if (c.basis == B::none) { c.problem = "give its unit: (g), (kg) or (%)"; return; }
    if (c.measure == M::passing && c.basis != B::percent) { c.problem = "percent passing is a percentage; unit " + quoted + " does not fit"; return; }
    c.to_si = c.basis == B::mass ? (unit ? unit->factor : 1.0) : 1.0;
}

std::string trim_separators(std::string s) {
    const char* seps = " \t-:;,/|()[]";
    const auto first = s.find_first_not_of(seps);
    if (first == std::string::npos) return {};
    return s.substr(first, s.find_last_not_of(seps) - first + 1);
}

// ---- Designations ---------------------------------------------------------------------------

// ASTM E11 [check edition] Table 1: alternative (US) sieve number -> nominal opening [mm].
struct UsSieve {
    double number;
    double opening_mm;
};
constexpr UsSieve kUsSieves[] = {
    {3.5, 5.60},   {4, 4.75},     {5, 4.00},     {6, 3.35},     {7, 2.80},     {8, 2.36},     {10, 2.00},
    {12, 1.70},    {14, 1.40},    {16, 1.18},    {18, 1.00},    {20, 0.850},   {25, 0.710},   {30, 0.600},
    {35, 0.500},   {40, 0.425},   {45, 0.355},   {50, 0.300},   {60, 0.250},   {70, 0.212},   {80, 0.180},
    {100, 0.150},  {120, 0.125},  {140, 0.106},  {170, 0.090},  {200, 0.075},  {230, 0.063},  {270, 0.053},
    {325, 0.045},  {400, 0.038},  {450, 0.032},  {500, 0.025},  {635, 0.020},
};

// ASTM E11 Table 1: inch designation -> nominal opening [mm] (3/8" is 9.5 mm, not 9.525).
struct InchSieve {
    double inches;
    double opening_mm;
};
constexpr InchSieve kInchSieves[] = {
    {5, 125},      {4.24, 106},   {4, 100},      {3.5, 90},     {3, 75},       {2.5, 63},
    {2.12, 53},    {2, 50},       {1.75, 45},    {1.5, 37.5},   {1.25, 31.5},  {1.06, 26.5},
    {1, 25.0},     {0.875, 22.4}, {0.75, 19.0},  {0.625, 16.0}, {0.530, 13.2}, {0.5, 12.5},
    {0.4375, 11.2}, {0.375, 9.5}, {0.3125, 8.0}, {0.265, 6.7},  {0.25, 6.3},
};

bool close(double a, double b) { return std::abs(a - b) <= 1e-9 * std::max(std::abs(a), std::abs(b)); }

SieveDesignation sieve_at(double opening_m) { return {SieveRowKind::sieve, opening_m, {}}; }

SieveDesignation us_sieve(double number) {
    for (const auto& s : kUsSieves)
        if (close(s.number, number)) return sieve_at(s.opening_mm * 1e-3);
    return {SieveRowKind::sieve, 0, "is not an ASTM E11 sieve number (No. 3.5 to No. 635)"};
}

SieveDesignation inch_sieve(double inches) {
    for (const auto& s : kInchSieves)
        if (close(s.inches, inches)) return sieve_at(s.opening_mm * 1e-3);
    return sieve_at(inches * kInch);
}

// Lower case, micro sign and Greek mu as 'u', typographic inch marks as '"'.
std::string normalise_designation(std::string_view text) {
    std::string s = to_lower(trim(text));
    s = replace_all(std::move(s), "\xC2\xB5", "u");      // µ MICRO SIGN
    s = replace_all(std::move(s), "\xCE\xBC", "u");      // μ GREEK SMALL LETTER MU
    s = replace_all(std::move(s), "\xE2\x80\xB3", "\"");  // ″ DOUBLE PRIME
    s = replace_all(std::move(s), "\xE2\x80\x9D", "\"");  // ” RIGHT DOUBLE QUOTATION MARK
    s = replace_all(std::move(s), "''", "\"");
    return s;
}

bool is_digit(char c) { return c >= '0' && c <= '9'; }

// "3", "4.75", "3/8", "1 1/2", "1-1/2" (decimal separator of `dialect`).
std::optional<double> parse_size_number(std::string_view text, const Dialect& dialect) {
    const std::string s = trim(text);
    const auto slash = s.find('/');
    if (slash == std::string::npos) return parse_number(s, dialect);
    const auto split = s.find_last_of(" -", slash);
    const std::string whole = split == std::string::npos ? "" : trim(s.substr(0, split));
    const auto num = parse_number(s.substr(split == std::string::npos ? 0 : split + 1, slash - (split == std::string::npos ? 0 : split + 1)), dialect);
    const auto den = parse_number(s.substr(slash + 1), dialect);
    if (!num || !den || !(*den > 0)) return std::nullopt;
    double value = *num / *den;
    if (!whole.empty()) {
        const auto w = parse_number(whole, dialect);
        if (!w) return std::nullopt;
        value += *w;
    }
    return value;
}

// "No. 4", "No 4", "#4", "# 30": the text after the prefix, or nullopt when not written so.
std::optional<std::string> us_number_part(const std::string& s) {
    if (!s.empty() && s[0] == '#') return trim(std::string_view(s).substr(1));
    const bool spaced_digit = s.size() > 3 && s[2] == ' ' && is_digit(s[3]);  // "no 4", not "no wash"
    if (s.size() > 2 && s.compare(0, 2, "no") == 0 && (s[2] == '.' || spaced_digit || is_digit(s[2]))) {
        const auto start = s.find_first_not_of(". ", 2);
        return start == std::string::npos ? std::string() : s.substr(start);
    }
    return std::nullopt;
}

bool is_inch_unit(const std::string& u) { return u == "\"" || u == "in" || u == "in." || u == "inch" || u == "inches"; }

// A size with its unit ("4.75 mm", "600 um", "3/8\"", "3/8 in") or a bare number.
std::optional<SieveDesignation> parse_size(const std::string& s, const Dialect& dialect, const BareNumbers& bare) {
    if (s.empty() || !(is_digit(s[0]) || s[0] == '.' || (s[0] == ',' && dialect.decimal == ','))) return std::nullopt;
    const auto end = s.find_first_not_of("0123456789.,/ -");
    const std::string unit = trim(std::string_view(s).substr(end == std::string::npos ? s.size() : end));
    const auto value = parse_size_number(s.substr(0, end), dialect);
    if (!value) return std::nullopt;
    if (is_inch_unit(unit)) return inch_sieve(*value);
    if (!unit.empty()) {
        const auto u = parse_unit(unit);
        if (!u || u->dimension != Dimension::length) return std::nullopt;
        return sieve_at(*value * u->to_si);
    }
    if (bare.us_sieve) return us_sieve(*value);
    if (bare.unit_m == kInch) return inch_sieve(*value);
    if (bare.unit_m > 0) return sieve_at(*value * bare.unit_m);
    return SieveDesignation{SieveRowKind::sieve, 0,
                            "is ambiguous: write No. " + s + ", " + s + " mm or " + s +
                                "\", or name the column 'Sieve No.' (US numbers) or 'Opening (mm)'"};
}

std::optional<SieveDesignation> parse_plain_designation(const std::string& s, const Dialect& dialect, const BareNumbers& bare) {
    std::string first = s.substr(0, s.find_first_of(" \t:("));
    if (first == "pan" || first == "receiver") return SieveDesignation{SieveRowKind::pan, 0, {}};
    if (first == "total" || first == "totals" || first == "sum") return SieveDesignation{SieveRowKind::total, 0, {}};
    if (const auto rest = us_number_part(s)) {
        const auto n = parse_number(*rest, Dialect{});
        if (!n) return SieveDesignation{SieveRowKind::sieve, 0, "is not an ASTM E11 sieve number (No. 3.5 to No. 635)"};
        return us_sieve(*n);
    }
    return parse_size(s, dialect, bare);
}

}  // namespace

std::optional<SieveColumn> classify_sieve_header(std::string_view header, std::size_t index, std::string_view unit) {
    NameUnit nu = split_unit(header);
    if (nu.unit.empty()) nu.unit = trim(unit);
    const std::vector<Word> words = header_words(nu.name);
    const AliasMatch m = best_alias(words);
    if (!m.alias) return std::nullopt;
    SieveColumn c;
    c.index = index;
    c.header = trim(header);
    c.measure = m.alias->measure;
    c.basis = m.alias->basis;
    c.bare_numbers_are_us_sieves = m.alias->bare_us;
    if (words.size() - (m.end - m.begin) > kMaxSandWords) return std::nullopt;  // a sentence, not a header
    std::string sand;
    for (std::size_t i = 0; i < words.size(); ++i) {
        if (i >= m.begin && i < m.end) continue;
        if (words[i].norm == "%" && nu.unit.empty()) { nu.unit.assign(1, '%'); continue; }
        for (const char* w : kLimitWords) c.limit = c.limit || (words[i].norm == w && !c.identifies_sieve());
        sand += (sand.empty() ? "" : " ") + words[i].text;
    }
    c.sand = trim_separators(sand);
    resolve_unit(c, read_sieve_unit(nu.unit), nu.unit);
    return c;
}

bool may_hold_sieve_header(std::string_view line) {
    const std::string lower = to_lower(line);
    return std::any_of(alias_key_words().begin(), alias_key_words().end(),
                       [&](const std::string& w) { return lower.find(w) != std::string::npos; });
}

bool is_sieve_unit(std::string_view text) { return read_sieve_unit(text).has_value(); }

const char* accepted_sieve_columns() {
    return "a sieve column (Sieve, Sieve No., Sieve Size, Opening (mm|µm|in), Particle Size (mm)) and at least one "
           "value column (% Passing, % Finer, Cumulative Retained (%), % Retained, Individual Retained (%), "
           "Mass Retained (g|kg), Weight Retained (g), Cumulative Retained (g))";
}

std::optional<SieveDesignation> parse_sieve_designation(std::string_view text, const Dialect& dialect, const BareNumbers& bare) {
    const std::string s = normalise_designation(text);
    if (s.empty()) return std::nullopt;
    const auto open = s.find('(');
    if (open == std::string::npos || s.back() != ')') return parse_plain_designation(s, dialect, bare);
    // "No. 4 (4.75 mm)", "4.75 mm (No. 4)": either part may name the sieve.
    const auto outer = parse_plain_designation(trim(std::string_view(s).substr(0, open)), dialect, bare);
    if (outer && outer->problem.empty()) return outer;
    const auto inner = parse_plain_designation(trim(std::string_view(s).substr(open + 1, s.size() - open - 2)), dialect, bare);
    if (inner && inner->problem.empty()) return inner;
    return outer ? outer : inner;
}

const char* accepted_sieve_designations() {
    return "No. 4 ... No. 200 or #30 (ASTM E11), 3/8\" or 3/8 in, 4.75 mm, 600 µm, Pan or Total";
}

}  // namespace gradem::lab
