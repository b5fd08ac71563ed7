#pragma once
// What a reader returns before any interpretation: metadata, named columns of raw cells with
// their unit spellings, and the file line of every row, so that later errors can point at it.

#include <string>
#include <vector>

#include "lab_data/text.hpp"

namespace gradem::lab {

/// One "key: value [unit]" line of a file's preamble (MTS metadata, Bluehill header lines,
/// MTS 793 operator-information block, "# key: value" comments of plain CSV).
struct MetaEntry {
    std::string key;    ///< without category prefix and trailing ':'; unit in brackets removed
    std::string value;  ///< as written (decimal separator of the file)
    std::string unit;   ///< from "[mm]" in the key or a third cell; may be empty
    int line = 0;
};

struct RawColumn {
    std::string name;         ///< trimmed (MTS TestSuite pads names with trailing spaces), unit part removed
    std::string header;       ///< the names-row cell as written (trimmed), e.g. "load_kN"
    std::string unit;         ///< unit spelling from the units row or from the name; may be empty
    int header_line = 0;      ///< line of the names row that introduced the column
    std::vector<Cell> cells;  ///< one per table row; empty text where a block lacked the column
};

struct RawTable {
    std::string file;
    std::string format;    ///< the format's name (export_readers.hpp, GRADEM_EXPORT_FORMATS)
    std::string encoding;  ///< from decode_text()
    Dialect dialect;
    std::vector<MetaEntry> metadata;
    std::vector<RawColumn> columns;  ///< all with cells.size() == row_line.size()
    std::vector<int> row_line;       ///< file line of each row
    int blocks = 0;                  ///< number of data blocks (MTS writes one per buffer)
    std::vector<std::string> notes;  ///< what the reader noticed and did (shown to the user)

    [[nodiscard]] std::size_t rows() const { return row_line.size(); }
    [[nodiscard]] const MetaEntry* find_meta(const std::string& lower_key_part) const;
};

}  // namespace gradem::lab
