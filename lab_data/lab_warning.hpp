#pragma once
// What the lab readers did to a file that the user should know without reading the JSON: data
// rows they skipped, and specimen dimensions they took from a nominal value because the file
// does not state them. Each event is one LabWarning record, made once where it happens; the
// record gives both the note in lab_results.json (message()) and the line on stderr (line()),
// and goes to the warning sink, which prints each distinct record once per command (none with
// --quiet: the app sets its printer, app/cli.hpp).

#include <functional>
#include <mutex>
#include <set>
#include <string>
#include <vector>

namespace gradem::lab {

/// A specimen dimension taken from a nominal value.
struct NominalDimension {
    std::string name;    ///< "width", "depth", "height", "diameter", "length", "span"
    double value_m = 0;  ///< the value used [m]
    std::string origin;  ///< where it was set: "lab/dataset.toml [specimen]", "the command line", "ASTM C348"
    std::string key;     ///< the key or option there ("width_mm", "--diameter-mm"); empty for a default
};

struct LabWarning {
    enum class Kind { rows_skipped, nominal_geometry };
    Kind kind = Kind::rows_skipped;
    std::string file;                          ///< the file as read (the path errors name too)
    std::vector<int> lines;                    ///< rows_skipped: the file lines skipped, ascending
    std::string reason;                        ///< rows_skipped: why ("no load or strain value")
    std::vector<NominalDimension> dimensions;  ///< nominal_geometry: the dimensions not in the file
    bool nothing_from_file = false;            ///< nominal_geometry: the file states none of the dimensions

    [[nodiscard]] std::size_t count() const { return lines.size(); }
    /// Without the file: "4 rows skipped (lines 212-215: no load or strain value)",
    /// "no specimen dimensions in the file; nominal 50 x 50 x 50 mm (width x depth x height) from
    /// lab/dataset.toml [specimen] width_mm, depth_mm, height_mm". At most kShownLineRanges runs
    /// of lines are listed, then "...".
    [[nodiscard]] std::string message() const;
    /// "warning: <file>: <message()>" (no newline).
    [[nodiscard]] std::string line() const;
};

/// Runs of consecutive lines shown in a message; the count is always given in full.
inline constexpr std::size_t kShownLineRanges = 5;

/// "line 7", "lines 212-215", "lines 3, 9-11, 20, ..." (at most kShownLineRanges runs).
std::string describe_lines(const std::vector<int>& ascending_lines);

/// A rows_skipped record for `file`; nothing (count() == 0) when `lines` is empty.
LabWarning rows_skipped(const std::string& file, std::vector<int> lines, const std::string& reason);
/// A nominal_geometry record for `file`.
LabWarning nominal_geometry(const std::string& file, std::vector<NominalDimension> dimensions, bool nothing_from_file);

/// Where the readers send their records. Each distinct record (by its line()) reaches the printer
/// once until the next start(); the default printer writes line() to stderr. Thread-safe.
class WarningSink {
public:
    using Printer = std::function<void(const LabWarning&)>;
    /// From now on records go to `printer` (an empty one drops them); forgets the records seen.
    void start(Printer printer);
    void add(const LabWarning& warning);

private:
    std::mutex mutex_;
    std::set<std::string> seen_;
    Printer printer_ = print_to_stderr;
    static void print_to_stderr(const LabWarning& warning);
};

/// The sink of the process.
WarningSink& warning_sink();

/// Sends `warning` to the sink, keeps it in `records` and appends its message to `notes` (what
/// the JSON shows); nothing for a record without lines or dimensions.
void report(const LabWarning& warning, std::vector<LabWarning>& records, std::vector<std::string>& notes);

}  // namespace gradem::lab
