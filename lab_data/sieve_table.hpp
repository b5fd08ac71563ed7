#pragma once
// Sieve-analysis tables (CSV) and ASTM C144 limit tables, read with fast-cpp-csv-parser.
//
// Sieve CSV: optional "# key: value" lines first (e.g. "# provenance: ...",
// "# initial_dry_mass_g: 500.0"), then a header with these columns in any order:
//   opening_mm        sieve opening [mm] (required; empty or 0 on the pan row)
//   sieve             designation, e.g. "#4", "No. 200", "Pan" (optional)
//   percent_passing   cumulative percent passing, 0..100          } exactly one
//   mass_retained_g   mass retained on the sieve [g], with a Pan row } of these
// With masses, percent passing = 100 × (1 − cumulative retained / total), total including the
// pan; when initial_dry_mass_g is given the total must agree within 0.3 % (ASTM C136 [check]).
//
// C144 limits CSV: columns sieve, opening_mm, min_passing_pct, max_passing_pct.

#include <filesystem>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "lab_data/gradation.hpp"
#include "lab_data/raw_table.hpp"

namespace gradem::lab {

struct SieveRow {
    std::string designation;
    double opening_m = 0;     ///< 0 for the pan
    double passing = 0;       ///< cumulative fraction passing [0, 1]
    double retained_g = 0;    ///< mass retained [g]; NaN when the table gave percent passing
    int line = 0;
};

struct SieveAnalysis {
    std::string file;
    std::string provenance;         ///< from "# provenance: ..." (or "# source: ...")
    std::vector<MetaEntry> metadata;
    std::vector<SieveRow> rows;     ///< sieves as listed (pan excluded), coarsest first
    bool from_masses = false;
    double pan_g = 0, total_g = 0;  ///< with masses
    GradationCurve curve;
};

/// Throws InputError (file:line: column 'x': ...) for: missing or duplicated columns, text in
/// numeric cells, truncated rows, percent passing outside [0, 100] or increasing towards finer
/// sieves, negative masses, a missing pan row, masses that do not add up, repeated openings.
SieveAnalysis parse_sieve_csv(std::string_view bytes, const std::string& file);
SieveAnalysis read_sieve_csv(const std::filesystem::path& path);

/// True when the file's header row (after "# key: value" lines) names an `opening_mm` column
/// and a `percent_passing` or `mass_retained_g` column: a sieve analysis, not a load-frame export.
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
