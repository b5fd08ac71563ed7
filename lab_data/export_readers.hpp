#pragma once
// Readers for the load-frame exports users actually have, detected from the file itself.
// THE list of formats is GRADEM_EXPORT_FORMATS below: a format is one file,
// lab_data/formats/<format>.cpp, defining `const ExportFormatSpec <format>_format` (how to
// recognise the decoded lines, how to read them), plus one row FORMAT(<format>, name, alias) here
// (docs/extending.md "A lab-file format"; lab_data/README.md "Export formats" describes each).
// Detection tries the rows in order (so a format whose mark is the most specific comes first);
// the last row takes any file the others do not.
// All return a RawTable; column roles and units are interpreted later (load_frame_test.hpp).

#include <array>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "common/named_enum.hpp"
#include "lab_data/raw_table.hpp"

// clang-format off
#define GRADEM_EXPORT_FORMATS(FORMAT)                          \
    FORMAT(mts793, "mts793", "mts-793")                        \
    FORMAT(bluehill, "instron-bluehill", "bluehill")           \
    FORMAT(mts_testsuite, "mts-testsuite", "testsuite")        \
    FORMAT(plain_csv, "plain-csv", "csv")
// clang-format on

namespace gradem::lab {

#define GRADEM_EXPORT_FORMAT_ENUMERATOR(format, name, alias) format,
/// `automatic` (detect from the file), then one enumerator per row of GRADEM_EXPORT_FORMATS.
enum class ExportFormat { automatic, GRADEM_EXPORT_FORMATS(GRADEM_EXPORT_FORMAT_ENUMERATOR) };
#undef GRADEM_EXPORT_FORMAT_ENUMERATOR

#define GRADEM_EXPORT_FORMAT_NAME(format, name, alias) EnumName<ExportFormat>{ExportFormat::format, name},
#define GRADEM_EXPORT_FORMAT_ALIAS(format, name, alias) EnumName<ExportFormat>{ExportFormat::format, alias},
/// The names (`--format`, a dataset's export_format, RawTable::format), then their aliases.
constexpr auto enum_name_table(ExportFormat) {
    return std::to_array({EnumName<ExportFormat>{ExportFormat::automatic, "auto"}, GRADEM_EXPORT_FORMATS(GRADEM_EXPORT_FORMAT_NAME)
                              GRADEM_EXPORT_FORMATS(GRADEM_EXPORT_FORMAT_ALIAS)});
}
#undef GRADEM_EXPORT_FORMAT_NAME
#undef GRADEM_EXPORT_FORMAT_ALIAS

/// What a format is (one per file in lab_data/formats/).
struct ExportFormatSpec {
    /// True when the decoded lines (`dialect` sniffed from them) look like this format.
    bool (*detect)(const std::vector<std::string_view>& lines, const Dialect& dialect);
    /// Reads the lines into `table` (file, encoding and format set); InputError naming the line.
    void (*read)(RawTable& table, const std::vector<std::string_view>& lines);
};

/// parse_enum<ExportFormat> ignoring case and outer spaces; empty is "auto".
std::optional<ExportFormat> parse_format_name(std::string_view name);

/// Decides the format from the decoded lines (never from the file name).
ExportFormat detect_export_format(const std::vector<std::string_view>& lines);

/// Decodes `bytes` and reads them as `format` (detected when automatic). `file` is only used
/// in messages. Throws InputError.
RawTable read_raw_export(std::string_view bytes, const std::string& file, ExportFormat format = ExportFormat::automatic);

}  // namespace gradem::lab
