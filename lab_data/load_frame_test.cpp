#include "lab_data/load_frame_test.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <sstream>

#include "common/input_error.hpp"
#include "lab_data/channel_roles.hpp"
#include "lab_data/units.hpp"

namespace gradem::lab {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

Dimension role_quantity(ChannelRole role) {
    switch (role) {
        case ChannelRole::time: return Dimension::time;
        case ChannelRole::load: return Dimension::force;
        case ChannelRole::crosshead: return Dimension::length;
        case ChannelRole::strain:
        case ChannelRole::lateral_strain: return Dimension::strain;
        case ChannelRole::stress: return Dimension::stress;
    }
    return Dimension::force;
}

// The unit of a role column, from the override or the file; InputError when missing/unknown,
// and when an override contradicts a unit the file's header states (a different scale: the
// header is more likely right than a guess), unless the override is forced with a leading '!'.
Unit column_unit(const RawTable& t, const RawColumn& col, ChannelRole role, const ChannelOverrides& o) {
    const auto it = o.unit.find(role);
    const bool forced = it != o.unit.end() && !trim(it->second).empty() && trim(it->second).front() == '!';
    const std::string spelling = it == o.unit.end() ? col.unit : forced ? trim(it->second).substr(1) : it->second;
    if (it != o.unit.end() && !forced) {
        const auto header = parse_unit(col.unit), given = parse_unit(spelling);
        if (header && given && header->to_si != given->to_si)
            throw InputError(t.file, col.header_line,
                             column_prefix(col.name) + "the unit override '" + spelling + "' for " + to_string(role) +
                                 " contradicts the header's unit '" + col.unit + "'; drop the override, or force it with '!" +
                                 spelling + "' (--unit " + to_string(role) + "=!" + spelling + ", or [columns] " + to_string(role) +
                                 "_unit = \"!" + spelling + "\")");
    }
    const Dimension want = role_quantity(role);
    const std::string hint = std::string("expected a ") + to_string(want) + " unit (" + accepted_units(want) +
                             "); set [columns] " + to_string(role) + "_unit in the config if the file does not say";
    if (trim(spelling).empty()) throw InputError(t.file, col.header_line, column_prefix(col.name) + "no unit given; " + hint);
    const auto unit = parse_unit(spelling);
    if (!unit) throw InputError(t.file, col.header_line, column_prefix(col.name) + "unit '" + spelling + "' is unknown; " + hint);
    const bool extensometer_length = (role == ChannelRole::strain || role == ChannelRole::lateral_strain) && unit->dimension == Dimension::length;
    if (unit->dimension != want && !extensometer_length)
        throw InputError(t.file, col.header_line, column_prefix(col.name) + "unit '" + spelling + "' is a " +
                                                      to_string(unit->dimension) + " unit; " + hint);
    return *unit;
}

// Cells of one column in SI; empty cells become NaN, text is an error naming line and column.
std::vector<double> column_values(const RawTable& t, const RawColumn& col, const Unit& unit) {
    std::vector<double> v(t.rows(), kNaN);
    for (std::size_t r = 0; r < t.rows(); ++r) {
        const Cell& cell = col.cells[r];
        if (is_blank(cell.text)) continue;
        const auto x = parse_number(cell.text, t.dialect, cell.quoted);
        if (!x)
            throw InputError(t.file, t.row_line[r], column_prefix(col.name) + "'" + trim(cell.text) +
                                                        "' is not a number (expected " + to_string(unit.dimension) +
                                                        " in " + unit.symbol + ", decimal separator '" + t.dialect.decimal + "')");
        v[r] = *x * unit.to_si;
    }
    return v;
}

// A length from metadata ("50.21 mm", or value + unit cell); nullopt when the value is not a number.
std::optional<double> meta_length(const RawTable& t, const MetaEntry& m, Dimension q, std::vector<std::string>& notes) {
    std::string value = trim(m.value), unit = trim(m.unit);
    if (const auto sp = value.find(' '); sp != std::string::npos && unit.empty()) {
        unit = trim(std::string_view(value).substr(sp + 1));
        value = value.substr(0, sp);
    }
    const auto x = parse_number(value, t.dialect, true);
    if (!x) return std::nullopt;
    if (unit.empty()) {
        notes.push_back("metadata '" + m.key + "' has no unit: taken as " + (q == Dimension::area ? "mm²" : "mm"));
        return *x * (q == Dimension::area ? 1e-6 : 1e-3);
    }
    const auto u = parse_unit(unit);
    if (!u || u->dimension != q)
        throw InputError(t.file, m.line, "metadata '" + m.key + "': unit '" + unit + "' is not a " + to_string(q) +
                                             " unit (expected " + accepted_units(q) + ")");
    return *x * u->to_si;
}

// The nominal value of a cube dimension the file does not state, with where it was set.
NominalDimension nominal_dimension(const ReadOptions& o, const char* name, double value_m) {
    const auto it = o.nominal_origin.find(name);
    if (it == o.nominal_origin.end()) return {name, value_m, kDefaultCubeOrigin, {}};
    return {name, value_m, it->second, std::string(name) + "_mm"};
}

// The file's dimensions where its metadata states them, else the nominal ones (those are listed
// in test.nominal_dimensions for the warning).
SpecimenGeometry geometry_from(const RawTable& t, const ReadOptions& o, LoadFrameTest& test) {
    SpecimenGeometry g = o.nominal;
    if (!o.use_file_geometry) return g;
    bool from_file = false;
    auto take = [&](std::initializer_list<const char*> keys, std::initializer_list<const char*> not_keys, double& field, Dimension q) {
        const auto v = metadata_dimension(t, keys, not_keys, q, test.notes);
        if (v) { field = *v; from_file = true; }
        return v.has_value();
    };
    const bool width = take({"width", "breite"}, {"rate"}, g.width_m, Dimension::length);
    const bool depth = take({"depth", "thickness", "tiefe", "dicke", "länge", "length"}, {"gauge", "gage", "mess", "extensometer", "rate"}, g.depth_m, Dimension::length);
    const bool height = take({"height", "höhe"}, {"rate"}, g.height_m, Dimension::length);
    take({"gauge length", "gage length", "messlänge", "extensometer length"}, {}, g.gauge_length_m, Dimension::length);
    double diameter = 0;
    const bool round = take({"diameter", "durchmesser"}, {}, diameter, Dimension::length);
    if (diameter > 0) g.area_m2 = std::numbers::pi * diameter * diameter / 4;
    const bool area = take({"area", "fläche", "querschnitt"}, {}, g.area_m2, Dimension::area) || round;
    if (from_file) g.source = "file";
    if (!area) {  // a stated area (or diameter) makes width and depth irrelevant
        if (!width) test.nominal_dimensions.push_back(nominal_dimension(o, "width", g.width_m));
        if (!depth) test.nominal_dimensions.push_back(nominal_dimension(o, "depth", g.depth_m));
    }
    if (!height) test.nominal_dimensions.push_back(nominal_dimension(o, "height", g.height_m));
    test.no_file_dimensions = !width && !depth && !height && !area;
    return g;
}

// Offsets a channel to its first finite value and flips it so that it is positive at `at`.
void zero_and_orient(std::vector<double>& v, std::size_t at, const char* what, std::vector<std::string>& notes) {
    const auto first = std::find_if(v.begin(), v.end(), [](double x) { return std::isfinite(x); });
    if (first == v.end()) return;
    const double v0 = *first;
    for (double& x : v) x -= v0;
    if (v[at] < 0) {
        for (double& x : v) x = -x;
        notes.push_back(std::string(what) + " was negative in compression (machine coordinates): sign flipped");
    }
}

// Keeps the rows that have a load and the strain source (extensometer, else crosshead); other
// channels may be NaN (e.g. an MTS 793 block without a time column).
void drop_incomplete_rows(LoadFrameTest& test) {
    const std::vector<double>& strain_source = test.strain.empty() ? test.crosshead_m : test.strain;
    std::vector<std::size_t> keep;
    for (std::size_t r = 0; r < test.load_n.size(); ++r)
        if (std::isfinite(test.load_n[r]) && std::isfinite(strain_source[r])) keep.push_back(r);
    if (keep.size() == test.load_n.size()) return;
    auto filter = [&](auto& v) {
        if (v.empty()) return;
        std::remove_reference_t<decltype(v)> out;
        for (auto k : keep) out.push_back(v[k]);
        v.swap(out);
    };
    std::vector<int> skipped;
    for (std::size_t r = 0, k = 0; r < test.load_n.size(); ++r) {
        if (k < keep.size() && keep[k] == r) ++k;
        else skipped.push_back(r < test.line.size() ? test.line[r] : 0);
    }
    report(rows_skipped(test.file, skipped, "no load or strain value"), test.warnings, test.notes);
    for (auto* v : {&test.load_n, &test.time_s, &test.crosshead_m, &test.strain, &test.lateral_strain}) filter(*v);
    filter(test.line);
}

}  // namespace

