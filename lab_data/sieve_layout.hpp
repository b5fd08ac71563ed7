#pragma once
// What the cells of a sieve analysis mean, in the layouts labs write:
//   * column headers: an alias ("Opening (mm)", "% Passing", "Weight Retained (g)", ...) with an
//     optional unit and the name of a sand around it ("Sand A % passing");
//   * sieve designations: ASTM E11 US numbers ("No. 4", "#30", bare numbers in a "Sieve No."
//     column), inch sizes ("3/8\"", "3/8 in"), metric sizes ("4.75 mm", "600 µm"), and the
//     "Pan" and "Total" rows.
// Lengths are metres, masses grams (SieveRow's convention), percentages percent.

#include <cstddef>
#include <optional>
#include <string>
#include <string_view>

#include "lab_data/text.hpp"

namespace gradem::lab {

/// What a sieve-table column holds.
enum class SieveMeasure {
    designation,          ///< sieve names: "No. 4", "#30", "3/8\"", "600 µm", "Pan", "Total"
    opening,              ///< sieve openings as numbers in the column's unit (or designations)
    passing,              ///< cumulative percent passing (finer)
    retained,             ///< retained on each sieve, as a mass or a percent of the total
    cumulative_retained,  ///< cumulative retained, as a mass or a percent of the total
};

enum class SieveBasis { none, percent, mass };

/// A header cell read as a sieve-table column.
struct SieveColumn {
    std::size_t index = 0;       ///< cell index in the header row
    std::string header;          ///< as written (trimmed)
    SieveMeasure measure = SieveMeasure::designation;
    SieveBasis basis = SieveBasis::none;  ///< value columns: percent or mass
    double to_si = 1.0;          ///< opening: metres per file unit; mass: grams per file unit
    bool bare_numbers_are_us_sieves = false;  ///< designation column: "4" means No. 4
    std::string sand;            ///< header text around the alias ("Sand A"); may be empty
    std::string problem;         ///< non-empty: a sieve column that cannot be used, and why
    bool limit = false;          ///< a specification limit ("C144 min % passing"), not a sand: not read

    [[nodiscard]] bool identifies_sieve() const {
        return measure == SieveMeasure::designation || measure == SieveMeasure::opening;
    }
};

/// Reads one header cell. nullopt for cells that are not sieve columns (notes, anything
/// unknown); specification limits ("Spec min % passing") come back with `limit` set. `unit`
/// (e.g. from a units row below the header) is used when the header itself names none.
std::optional<SieveColumn> classify_sieve_header(std::string_view header, std::size_t index,
                                                 std::string_view unit = {});

/// False when no cell of `line` can be a sieve column (it lacks every alias's key word): a
/// quick test before classify_sieve_header() on each cell.
bool may_hold_sieve_header(std::string_view line);

/// True when `text` is a unit a sieve table uses: a length, a mass or '%'.
bool is_sieve_unit(std::string_view text);

/// The column kinds the reader accepts, for messages.
const char* accepted_sieve_columns();

enum class SieveRowKind { sieve, pan, total };

/// A designation cell read as a sieve, the pan or the total.
struct SieveDesignation {
    SieveRowKind kind = SieveRowKind::sieve;
    double opening_m = 0;  ///< sieves only [m]
    std::string problem;   ///< non-empty: written like a designation but not one; completes "'No. 13' ..."
};

/// How a designation cell reads bare numbers ("4", "3/8"): as US sieve numbers, as a size in
/// `unit_m` metres per unit (inch fractions take the ASTM E11 nominal opening), or not at all.
struct BareNumbers {
    bool us_sieve = false;
    double unit_m = 0;  ///< 0: a bare number is ambiguous
};

/// nullopt when `text` is not written like a designation at all (a note, a title).
/// Numbers use `dialect`'s decimal separator ("4,75 mm").
std::optional<SieveDesignation> parse_sieve_designation(std::string_view text, const Dialect& dialect,
                                                        const BareNumbers& bare = {});

/// The designations the reader accepts, for messages.
const char* accepted_sieve_designations();

}  // namespace gradem::lab
