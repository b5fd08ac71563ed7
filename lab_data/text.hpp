#pragma once
// Text layer for messy lab exports: encodings, lines, delimited cells, locale-aware numbers.
// Everything downstream sees UTF-8 and '.'-free knowledge of the file's locale stays here.

#include <cstddef>
#include <filesystem>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "common/text_file.hpp"

namespace gradem::lab {

// Decoding and reading whole files live in common/ (config files read the same way).
using common::DecodedText;
using common::decode_text;
using common::read_file_bytes;

/// Splits on "\n", "\r\n" or "\r". The views point into `text`, line i is file line i + 1.
std::vector<std::string_view> split_lines(std::string_view text);

/// Delimiter and decimal separator of a delimited text file.
struct Dialect {
    char delimiter = ',';  ///< ',', ';', '\t', or ' ' (runs of white space)
    char decimal = '.';    ///< '.' or ','
};

/// One cell of a delimited line: its text with quotes removed ("" -> ") but not trimmed.
struct Cell {
    std::string text;
    bool quoted = false;
};

struct SplitLine {
    std::vector<Cell> cells;
    bool unterminated_quote = false;
};

/// Quote-aware split. With delimiter ' ' a line is split on tabs if it has any, else on runs
/// of two or more spaces if it has any, else on single spaces (MTS 793 "Plain" files).
SplitLine split_cells(std::string_view line, char delimiter);

/// Number in the file's locale. Accepts a leading sign, exponent, the decimal separator of
/// `dialect`, and thousands separators (',' when decimal is '.', else '.') in strict groups of
/// three when the cell was quoted or the number also has a decimal part ("1,234.5").
/// Returns nullopt for anything else, including empty text, "nan" and "inf".
std::optional<double> parse_number(std::string_view text, const Dialect& dialect, bool quoted = false);

/// Guesses delimiter (tab, ';', ',' in that order of preference, first that splits the sampled
/// lines consistently into 2+ cells) and decimal separator (',' when most decimal-looking cells
/// use it and the delimiter is not ',').
Dialect sniff_dialect(const std::vector<std::string_view>& lines);

// Small string helpers (ASCII case folding; UTF-8 bytes above 0x7F pass through unchanged).
std::string trim(std::string_view s);
std::string to_lower(std::string_view s);
bool is_blank(std::string_view s);
bool starts_with_ci(std::string_view s, std::string_view prefix);
/// Replaces every occurrence of `from` by `to`.
std::string replace_all(std::string s, std::string_view from, std::string_view to);

}  // namespace gradem::lab