std::optional<ChannelRole> parse_role(std::string_view name) { return parse_enum<ChannelRole>(to_lower(trim(name))); }

std::optional<double> metadata_dimension(const RawTable& t, std::initializer_list<const char*> keys,
                                         std::initializer_list<const char*> not_keys, Dimension q, std::vector<std::string>& notes) {
    for (const auto& m : t.metadata) {
        const std::string k = to_lower(m.key);
        bool excluded = false;
        for (const char* n : not_keys) excluded = excluded || k.find(n) != std::string::npos;
        if (excluded) continue;
        for (const char* key : keys)
            if (k.find(key) != std::string::npos) {
                const auto v = meta_length(t, m, q, notes);
                return v && *v > 0 ? v : std::nullopt;
            }
    }
    return std::nullopt;
}

std::optional<std::string> SpecimenGeometry::invalid_reason() const {
    auto positive = [](const char* f, double v) -> std::optional<std::string> {
        if (v > 0 && std::isfinite(v)) return std::nullopt;
        std::ostringstream os;
        os << "SpecimenGeometry::" << f << " = " << v << " violates > 0";
        return os.str();
    };
    if (auto r = positive("width_m", width_m)) return r;
    if (auto r = positive("depth_m", depth_m)) return r;
    if (auto r = positive("height_m", height_m)) return r;
    return std::nullopt;
}

