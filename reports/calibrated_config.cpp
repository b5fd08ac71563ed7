#include "reports/calibrated_config.hpp"

#include <toml++/toml.h>

#include <cctype>
#include <cmath>
#include <functional>
#include <sstream>

#include "experiments/config/material_table.hpp"

namespace gradem::report {

using namespace gradem::cal;  // the calibration types these outputs are written from

namespace {

namespace fs = std::filesystem;

toml::table& table_of(toml::table& root, const char* name) {
    if (!root.contains(name) || !root[name].is_table()) root.insert_or_assign(name, toml::table{});
    return *root[name].as_table();
}

/// The sand's name made a file-name part ("Van Buren" -> "Van_Buren").
std::string tag_of(const std::string& sand) {
    std::string tag;
    for (char c : sand) tag += std::isalnum(static_cast<unsigned char>(c)) || c == '-' ? c : '_';
    return tag;
}

std::string file_name(const std::string& sand) { return "calibrated-" + tag_of(sand) + ".toml"; }

/// A config value x that the reader turns into exactly `si` (x · to_si == si), so the config
/// reproduces the calibration's runs bitwise: si / to_si, or a neighbour a few ulps away (the
/// quotient's rounding can miss by one). An SI value no decimal reaches (rare: a product of two
/// calibrated values) keeps the nearest, and the run differs in the last bits.
double exact_config(double si, const std::function<double(double)>& to_si_of, double guess) {
    double up = guess, down = guess;
    for (int ulps = 0; ulps <= 4; ++ulps) {
        if (to_si_of(up) == si) return up;
        if (to_si_of(down) == si) return down;
        up = std::nextafter(up, HUGE_VAL);
        down = std::nextafter(down, -HUGE_VAL);
    }
    return guess;
}

double exact_config(double si, double to_si) {
    return exact_config(si, [to_si](double x) { return x * to_si; }, si / to_si);
}

/// The row's value in config units that the config reader maps back to m's SI value exactly.
double exact_row_value(const exp::MaterialParameter& row, const exp::MaterialParams& m) {
    const auto si_of = [&](double x) {
        exp::MaterialParams t = m;
        exp::set_config_value(row, t, x);
        return row.get(t);
    };
    return exact_config(row.get(m), si_of, exp::config_value(row, m));
}

/// The material table's rows that the bond model uses, in config units.
void write_material(toml::table& material, const exp::MaterialParams& m) {
    material.insert_or_assign("model", std::string(bond_model_name(m.bond.model)));
    for (const exp::MaterialParameter& row : exp::material_table()) {
        if (!row.in_config || !row.applies_to(m.bond.model)) continue;
        const std::string key(row.key);
        if (row.flag) material.insert_or_assign(key, row.get_int(m) != 0);
        else if (row.integer) material.insert_or_assign(key, row.get_int(m));
        else material.insert_or_assign(key, exact_row_value(row, m));
    }
}

/// The base config as written (`root`: every section the calibration did not change stays),
/// with the calibrated material `m` for `sand`.
std::string calibrated_cube_config(const CalibrationProblem& p, toml::table root, const exp::MaterialParams& m,
                                   const std::string& sand, const std::string& stage_label, double edge) {
    // 1. The specimen: this sand, the result's edge (`edge` [m]: the fit's, or the scale-up's
    //    when the scales were set there) and paste size, absolute paths.
    toml::table& specimen = table_of(root, "specimen");
    specimen.insert_or_assign("sand", sand);
    if (!p.base.dataset.empty()) specimen.insert_or_assign("dataset", fs::absolute(p.base.dataset).string());
    if (!p.base.sieve_csv.empty()) specimen.insert_or_assign("sieve_csv", fs::absolute(p.base.sieve_csv).string());
    constexpr double kMm = 1e-3;  // [m] per config mm
    table_of(root, "genesis").insert_or_assign("edge_mm", exact_config(edge, kMm));
    table_of(root, "test").insert_or_assign("stop_fraction", p.base.test.loading.stop_fraction);  // the calibration's
    if (toml::table& test = table_of(root, "test"); p.base.test.loading.stop_strain_ratio > 0.0 || test.contains("stop_strain_ratio"))
        test.insert_or_assign("stop_strain_ratio", p.base.test.loading.stop_strain_ratio);  // the calibration's (absent: off)
    if (p.base.specimen.paste) {
        toml::table& paste = table_of(root, "paste");
        paste.insert_or_assign("min_diameter_mm", exact_config(p.base.specimen.paste->paste.min_diameter, kMm));
        paste.insert_or_assign("max_diameter_mm", exact_config(p.base.specimen.paste->paste.max_diameter, kMm));
        paste.insert_or_assign("itz_strength_factor", m.families.itz_strength_factor);
        paste.insert_or_assign("itz_modulus_factor", m.families.itz_modulus_factor);
    }
    // 2. The calibrated material.
    write_material(table_of(root, "material"), m);
    // 3. Outputs inside the calibration's folder; the packing cache shared with it.
    toml::table& output = table_of(root, "output");
    output.insert_or_assign("dir", fs::absolute(p.out_dir / ("compress-" + tag_of(sand))).string());
    output.insert_or_assign("cache_dir", fs::absolute(p.base.cache_dir).string());

    std::ostringstream text;
    text << "# The calibrated material of `gradem calibrate " << p.file.filename().string() << "` (" << stage_label
         << "), sand '" << sand << "',\n# on its base cube config " << fs::absolute(p.base_file).string()
         << "\n# (comments dropped; [material] holds every parameter of the bond model, config units).\n"
         << "#   gradem compress " << file_name(sand) << "\n\n"
         << root << "\n";
    return text.str();
}

}  // namespace

std::vector<std::pair<fs::path, std::string>> calibrated_cube_configs(const CalibrationProblem& p, const CalibrationResult& r) {
    std::vector<std::pair<fs::path, std::string>> files;
    const toml::table base = toml::parse_file(p.base_file.string());  // read once, copied per sand
    const ParameterSpace space(p.parameters, p.base.material);
    for (const CalibrationStage& st : r.stages) {
        if (st.result().empty()) continue;
        const exp::MaterialParams m = space.material(st.result());
        const double edge = st.scale_up.point.empty() ? p.base.specimen.genesis.edge : p.scale_up.edge;
        std::vector<std::size_t> sands = st.fitted;  // study mode: the predicted sands run the same parameters
        sands.insert(sands.end(), st.predicted.begin(), st.predicted.end());
        for (std::size_t s : sands)
            files.emplace_back(p.out_dir / file_name(p.sands[s]), calibrated_cube_config(p, base, m, p.sands[s], st.label, edge));
    }
    return files;
}

}  // namespace gradem::report
