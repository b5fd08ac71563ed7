#include "lab_data/text.hpp"

#include <algorithm>
#include <array>
#include <charconv>
#include <cmath>
#include <fstream>
#include <iterator>
#include <map>

#include "common/input_error.hpp"

namespace gradem::lab {
namespace {

bool is_digit(char c) { return c >= '0' && c <= '9'; }

// Removes thousands separators from the integer part of `s` when they form strict groups of
// three ("12,345,678"); returns false when a separator is misplaced.
bool strip_thousands(std::string& s, char sep, char decimal) {
    std::size_t begin = (!s.empty() && (s[0] == '+' || s[0] == '-')) ? 1 : 0;
    std::size_t end = s.find_first_of(std::string{decimal, 'e', 'E'}, begin);
    if (end == std::string::npos) end = s.size();
    if (s.find(sep, end) != std::string::npos) return false;  // separator after the integer part
    std::string digits;
    std::size_t group = 0;
    bool first = true;
    for (std::size_t i = begin; i < end; ++i) {
        if (s[i] == sep) {
            if ((first && (group == 0 || group > 3)) || (!first && group != 3)) return false;
            first = false;
            group = 0;
        } else if (is_digit(s[i])) {
            digits.push_back(s[i]);
            ++group;
        } else {
            return false;
        }
    }
    if (!first && group != 3) return false;
    s = s.substr(0, begin) + digits + s.substr(end);
    return true;
}

std::size_t count_cells(std::string_view line, char delimiter) {
    return split_cells(line, delimiter).cells.size();
}

}  // namespace

std::vector<std::string_view> split_lines(std::string_view text) {
    std::vector<std::string_view> lines;
    std::size_t start = 0;
    for (std::size_t i = 0; i < text.size(); ++i) {
        if (text[i] == '\n' || text[i] == '\r') {
            lines.push_back(text.substr(start, i - start));
            if (text[i] == '\r' && i + 1 < text.size() && text[i + 1] == '\n') ++i;
            start = i + 1;
        }
    }
    if (start < text.size()) lines.push_back(text.substr(start));
    return lines;
}

SplitLine split_cells(std::string_view line, char delimiter) {
    SplitLine out;
    if (line.empty()) return out;
    if (delimiter == ' ') {
        const bool tabs = line.find('\t') != std::string_view::npos;
        const bool runs = line.find("  ") != std::string_view::npos;
        std::string_view rest = line;
        while (!rest.empty()) {
            const std::size_t first = rest.find_first_not_of(" \t");
            if (first == std::string_view::npos) break;
            rest.remove_prefix(first);
            std::size_t end = tabs ? rest.find('\t') : runs ? rest.find("  ") : rest.find(' ');
            if (end == std::string_view::npos) end = rest.size();
            out.cells.push_back({trim(rest.substr(0, end)), false});
            rest.remove_prefix(end);
        }
        return out;
    }
    std::size_t p = 0;
    while (true) {
        Cell cell;
        std::size_t q = p;
        while (q < line.size() && line[q] == ' ') ++q;
        if (q < line.size() && line[q] == '"') {
            cell.quoted = true;
            ++q;
            bool closed = false;
            while (q < line.size()) {
                if (line[q] == '"') {
                    if (q + 1 < line.size() && line[q + 1] == '"') { cell.text.push_back('"'); q += 2; continue; }
                    closed = true;
                    ++q;
                    break;
                }
                cell.text.push_back(line[q++]);
            }
            if (!closed) out.unterminated_quote = true;
            while (q < line.size() && line[q] != delimiter) {  // text after the closing quote
                if (line[q] != ' ') cell.text.push_back(line[q]);
                ++q;
            }
            p = q;
        } else {
            const std::size_t end = std::min(line.find(delimiter, p), line.size());
            cell.text = std::string(line.substr(p, end - p));
            p = end;
        }
        out.cells.push_back(std::move(cell));
        if (p >= line.size()) break;
        ++p;  // skip the delimiter; a trailing delimiter yields a final empty cell
        if (p == line.size()) { out.cells.push_back({}); break; }
    }
    return out;
}

std::optional<double> parse_number(std::string_view text, const Dialect& dialect, bool quoted) {
    std::string s = trim(text);
    if (s.empty()) return std::nullopt;
    const char decimal = dialect.decimal;
    const char thousands = decimal == '.' ? ',' : '.';
    if (s.find(thousands) != std::string::npos) {
        const bool has_fraction = s.find(decimal) != std::string::npos;
        if (!(quoted || has_fraction)) return std::nullopt;
        if (!strip_thousands(s, thousands, decimal)) return std::nullopt;
    }
    if (decimal != '.') std::replace(s.begin(), s.end(), decimal, '.');
    const char* first = s.data();
    if (*first == '+') ++first;
    if (first == s.data() + s.size()) return std::nullopt;
    // from_chars accepts "inf"/"nan" and hex-like forms only with letters; require a digit or
    // '.' to start the mantissa so that text such as "n/a" is never a number.
    const char c0 = (*first == '-' && first + 1 < s.data() + s.size()) ? first[1] : *first;
    if (!is_digit(c0) && c0 != '.') return std::nullopt;
    double value = 0.0;
    const auto [ptr, ec] = std::from_chars(first, s.data() + s.size(), value);
    if (ec != std::errc() || ptr != s.data() + s.size() || !std::isfinite(value)) return std::nullopt;
    return value;
}

Dialect sniff_dialect(const std::vector<std::string_view>& lines) {
    std::vector<std::string_view> sample;
    for (auto it = lines.rbegin(); it != lines.rend() && sample.size() < 30; ++it)
        if (!is_blank(*it)) sample.push_back(*it);
    Dialect d;
    if (sample.empty()) return d;
    for (char candidate : {'\t', ';', ','}) {
        std::map<std::size_t, std::size_t> histogram;
        for (auto line : sample) ++histogram[count_cells(line, candidate)];
        const auto mode = std::max_element(histogram.begin(), histogram.end(),
                                           [](auto& a, auto& b) { return a.second < b.second; });
        if (mode->first >= 2 && mode->second * 10 >= sample.size() * 8) {
            d.delimiter = candidate;
            break;
        }
    }
    if (d.delimiter == ',') return d;
    std::size_t comma = 0, dot = 0;
    for (auto line : sample) {
        for (const Cell& c : split_cells(line, d.delimiter).cells) {
            const std::string t = trim(c.text);
            const auto sep = t.find_first_of(".,");
            if (sep == std::string::npos || sep == 0 || sep + 1 >= t.size()) continue;
            if (!is_digit(t[sep - 1]) || !is_digit(t[sep + 1])) continue;
            (t[sep] == ',' ? comma : dot) += 1;
        }
    }
    if (comma > dot) d.decimal = ',';
    return d;
}

std::string trim(std::string_view s) {
    const auto first = s.find_first_not_of(" \t\r\n\f\v");
    if (first == std::string_view::npos) return {};
    const auto last = s.find_last_not_of(" \t\r\n\f\v");
    return std::string(s.substr(first, last - first + 1));
}

std::string to_lower(std::string_view s) {
    std::string out(s);
    for (char& c : out)
        if (c >= 'A' && c <= 'Z') c = static_cast<char>(c - 'A' + 'a');
    return out;
}

bool is_blank(std::string_view s) { return s.find_first_not_of(" \t\r\n\f\v") == std::string_view::npos; }

bool starts_with_ci(std::string_view s, std::string_view prefix) {
    return s.size() >= prefix.size() && to_lower(s.substr(0, prefix.size())) == to_lower(prefix);
}

std::string replace_all(std::string s, std::string_view from, std::string_view to) {
    if (from.empty()) return s;
    std::size_t pos = 0;
    while ((pos = s.find(from, pos)) != std::string::npos) {
        s.replace(pos, from.size(), to);
        pos += to.size();
    }
    return s;
}

}  // namespace gradem::lab