LoadFrameTest interpret_export(const RawTable& t, const ReadOptions& o) {
    LoadFrameTest test;
    test.file = t.file;
    test.format = t.format;
    test.encoding = t.encoding;
    test.notes = t.notes;
    const RoleAssignment roles = assign_roles(t, o.channels);
    test.notes.insert(test.notes.end(), roles.notes.begin(), roles.notes.end());
    std::string all;
    for (const auto& c : t.columns) all += (all.empty() ? "" : ", ") + c.name + (c.unit.empty() ? "" : " [" + c.unit + "]");
    const int header_line = t.columns.empty() ? 0 : t.columns.front().header_line;
    if (!roles.column.count(ChannelRole::load) && !roles.column.count(ChannelRole::stress))
        throw InputError(t.file, header_line, "no load column: expected a force column named like Load, Force, Axial Force "
                                              "or Kraft (N, kN, lbf) or a stress column (MPa, psi); columns are: " + all);
    if (!roles.column.count(ChannelRole::strain) && !roles.column.count(ChannelRole::crosshead))
        throw InputError(t.file, header_line, "no strain or displacement column: expected an extensometer strain (mm/mm, %, µε) "
                                              "or a crosshead/actuator displacement (mm, in); columns are: " + all);
    test.geometry = geometry_from(t, o, test);
    if (auto why = test.geometry.invalid_reason()) throw InputError(t.file, 0, *why);

    std::map<ChannelRole, std::vector<double>> v;
    for (const auto& [role, index] : roles.column) {
        const RawColumn& col = t.columns[index];
        const Unit unit = column_unit(t, col, role, o.channels);
        v[role] = column_values(t, col, unit);
        test.columns[to_string(role)] = col.name + " [" + unit.symbol + "]";
        const bool is_strain = role == ChannelRole::strain || role == ChannelRole::lateral_strain;
        if (is_strain && unit.dimension == Dimension::length) {  // extensometer reports its elongation
            if (!(test.geometry.gauge_length_m > 0))
                throw InputError(t.file, col.header_line, column_prefix(col.name) + "extensometer reports a length (" + unit.symbol +
                                                              ") but no gauge length is known; set [specimen] gauge_length_mm");
            for (double& x : v[role]) x /= test.geometry.gauge_length_m;
        }
    }
    const double area = test.geometry.loaded_area_m2();
    test.load_n = v.count(ChannelRole::load) ? v[ChannelRole::load] : std::vector<double>{};
    if (test.load_n.empty()) {
        for (double s : v[ChannelRole::stress]) test.load_n.push_back(s * area);
        test.notes.push_back("no load column: load = stress × loaded area");
    }
    test.time_s = v[ChannelRole::time];
    test.crosshead_m = v[ChannelRole::crosshead];
    test.strain = v[ChannelRole::strain];
    test.lateral_strain = v[ChannelRole::lateral_strain];
    test.line = t.row_line;
    if (test.strain.empty())
        test.notes.push_back("no extensometer strain: strain taken from crosshead displacement / specimen height");
    drop_incomplete_rows(test);
    if (test.load_n.size() < 5)
        throw InputError(t.file, header_line, "fewer than 5 complete data rows (load and strain/displacement)");

    const auto [min_it, max_it] = std::minmax_element(test.load_n.begin(), test.load_n.end());
    if (-*min_it > *max_it) {
        for (double& x : test.load_n) x = -x;
        test.notes.push_back("load was negative in compression (machine coordinates): sign flipped to compression-positive");
    }
    const auto peak = static_cast<std::size_t>(std::max_element(test.load_n.begin(), test.load_n.end()) - test.load_n.begin());
    if (!test.time_s.empty()) zero_and_orient(test.time_s, test.time_s.size() - 1, "time", test.notes);
    zero_and_orient(test.crosshead_m, peak, "crosshead displacement", test.notes);
    zero_and_orient(test.strain, peak, "extensometer strain", test.notes);
    if (!test.lateral_strain.empty()) {
        const double l0 = test.lateral_strain.front();
        for (double& x : test.lateral_strain) x -= l0;
    }
    for (const auto& m : t.metadata)
        if (m.value.find("REPRESENTATIVE") != std::string::npos || m.key.find("REPRESENTATIVE") != std::string::npos)
            test.representative = true;
    return test;
}

LabWarning cube_geometry_warning(const LoadFrameTest& test) {
    return nominal_geometry(test.file, test.nominal_dimensions, test.no_file_dimensions);
}

LoadFrameTest read_load_frame_bytes(std::string_view bytes, const std::string& file, const ReadOptions& options) {
    return interpret_export(read_raw_export(bytes, file, options.format), options);
}

LoadFrameTest read_load_frame_test(const std::filesystem::path& path, const ReadOptions& options) {
    return read_load_frame_bytes(read_file_bytes(path), path.string(), options);
}

StressStrainCurve to_stress_strain(const LoadFrameTest& test) {
    StressStrainCurve c;
    const double area = test.geometry.loaded_area_m2();
    for (double f : test.load_n) c.stress_pa.push_back(f / area);
    for (double d : test.crosshead_m) c.crosshead_strain.push_back(d / test.geometry.height_m);
    c.strain = test.strain.empty() ? c.crosshead_strain : test.strain;
    c.lateral_strain = test.lateral_strain;
    c.time_s = test.time_s;
    return c;
}

}  // namespace gradem::lab
