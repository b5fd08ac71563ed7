#pragma once
// The part every export format shares: a names row, an optional units row, numeric data rows,
// possibly repeated in several blocks with different columns (MTS writes a header per buffer).
// Readers handle their own preamble and then call read_blocks().

#include <cstddef>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "lab_data/raw_table.hpp"

namespace gradem::lab {

using Lines = std::vector<std::string_view>;

enum class RowKind { blank, text, numeric, mixed };

/// text: no cell is a number; numeric: more than half the non-empty cells are numbers;
/// mixed: anything else.
RowKind classify_row(std::string_view line, const Dialect& dialect);

/// True when line `i` is a names row: a text row with 2+ non-empty cells, followed by numeric
/// data either directly or after one units row.
bool is_header_at(const Lines& lines, std::size_t i, const Dialect& dialect);

/// Index of the first names row at or after `from`, or lines.size().
std::size_t find_header(const Lines& lines, std::size_t from, const Dialect& dialect);

/// Options of read_blocks().
struct BlockOptions {
    /// After the first block, non-blank lines that are neither headers nor data are an error
    /// ("row is not data") when true; MTS 793 interleaves marker lines, so it sets false.
    bool strict_between_blocks = true;
};

/// Reads every block from `first_header` to the end into `table` (columns matched by name and
/// unit across blocks). Throws InputError for truncated or overlong rows, unterminated quotes,
/// a units row longer than the names row, and a file without data rows.
void read_blocks(RawTable& table, const Lines& lines, std::size_t first_header, const BlockOptions& options = {});

/// Parses a preamble line into key/value/unit, or nullopt for a line that is not "key: value".
std::optional<MetaEntry> parse_meta_line(std::string_view line, int line_number, const Dialect& dialect);

}  // namespace gradem::lab
