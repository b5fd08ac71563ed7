#include "lab_data/units.hpp"

#include <array>

#include "lab_data/text.hpp"

namespace gradem::lab {
namespace {

constexpr double kInch = 0.0254;        // m (exact)
constexpr double kPoundForce = 4.4482216152605;  // N (exact by definition of lbf)

struct UnitSpelling {
    const char* spelling;  // lower case, micro sign written as 'u', '²' as '2'
    Quantity quantity;
    double to_si;
    const char* symbol;
};

constexpr std::array<UnitSpelling, 56> kUnits = {{
    {"s", Quantity::time, 1.0, "s"},           {"sec", Quantity::time, 1.0, "s"},
    {"secs", Quantity::time, 1.0, "s"},        {"second", Quantity::time, 1.0, "s"},
    {"seconds", Quantity::time, 1.0, "s"},     {"ms", Quantity::time, 1e-3, "ms"},
    {"min", Quantity::time, 60.0, "min"},      {"h", Quantity::time, 3600.0, "h"},
    {"hr", Quantity::time, 3600.0, "h"},       {"d", Quantity::time, 86400.0, "d"},
    {"n", Quantity::force, 1.0, "N"},          {"kn", Quantity::force, 1e3, "kN"},
    {"lbf", Quantity::force, kPoundForce, "lbf"}, {"lb", Quantity::force, kPoundForce, "lbf"},
    {"lbs", Quantity::force, kPoundForce, "lbf"}, {"kip", Quantity::force, 1e3 * kPoundForce, "kip"},
    {"kips", Quantity::force, 1e3 * kPoundForce, "kip"}, {"kgf", Quantity::force, 9.80665, "kgf"},
    {"mm", Quantity::length, 1e-3, "mm"},      {"m", Quantity::length, 1.0, "m"},
    {"cm", Quantity::length, 1e-2, "cm"},      {"um", Quantity::length, 1e-6, "µm"},
    {"in", Quantity::length, kInch, "in"},     {"inch", Quantity::length, kInch, "in"},
    {"inches", Quantity::length, kInch, "in"}, {"\"", Quantity::length, kInch, "in"},
    {"mm/mm", Quantity::strain, 1.0, "mm/mm"}, {"m/m", Quantity::strain, 1.0, "m/m"},
    {"in/in", Quantity::strain, 1.0, "in/in"},
    {"-", Quantity::strain, 1.0, "mm/mm"},     {"%", Quantity::strain, 1e-2, "%"},
    {"pct", Quantity::strain, 1e-2, "%"},      {"percent", Quantity::strain, 1e-2, "%"},
    {"mm/m", Quantity::strain, 1e-3, "mm/m"},  {"ue", Quantity::strain, 1e-6, "µε"},
    {"ustrain", Quantity::strain, 1e-6, "µε"}, {"microstrain", Quantity::strain, 1e-6, "µε"},
    {"um/m", Quantity::strain, 1e-6, "µε"},
    {"pa", Quantity::stress, 1.0, "Pa"},       {"kpa", Quantity::stress, 1e3, "kPa"},
    {"mpa", Quantity::stress, 1e6, "MPa"},     {"gpa", Quantity::stress, 1e9, "GPa"},
    {"n/mm2", Quantity::stress, 1e6, "MPa"},   {"n/mm^2", Quantity::stress, 1e6, "MPa"},
    {"psi", Quantity::stress, kPoundForce / (kInch * kInch), "psi"},
    {"ksi", Quantity::stress, 1e3 * kPoundForce / (kInch * kInch), "ksi"},
    {"lbf/in2", Quantity::stress, kPoundForce / (kInch * kInch), "psi"},
    {"lbf/in^2", Quantity::stress, kPoundForce / (kInch * kInch), "psi"},
    {"mm2", Quantity::area, 1e-6, "mm²"},      {"mm^2", Quantity::area, 1e-6, "mm²"},
    {"m2", Quantity::area, 1.0, "m²"},         {"cm2", Quantity::area, 1e-4, "cm²"},
    {"in2", Quantity::area, kInch * kInch, "in²"}, {"in^2", Quantity::area, kInch * kInch, "in²"},
    {"sq in", Quantity::area, kInch * kInch, "in²"}, {"sq. in.", Quantity::area, kInch * kInch, "in²"},
}};

// Lower-case, strip "()"/"[]", and write the micro sign, Greek mu/epsilon and '²' in ASCII.
std::string normalise(std::string_view text) {
    std::string s = trim(text);
    while (s.size() >= 2 && ((s.front() == '(' && s.back() == ')') || (s.front() == '[' && s.back() == ']')))
        s = trim(std::string_view(s).substr(1, s.size() - 2));
    s = replace_all(std::move(s), "\xC2\xB5", "u");   // µ MICRO SIGN
    s = replace_all(std::move(s), "\xCE\xBC", "u");   // μ GREEK SMALL LETTER MU
    s = replace_all(std::move(s), "\xCE\xB5", "e");   // ε GREEK SMALL LETTER EPSILON
    s = replace_all(std::move(s), "\xC2\xB2", "2");   // ² SUPERSCRIPT TWO
    s = replace_all(std::move(s), " / ", "/");
    return to_lower(s);
}

}  // namespace

const char* accepted_units(Quantity q) {
    switch (q) {
        case Quantity::time: return "s, sec, ms, min";
        case Quantity::force: return "N, kN, lbf, kip";
        case Quantity::length: return "mm, m, in";
        case Quantity::strain: return "mm/mm, in/in, %, µε";
        case Quantity::stress: return "MPa, kPa, Pa, psi, ksi";
        case Quantity::area: return "mm², in²";
    }
    return "?";
}

std::optional<Unit> parse_unit(std::string_view text) {
    const std::string key = normalise(text);
    if (key.empty()) return std::nullopt;
    for (const auto& u : kUnits)
        if (key == u.spelling) return Unit{u.quantity, u.to_si, u.symbol};
    return std::nullopt;
}

NameAndUnit split_name_unit(std::string_view header) {
    const std::string h = trim(header);
    if (!h.empty() && (h.back() == ')' || h.back() == ']')) {
        const char open = h.back() == ')' ? '(' : '[';
        const auto pos = h.rfind(open);
        const std::string inside = h.substr(pos == std::string::npos ? 0 : pos + 1, h.size() - pos - 2);
        // A parenthesised suffix is a unit when it is one we know or short enough to be one
        // ("(kp)"); "(Extension)" in "Tensile strain (Extension)" is part of the name.
        if (pos != std::string::npos && pos > 0 && (parse_unit(inside) || trim(inside).size() <= 6))
            return {trim(std::string_view(h).substr(0, pos)), trim(std::string_view(h).substr(pos + 1, h.size() - pos - 2))};
    }
    const auto underscore = h.rfind('_');
    if (underscore != std::string::npos && underscore > 0 && parse_unit(h.substr(underscore + 1)))
        return {h.substr(0, underscore), h.substr(underscore + 1)};
    return {h, {}};
}

}  // namespace gradem::lab
