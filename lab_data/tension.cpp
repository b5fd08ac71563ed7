#include "lab_data/tension.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <sstream>

#include "common/input_error.hpp"
#include "common/number_format.hpp"
#include "lab_data/export_readers.hpp"
#include "lab_data/text.hpp"
#include "lab_data/units.hpp"

namespace gradem::lab {
namespace {

// One dimension of the specimen: its metadata keys, the dataset key and command-line option
// that give it, and where it lives in TensileGeometry.
struct SpecimenDimension {
    const char* what;
    std::initializer_list<const char*> keys, not_keys;
    const char* config_key;
    const char* option;
    double TensileGeometry::*field;
    double standard;  ///< ASTM C348 default [m], 0: none
};

const SpecimenDimension kSplitting[] = {
    {"diameter", {"diameter", "durchmesser"}, {}, "diameter_mm", "--diameter-mm", &TensileGeometry::diameter_m, 0},
    {"length", {"length", "länge"}, {"gauge", "gage", "mess", "extensometer", "rate", "span"}, "length_mm", "--length-mm",
     &TensileGeometry::length_m, 0}};
const SpecimenDimension kFlexural[] = {
    {"width", {"width", "breite"}, {"rate"}, "width_mm", "--width-mm", &TensileGeometry::width_m, kC348PrismWidth},
    {"depth", {"depth", "thickness", "tiefe", "dicke", "height", "höhe"}, {"gauge", "gage", "rate"}, "depth_mm", "--depth-mm",
     &TensileGeometry::depth_m, kC348PrismDepth},
    {"span", {"span", "stützweite", "auflagerabstand", "support distance"}, {"rate"}, "span_mm", "--span-mm",
     &TensileGeometry::span_m, kC348Span}};

void add_source(std::string& sources, const std::string& s) {
    if (sources.find(s) != std::string::npos) return;
    sources += (sources.empty() ? "" : "+") + s;
}

[[noreturn]] void missing_dimension(const SpecimenDimension& d, const RawTable& t, const TensileSpec& spec, TensileTestKind kind) {
    const std::string what = std::string(to_string(kind)) + " test: the export states no specimen " + d.what;
    if (spec.config_file.empty())
        throw InputError(t.file, 0, what + "; give " + d.option + " (mm)");
    throw InputError(spec.config_file.string(), spec.config_line,
                     spec.label + ": " + t.file + ": " + what + "; set " + d.config_key + " (mm)");
}

// Where a dimension the file does not state comes from: the dataset's group, the command line,
// or ASTM C348.
NominalDimension nominal_of(const SpecimenDimension& d, double value_m, const TensileSpec& spec, bool standard) {
    if (standard) return {d.what, value_m, "ASTM C348 (the 40 x 40 mm prism on a 120 mm span)", {}};
    if (spec.config_file.empty()) return {d.what, value_m, "the command line", d.option};
    return {d.what, value_m, spec.config_file.string() + " " + spec.label, d.config_key};
}

std::string mm(double m) {
    std::ostringstream os;
    os << m * 1e3;
    return os.str();
}

}  // namespace

std::optional<TensileTestKind> parse_tensile_test(std::string_view name) { return parse_enum<TensileTestKind>(to_lower(trim(name))); }

double splitting_tensile_strength_pa(double peak_load_n, double length_m, double diameter_m) {
    return 2 * peak_load_n / (std::numbers::pi * length_m * diameter_m);  // ASTM C496: T = 2P/(π l d)
}

double flexural_strength_pa(double peak_load_n, double span_m, double width_m, double depth_m) {
    return 3 * peak_load_n * span_m / (2 * width_m * depth_m * depth_m);  // ASTM C348: Sf = 3PL/(2bd²)
}

double mc2010_alpha_flexural(double depth_m) {
    const double k = 0.06 * std::pow(depth_m * 1e3, 0.7);  // h in mm (fib MC2010 Eq. 5.1-7)
    return k / (1 + k);
}

double direct_tension_factor(TensileTestKind kind, const TensileGeometry& g) {
    return kind == TensileTestKind::splitting ? kMc2010AlphaSplitting : mc2010_alpha_flexural(g.depth_m);
}

std::string direct_tension_formula(TensileTestKind kind, const TensileGeometry& g) {
    if (kind == TensileTestKind::splitting) return "f_ct = 1.0 x f_ct,sp (fib Model Code 2010 5.1.5.1, alpha_sp = 1.0)";
    std::ostringstream os;
    os << "f_ct = alpha_fl x f_ct,fl, alpha_fl = 0.06 h^0.7 / (1 + 0.06 h^0.7) (fib Model Code 2010 5.1.5.1); h = " << mm(g.depth_m)
       << " mm: alpha_fl = " << common::format_significant(mc2010_alpha_flexural(g.depth_m), 4);
    return os.str();
}

std::string direct_tension_conversion(const std::vector<TensileResult>& tests, const std::vector<std::size_t>& members) {
    std::vector<std::string> formulas;
    bool splitting = false, flexural = false;
    for (auto i : members) {
        const TensileResult& t = tests[i];
        (t.test == TensileTestKind::splitting ? splitting : flexural) = true;
        const std::string f = direct_tension_formula(t.test, t.geometry);
        if (std::find(formulas.begin(), formulas.end(), f) == formulas.end()) formulas.push_back(f);
    }
    std::string text = splitting && flexural ? "pooled over the splitting and flexural specimens, each converted: " : "";
    for (std::size_t k = 0; k < formulas.size(); ++k) text += (k ? "; " : "") + formulas[k];
    return text;
}

TensileGeometry tensile_geometry(const RawTable& t, const TensileSpec& spec, std::vector<std::string>& notes) {
    TensileGeometry g;
    const bool splitting = spec.test == TensileTestKind::splitting;
    const auto* begin = splitting ? std::begin(kSplitting) : std::begin(kFlexural);
    const auto* end = splitting ? std::end(kSplitting) : std::end(kFlexural);
    for (const SpecimenDimension* d = begin; d != end; ++d) {
        double& value = g.*(d->field);
        if (spec.use_file_geometry)
            if (const auto v = metadata_dimension(t, d->keys, d->not_keys, Dimension::length, notes)) {
                value = *v;
                add_source(g.source, "file");
                continue;
            }
        const bool standard = !(spec.nominal.*(d->field) > 0);
        if (!standard) {
            value = spec.nominal.*(d->field);
            add_source(g.source, spec.nominal_source);
        } else if (d->standard > 0) {
            value = d->standard;
            add_source(g.source, "ASTM C348");
        } else {
            missing_dimension(*d, t, spec, spec.test);
        }
        if (spec.use_file_geometry) g.nominal_dimensions.push_back(nominal_of(*d, value, spec, standard));
    }
    return g;
}

TensileResult reduce_tensile_test(const LoadFrameTest& test, const TensileGeometry& g, TensileTestKind kind) {
    TensileResult r;
    r.file = test.file;
    r.format = test.format;
    r.test = kind;
    r.geometry = g;
    r.columns = test.columns;
    r.representative = test.representative;
    r.notes = test.notes;
    r.warnings = test.warnings;
    // The largest load sample (the specimen breaks at it; no smoothing, as for C109 cubes).
    const auto peak = std::max_element(test.load_n.begin(), test.load_n.end());
    if (peak == test.load_n.end() || !(*peak > 0))
        throw InputError(test.file, test.line.empty() ? 0 : test.line.front(), "no positive load sample: expected a load column with the test's loads");
    const auto i = static_cast<std::size_t>(peak - test.load_n.begin());
    r.peak_load_n = *peak;
    r.peak_line = i < test.line.size() ? test.line[i] : 0;
    r.strength_pa = kind == TensileTestKind::splitting ? splitting_tensile_strength_pa(r.peak_load_n, g.length_m, g.diameter_m)
                                                       : flexural_strength_pa(r.peak_load_n, g.span_m, g.width_m, g.depth_m);
    r.direct_factor = direct_tension_factor(kind, g);
    r.direct_equivalent_pa = r.direct_factor * r.strength_pa;
    if (i + 1 == test.load_n.size()) r.flags.push_back("peak_at_last_sample");  // the export may stop before failure
    if (kind == TensileTestKind::flexural &&
        (std::abs(g.width_m - kC348PrismWidth) > 1e-4 || std::abs(g.depth_m - kC348PrismDepth) > 1e-4 || std::abs(g.span_m - kC348Span) > 1e-4))
        r.notes.push_back("not the ASTM C348 prism and span (40 x 40 mm on 120 mm): Sf = 3PL/(2bd^2) with b = " + mm(g.width_m) +
                          " mm, d = " + mm(g.depth_m) + " mm, L = " + mm(g.span_m) + " mm");
    return r;
}

TensileResult read_tensile_bytes(std::string_view bytes, const std::string& file, const TensileSpec& spec, const ReadOptions& read) {
    const RawTable table = read_raw_export(bytes, file, read.format);
    const LoadFrameTest test = interpret_export(table, read);
    std::vector<std::string> notes;
    const TensileGeometry g = tensile_geometry(table, spec, notes);
    TensileResult r = reduce_tensile_test(test, g, spec.test);
    r.notes.insert(r.notes.end(), notes.begin(), notes.end());
    const bool nothing_from_file = g.source.find("file") == std::string::npos;
    report(nominal_geometry(file, g.nominal_dimensions, nothing_from_file), r.warnings, r.notes);
    return r;
}

TensileResult read_tensile_file(const std::filesystem::path& path, const std::string& display_name, const TensileSpec& spec,
                                const ReadOptions& read) {
    TensileResult r = read_tensile_bytes(read_file_bytes(path), path.string(), spec, read);
    r.file = display_name;
    return r;
}

}  // namespace gradem::lab
