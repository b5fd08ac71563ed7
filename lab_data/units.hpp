#pragma once
// Physical units as lab exports spell them: "(sec)", "[mm]", "kN", "lbf", "mm/mm", "%", "µε",
// "MPa", "psi", ... Every value is converted to SI once, when it is read.

#include <optional>
#include <string>
#include <string_view>

#include "common/named_enum.hpp"

namespace gradem::lab {

/// What a unit measures (one Dimension per unit; the calibration's target quantities are cal::Quantity).
enum class Dimension { time, force, length, strain, stress, area };
constexpr EnumNameTable<Dimension, 6> enum_name_table(Dimension) {
    return {{{Dimension::time, "time"},
             {Dimension::force, "force"},
             {Dimension::length, "length"},
             {Dimension::strain, "strain"},
             {Dimension::stress, "stress"},
             {Dimension::area, "area"}}};
}

/// The unit spellings accepted for a quantity, for error messages ("N, kN, lbf, kip").
const char* accepted_units(Dimension q);

struct Unit {
    Dimension dimension = Dimension::force;
    double to_si = 1.0;  ///< multiply a value in this unit by to_si to get s, N, m, m/m, Pa or m²
    std::string symbol;  ///< canonical spelling, e.g. "kN", "µε"
};

/// Parses a unit spelling; surrounding "()" or "[]" and white space are ignored, case is
/// ignored except where it matters (none of the accepted units clash). Returns nullopt for
/// an unknown or empty unit.
std::optional<Unit> parse_unit(std::string_view text);

/// A column header split into name and unit: "Load (kN)" -> {"Load", "kN"},
/// "Höhe [mm]" -> {"Höhe", "mm"}, "load_kN" -> {"load", "kN"} (suffix only when it is a known
/// unit). Without a recognisable unit, unit is empty and name is the trimmed header.
struct NameAndUnit {
    std::string name;
    std::string unit;
};
NameAndUnit split_name_unit(std::string_view header);

}  // namespace gradem::lab
