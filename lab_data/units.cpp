#include "lab_data/units.hpp"

#include <array>

#include "lab_data/text.hpp"

namespace gradem::lab {
namespace {

constexpr double kInch = 0.0254;        // m (exact)
constexpr double kPoundForce = 4.4482216152605;  // N (exact by definition of lbf)

struct UnitSpelling {
    const char* spelling;  // lower case, micro sign written as 'u', '²' as '2'
    Dimension dimension;
    double to_si;
    const char* symbol;
};

constexpr std::array<UnitSpelling, 56> kUnits = {{
    {"s", Dimension::time, 1.0, "s"},           {"sec", Dimension::time, 1.0, "s"},
    {"secs", Dimension::time, 1.0, "s"},        {"second", Dimension::time, 1.0, "s"},
    {"seconds", Dimension::time, 1.0, "s"},     {"ms", Dimension::time, 1e-3, "ms"},
    {"min", Dimension::time, 60.0, "min"},      {"h", Dimension::time, 3600.0, "h"},
    {"hr", Dimension::time, 3600.0, "h"},       {"d", Dimension::time, 86400.0, "d"},
    {"n", Dimension::force, 1.0, "N"},          {"kn", Dimension::force, 1e3, "kN"},
    {"lbf", Dimension::force, kPoundForce, "lbf"}, {"lb", Dimension::force, kPoundForce, "lbf"},
    {"lbs", Dimension::force, kPoundForce, "lbf"}, {"kip", Dimension::force, 1e3 * kPoundForce, "kip"},
    {"kips", Dimension::force, 1e3 * kPoundForce, "kip"}, {"kgf", Dimension::force, 9.80665, "kgf"},
    {"mm", Dimension::length, 1e-3, "mm"},      {"m", Dimension::length, 1.0, "m"},
    {"cm", Dimension::length, 1e-2, "cm"},      {"um", Dimension::length, 1e-6, "µm"},
    {"in", Dimension::length, kInch, "in"},     {"inch", Dimension::length, kInch, "in"},
    {"inches", Dimension::length, kInch, "in"}, {"\"", Dimension::length, kInch, "in"},
    {"mm/mm", Dimension::strain, 1.0, "mm/mm"}, {"m/m", Dimension::strain, 1.0, "m/m"},
    {"in/in", Dimension::strain, 1.0, "in/in"},
    {"-", Dimension::strain, 1.0, "mm/mm"},     {"%", Dimension::strain, 1e-2, "%"},
    {"pct", Dimension::strain, 1e-2, "%"},      {"percent", Dimension::strain, 1e-2, "%"},
    {"mm/m", Dimension::strain, 1e-3, "mm/m"},  {"ue", Dimension::strain, 1e-6, "µε"},
    {"ustrain", Dimension::strain, 1e-6, "µε"}, {"microstrain", Dimension::strain, 1e-6, "µε"},
    {"um/m", Dimension::strain, 1e-6, "µε"},
    {"pa", Dimension::stress, 1.0, "Pa"},       {"kpa", Dimension::stress, 1e3, "kPa"},
    {"mpa", Dimension::stress, 1e6, "MPa"},     {"gpa", Dimension::stress, 1e9, "GPa"},
    {"n/mm2", Dimension::stress, 1e6, "MPa"},   {"n/mm^2", Dimension::stress, 1e6, "MPa"},
    {"psi", Dimension::stress, kPoundForce / (kInch * kInch), "psi"},
    {"ksi", Dimension::stress, 1e3 * kPoundForce / (kInch * kInch), "ksi"},
    {"lbf/in2", Dimension::stress, kPoundForce / (kInch * kInch), "psi"},
    {"lbf/in^2", Dimension::stress, kPoundForce / (kInch * kInch), "psi"},
    {"mm2", Dimension::area, 1e-6, "mm²"},      {"mm^2", Dimension::area, 1e-6, "mm²"},
    {"m2", Dimension::area, 1.0, "m²"},         {"cm2", Dimension::area, 1e-4, "cm²"},
    {"in2", Dimension::area, kInch * kInch, "in²"}, {"in^2", Dimension::area, kInch * kInch, "in²"},
    {"sq in", Dimension::area, kInch * kInch, "in²"}, {"sq. in.", Dimension::area, kInch * kInch, "in²"},
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

const char* accepted_units(Dimension q) {
    switch (q) {
        case Dimension::time: return "s, sec, ms, min";
        case Dimension::force: return "N, kN, lbf, kip";
        case Dimension::length: return "mm, m, in";
        case Dimension::strain: return "mm/mm, in/in, %, µε";
        case Dimension::stress: return "MPa, kPa, Pa, psi, ksi";
        case Dimension::area: return "mm², in²";
    }
    return "?";
}

std::optional<Unit> parse_unit(std::string_view text) {
    const std::string key = normalise(text);
    if (key.empty()) return std::nullopt;
    for (const auto& u : kUnits)
        if (key == u.spelling) return Unit{u.dimension, u.to_si, u.symbol};
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
