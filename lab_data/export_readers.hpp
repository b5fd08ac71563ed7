#pragma once
// Readers for the load-frame exports users actually have (adding one: docs/extending.md "A
// lab-file format"), detected from the
// file itself:
//   mts-testsuite     MTS TestSuite (TW Elite/Essential) CSV: "Key: value" lines (maybe quoted),
//                     blank lines, quoted names with trailing spaces, a units row, UTF-8 BOM.
//   mts793            MTS 793 specimen.dat: locale header "MTS793|prog|lang|ver|iDelim|sDecimal|…"
//                     giving delimiter and decimal separator, Windows code page text, an
//                     operator-information key/value block, several data blocks (names + units
//                     rows each) whose columns may differ.
//   instron-bluehill  Bluehill 2/3 RawData: optional "Category : Name,value[,unit]" lines, names
//                     row, units row in parentheses, quoted numbers with thousands separators;
//                     Bluehill Universal: a "Raw Data" marker and "Name (unit)" names.
//   plain-csv         a names row with units in the names ("Load (kN)", "load_kN"), optional
//                     "# key: value" comment lines above it.
// All return a RawTable; column roles and units are interpreted later (load_frame_test.hpp).

#include <optional>
#include <string>
#include <string_view>

#include "common/named_enum.hpp"
#include "lab_data/raw_table.hpp"

namespace gradem::lab {

enum class ExportFormat { automatic, mts_testsuite, mts793, bluehill, plain_csv };
/// The names (`--format`, a dataset's export_format, RawTable::format), then their aliases.
constexpr EnumNameTable<ExportFormat, 9> enum_name_table(ExportFormat) {
    return {{{ExportFormat::automatic, "auto"},
             {ExportFormat::mts_testsuite, "mts-testsuite"},
             {ExportFormat::mts793, "mts793"},
             {ExportFormat::bluehill, "instron-bluehill"},
             {ExportFormat::plain_csv, "plain-csv"},
             {ExportFormat::mts_testsuite, "testsuite"},
             {ExportFormat::mts793, "mts-793"},
             {ExportFormat::bluehill, "bluehill"},
             {ExportFormat::plain_csv, "csv"}}};
}

/// parse_enum<ExportFormat> ignoring case and outer spaces; empty is "auto".
std::optional<ExportFormat> parse_format_name(std::string_view name);

/// Decides the format from the decoded lines (never from the file name).
ExportFormat detect_export_format(const std::vector<std::string_view>& lines);

/// Decodes `bytes` and reads them as `format` (detected when automatic). `file` is only used
/// in messages. Throws InputError.
RawTable read_raw_export(std::string_view bytes, const std::string& file, ExportFormat format = ExportFormat::automatic);

}  // namespace gradem::lab
