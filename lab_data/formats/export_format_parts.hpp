#pragma once
// The pieces the export formats share (lab_data/formats/*.cpp): where the text starts, quoted
// cells, the metadata preamble, and the layout most vendors write - preamble, names (+ units),
// data (export_readers.cpp).
#include <cstddef>
#include <string>
#include <string_view>

#include "lab_data/block_parser.hpp"
#include "lab_data/raw_table.hpp"

namespace gradem::lab::formats {

/// Lines looked at to recognise a format.
inline constexpr std::size_t kSniffLines = 60;

/// The first line that is not blank (lines.size() if none).
std::size_t first_nonblank(const Lines& lines);
/// The trimmed text without one pair of enclosing double quotes.
std::string unquoted(std::string_view s);
/// "key: value" lines between `begin` and `end` into table.metadata.
void read_preamble(RawTable& t, const Lines& lines, std::size_t begin, std::size_t end);
/// Preamble, names (+ units), data from line `start` on, the dialect sniffed from the lines.
void read_generic(RawTable& t, const Lines& lines, std::size_t start = 0);

}  // namespace gradem::lab::formats
