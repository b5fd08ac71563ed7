#pragma once
// Sieve analyses in the layouts labs write, and ASTM C144 limit tables.
//
// Sieve analysis (sieve_layout.hpp says what each cell may hold): any lines first (a title,
// "Project: ...", "Sample: Sand A", "# key: value"), then a header row found by its content:
// a sieve column and one or more value columns, delimited by ',', ';' or tab (decimal comma
// detected as for load-frame exports), with an optional units row below it. Then one row per
// sieve, in any order, with optional "Pan" and "Total" rows; the table ends at the first row
// that names no sieve and holds no number (notes below it are read as "key: value" metadata; a
// row below it that names a sieve is not read, and is a warning).
//   sieve columns   Sieve / Sieve No. / Sieve Size (designations), Opening / Particle Size /
//                   Sieve Size (mm, µm, in; a number without unit is mm)
//   value columns   percent passing (% Passing, % Finer), cumulative retained (% or mass),
//                   individual retained (% or mass: Mass Retained (g), Retained (kg), ...)
// Columns whose header adds other words name a sand ("Sand A % passing"): one analysis per
// sand. Several value columns of one sand must agree (within 1 percentage point); the reader
// uses, in this order, masses retained, cumulative masses, % retained, cumulative %, % passing.
// With masses, percent passing = 100 × (1 − cumulative retained / total), total including the
// pan; a Total row must match within 0.5 %; with one sand, "# initial_dry_mass_g: 500.0" must
// match within 0.3 % (ASTM C136 [check]).
//
// C144 limits CSV: columns sieve, opening_mm, min_passing_pct, max_passing_pct.

#include <filesystem>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "lab_data/gradation.hpp"
#include "lab_data/lab_warning.hpp"
#include "lab_data/raw_table.hpp"

namespace gradem::lab {

struct SieveRow {
    std::string designation;  ///< as written in the sieve column ("#4", "No. 200", "600 µm"); may be empty
    double opening_m = 0;     ///< [m]
    double passing = 0;       ///< cumulative fraction passing [0, 1]
    double retained_g = 0;    ///< mass retained [g]; NaN when the table gave percentages
    int line = 0;
};

struct SieveAnalysis {
    std::string file;
    std::string provenance;         ///< from "# provenance: ..." (or "# source: ...")
    std::vector<MetaEntry> metadata;
    std::vector<SieveRow> rows;     ///< sieves as listed (pan excluded), coarsest first
    bool from_masses = false;
    double pan_g = 0, total_g = 0;  ///< with masses [g]
    GradationCurve curve;
    std::string sand;               ///< from the column headers, else a "sand"/"sample"/"material" line; may be empty
    std::vector<std::string> columns;  ///< headers of the value columns read for this sand
    int header_line = 0;
    std::vector<LabWarning> warnings;  ///< rows naming a sieve below the end of the table (not read)
};

/// Every sand of the file, in the order of their columns. Throws InputError (file:line: ...)
/// for: no recognisable header (naming the column kinds accepted), unusable or duplicated
/// columns, unknown sieve designations, text in numeric cells, truncated rows, percentages
/// outside [0, 100], negative masses, percent passing that increases towards finer sieves,
/// masses or percentages that do not add up (Pan, Total, initial dry mass), repeated sieves,
/// columns of one sand that disagree, fewer than 2 sieves.
std::vector<SieveAnalysis> parse_sieve_csv_all(std::string_view bytes, const std::string& file);

/// One sand: the one named `sand` (case-insensitive), or the file's only one when `sand` is
/// empty; a file with several sands and no name is an InputError listing them.
SieveAnalysis parse_sieve_csv(std::string_view bytes, const std::string& file, std::string_view sand = {});

/// `path` may name a sand after '#' ("sieves.csv#Sand B") when no file has that full name;
/// datasets and configs use this to pick one sand of a file with several.
SieveAnalysis read_sieve_csv(const std::filesystem::path& path);
SieveAnalysis read_sieve_csv(const std::filesystem::path& path, std::string_view sand);
/// All sands of the file (only the named one with "file.csv#sand").
std::vector<SieveAnalysis> read_sieve_csv_all(const std::filesystem::path& path);

/// True when the file holds a sieve-table header (a sieve column and a value column), or a
/// row naming a sieve or value column among others (a sieve table the reader will refuse with
/// a message saying what it needs): a sieve analysis, not a load-frame export.
bool looks_like_sieve_csv(std::string_view bytes);
bool is_sieve_csv_file(const std::filesystem::path& path);

struct C144Limit {
    std::string designation;
    double opening_m = 0;
    double min_passing = 0, max_passing = 1;  ///< fractions
    int line = 0;
};

struct C144Limits {
    std::string file, provenance;
    std::vector<C144Limit> sieves;  ///< coarsest first
    /// ASTM C144 §4 [check clause]: at most 50 % retained between two consecutive listed sieves,
    /// at most 25 % between the No. 50 (300 µm) and No. 100 (150 µm) sieves.
    double max_retained_between_consecutive = 0.50;
    double max_retained_no50_to_no100 = 0.25;
};

C144Limits parse_c144_limits(std::string_view bytes, const std::string& file);
C144Limits read_c144_limits(const std::filesystem::path& path);

}  // namespace gradem::lab
