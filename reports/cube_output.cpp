#include "reports/cube_output.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <memory>
#include <nlohmann/json.hpp>
#include <sstream>

#include "common/atomic_file.hpp"
#include "common/json_number.hpp"
#include "experiments/config/material_table.hpp"
#include "reports/vtk_output.hpp"

namespace gradem::report {

using namespace gradem::exp;  // the virtual tests' types these outputs are written from

namespace {

using json = nlohmann::ordered_json;  // keys in the order written: the headline numbers first

constexpr double kMpa = 1.0e-6, kGpa = 1.0e-9, kMm = 1.0e3;  // SI -> display unit

constexpr auto num = common::json_number<json>;  // a number, or null when it is not finite

double relative_change(double base, double changed) {
    return std::isfinite(base) && std::isfinite(changed) && base != 0.0 ? (changed - base) / base : std::nan("");
}

/// Platen strain at `step`, linear between the recorded points around it (clamped at the ends).
double platen_strain_at(const std::vector<CurvePoint>& curve, std::int64_t step) {
    if (curve.empty()) return std::nan("");
    const auto after = std::lower_bound(curve.begin(), curve.end(), step,
                                        [](const CurvePoint& p, std::int64_t s) { return p.step < s; });
    if (after == curve.begin()) return curve.front().platen_strain;
    if (after == curve.end()) return curve.back().platen_strain;
    const CurvePoint& a = *(after - 1);
    const CurvePoint& b = *after;
    const double t = static_cast<double>(step - a.step) / static_cast<double>(b.step - a.step);
    return a.platen_strain + t * (b.platen_strain - a.platen_strain);
}

json popovics_json(const lab::PopovicsFit& f) {
    return {{"converged", f.converged},
            {"elastic_modulus_mpa", num(f.elastic_modulus_pa * kMpa)},
            {"elastic_modulus_se_mpa", num(f.elastic_modulus_se_pa * kMpa)},
            {"peak_stress_mpa", num(f.peak_stress_pa * kMpa)},
            {"peak_stress_se_mpa", num(f.peak_stress_se_pa * kMpa)},
            {"strain_at_peak", num(f.strain_at_peak)},
            {"strain_at_peak_se", num(f.strain_at_peak_se)},
            {"n", num(f.n)},
            {"rms_residual_mpa", num(f.rms_residual_pa * kMpa)},
            {"points", f.points},
            {"message", f.message}};
}

/// The material in SI (grouped as the structs) and in the config's keys and units ([material]),
/// every row of the material table that the bond model uses.
json material_json(const MaterialParams& m) {
    const char* model = bond_model_name(m.bond.model);
    json si = {{"model", model}}, display = {{"model", model}};
    for (const MaterialParameter& p : material_table()) {
        if (!p.in_config || !p.applies_to(m.bond.model)) continue;
        json& group = p.si_group.empty() ? si : si[std::string(p.si_group)];
        if (p.integer) {
            group[std::string(p.si_name)] = p.get_int(m);
            display[std::string(p.key)] = p.get_int(m);
        } else {
            group[std::string(p.si_name)] = p.get(m);
            display[std::string(p.key)] = config_value(p, m);
        }
    }
    return {{"si", si}, {"display", display}};
}

json specimen_json(const Packing& k, const CubeConfig& c) {
    const std::size_t n = k.radius.size();
    return {{"particles", n},
            {"edge_mm", k.edge() * kMm},
            {"edge_over_d50", num(k.edge_over_d50)},
            {"d50_mm", num(k.grains.d50 * kMm)},
            {"porosity", num(k.porosity)},
            {"mean_coordination", num(k.mean_coordination)},
            {"converged", k.converged},
            {"seed", c.specimen.seed},
            {"sand", c.sand.empty() ? c.sieve_csv.string() : c.sand},
            {"min_diameter_mm", c.specimen.size_rule.min_diameter * kMm},
            {"max_diameter_mm", c.specimen.size_rule.max_diameter * kMm},
            {"scale", c.specimen.size_rule.scale}};
}

/// Explicit paste: the fill's report and the bonds per family pair.
json paste_json(const PasteReport& p, const CubeTestResult& r) {
    return {{"sand_count", p.sand_count},
            {"paste_count", p.paste_count},
            {"paste_d_min_mm", p.paste_d_min * kMm},
            {"paste_d_max_mm", p.paste_d_max * kMm},
            {"size_ratio", num(p.size_ratio)},
            {"sand_fraction", num(p.sand_fraction)},
            {"paste_fraction", num(p.paste_fraction)},
            {"paste_particle_fraction", num(p.paste_particle_fraction)},
            {"mix_sand_fraction", num(p.mix_sand_fraction)},
            {"mix_paste_fraction", num(p.mix_paste_fraction)},
            {"mix_air_fraction", num(p.mix_air_fraction)},
            {"void_fraction", num(p.void_fraction)},
            {"max_overlap_sand", num(p.max_overlap_sand)},
            {"bonds", {{"sand_sand", r.bonds_sand_sand}, {"sand_paste", r.bonds_itz}, {"paste_paste", r.bonds_paste_paste}}}};
}

json rate_check_json(const RateCheck& r) {
    return {{"strain_rate_per_s", r.strain_rate},
            {"half_rate_per_s", r.half_rate},
            {"peak_stress_mpa", num(r.peak_stress * kMpa)},
            {"peak_stress_half_rate_mpa", num(r.peak_stress_half * kMpa)},
            {"chord_modulus_mpa", num(r.chord_modulus * kMpa)},
            {"chord_modulus_half_rate_mpa", num(r.chord_modulus_half * kMpa)},
            {"peak_change", num(r.peak_change)},
            {"modulus_change", num(r.modulus_change)},
            {"platen_imbalance", num(r.imbalance)},
            {"platen_imbalance_half_rate", num(r.imbalance_half)},
            {"imbalance_falls_with_rate", r.imbalance_falls()},
            {"stop_reason_half_rate", r.stop_reason_half},
            {"diverged_half_rate", r.diverged_half}};
}

}  // namespace

RateCheck compare_rates(const CubeTestResult& base, const CubeTestResult& half, double strain_rate) {
    RateCheck r;
    r.strain_rate = strain_rate;
    r.half_rate = 0.5 * strain_rate;
    r.peak_stress = base.macro.peak_stress_pa;
    r.peak_stress_half = half.macro.peak_stress_pa;
    r.chord_modulus = base.macro.chord_modulus_pa;
    r.chord_modulus_half = half.macro.chord_modulus_pa;
    r.peak_change = relative_change(r.peak_stress, r.peak_stress_half);
    r.modulus_change = relative_change(r.chord_modulus, r.chord_modulus_half);
    r.imbalance = base.platen_imbalance;
    r.imbalance_half = half.platen_imbalance;
    r.stop_reason_half = half.test.stop_reason;
    r.diverged_half = half.diverged();
    return r;
}

bool RateCheck::imbalance_falls() const { return imbalance_half <= kInertialImbalanceShare * imbalance; }

std::string imbalance_verdict(const RateCheck& check, double limit) {
    if (!(check.imbalance > limit)) return {};
    std::ostringstream out;
    out.precision(2);
    out << std::fixed << "the ends' stresses differ by " << 100.0 * check.imbalance << " % at the rate, "
        << 100.0 * check.imbalance_half << " % at half of it: ";
    if (check.imbalance_falls()) out << "inertia (it falls with the rate); lower the strain rate";
    else out << "not inertia, which would halve with the rate, but cracks ahead of the peak; the rate is quasi-static as far as this shows";
    return out.str();
}

std::string load_curve_csv(const CubeTestResult& r) {
    std::ostringstream out;
    out.precision(10);
    out << "step,time_s,platen_strain,gauge_strain,lateral_strain,stress_mpa,stress_top_mpa,stress_bottom_mpa,"
           "broken_tension,broken_shear,kinetic_energy_j\n";
    for (const CurvePoint& p : r.test.curve)
        out << p.step << ',' << p.time << ',' << p.platen_strain << ',' << p.gauge_strain << ',' << p.lateral_strain << ','
            << p.stress * kMpa << ',' << p.stress_top * kMpa << ',' << p.stress_bottom * kMpa << ',' << p.broken_tension << ','
            << p.broken_shear << ',' << p.kinetic_energy << '\n';
    return out.str();
}

std::string cracks_csv(const CubeTestResult& r) {
    std::ostringstream out;
    out.precision(10);
    out << "step,time_s,platen_strain,x_m,y_m,z_m,nx,ny,nz,mode,i,j,bond_radius_m,tensile_stress_mpa,shear_stress_mpa\n";
    for (const BreakEvent& e : r.cracks)
        out << e.step << ',' << e.time << ',' << platen_strain_at(r.test.curve, e.step) << ',' << e.position.x << ','
            << e.position.y << ',' << e.position.z << ',' << e.normal.x << ',' << e.normal.y << ',' << e.normal.z << ','
            << (e.mode == BondState::broken_shear ? "shear" : "tension") << ',' << e.i << ',' << e.j << ',' << e.bond_radius
            << ',' << e.tensile_stress * kMpa << ',' << e.shear_stress * kMpa << '\n';
    return out.str();
}

std::string macro_json(const CubeTestResult& r, const CubeConfig& c, const Packing& k, double strain_rate,
                       const std::optional<RateCheck>& rate_check, const PasteReport* paste) {
    const lab::CurveReduction& m = r.macro;
    std::int64_t tension = 0, shear = 0;
    for (const BreakEvent& e : r.cracks) ++(e.mode == BondState::broken_shear ? shear : tension);
    const double wall = r.test.wall_seconds;
    const double particle_steps = static_cast<double>(r.particles) * static_cast<double>(r.test.steps);
    json j = {
        {"config", c.file.string()},
        {"peak_stress_mpa", num(m.peak_stress_pa * kMpa)},
        {"strain_at_peak", num(m.strain_at_peak)},
        {"strain_at_peak_platen", num(r.strain_at_peak_platen)},
        {"chord_modulus_mpa", num(m.chord_modulus_pa * kMpa)},
        {"tangent_modulus_mpa", num(m.tangent_modulus_pa * kMpa)},
        {"poisson_ratio", num(m.poisson_ratio)},
        {"reduction", {{"status", to_string(m.status)},
                       {"message", m.message},
                       {"chord_s1_mpa", num(m.chord_s1_pa * kMpa)},
                       {"chord_s2_mpa", num(m.chord_s2_pa * kMpa)},
                       {"chord_strain2", num(m.chord_strain2)},
                       {"strain_at_peak_crosshead", num(m.strain_at_peak_crosshead)}}},
        {"popovics", popovics_json(m.popovics)},
        {"run", {{"particles", r.particles},
                 {"bonds", r.bonds},
                 {"steps", r.test.steps},
                 {"time_step_s", num(r.time_step)},
                 {"strain_rate_per_s", num(strain_rate)},
                 {"wall_seconds", num(wall)},
                 {"particle_steps_per_s", num(wall > 0.0 ? particle_steps / wall : std::nan(""))},
                 {"stop_reason", r.test.stop_reason},
                 {"diverged", r.diverged()},
                 {"platen_imbalance", num(r.platen_imbalance)},
                 {"settle_ratio", num(r.settle_ratio)},
                 {"settle_steps", r.settle_steps}}},
        {"broken_bonds", {{"tension", tension}, {"shear", shear}, {"total", tension + shear}}},
        {"warnings", r.warnings},
        {"material", material_json(c.material)},
        {"specimen", specimen_json(k, c)},
    };
    if (rate_check) j["rate_check"] = rate_check_json(*rate_check);
    if (paste) j["paste"] = paste_json(*paste, r);
    return j.dump(2) + "\n";
}

SnapshotCallback vtk_snapshots(const std::filesystem::path& dir, int every) {
    struct State {
        PvdSeries series;
        std::vector<Vec3> reference;  // positions at the first snapshot [m]
        std::int64_t points = 0;
    };
    const int stride = every > 0 ? every : 20;
    auto state = std::make_shared<State>(State{PvdSeries(dir / "cube.pvd"), {}, 0});
    return [state, stride, dir](const World& world, const CurvePoint& p) {
        const std::int64_t index = state->points++;
        if (index % stride != 0) return;
        if (state->reference.empty()) state->reference = world.particles().position;
        char suffix[32];
        std::snprintf(suffix, sizeof suffix, "_%06lld.vtp", static_cast<long long>(index / stride));
        const auto name = [&](const char* what) { return dir / (std::string(what) + suffix); };
        write_particles_vtp(name("particles"), world, &state->reference);
        write_bonds_vtp(name("bonds"), world);
        write_cracks_vtp(name("cracks"), world.break_events());
        state->series.add(p.time, name("particles"), 0);
        state->series.add(p.time, name("bonds"), 1);
        state->series.add(p.time, name("cracks"), 2);
        state->series.write();
    };
}

void write_cube_outputs(const std::filesystem::path& dir, const CubeTestResult& r, const CubeConfig& c, const Packing& k,
                        double strain_rate, const std::optional<RateCheck>& rate_check, const PasteReport* paste) {
    common::write_file_atomically(dir / "load_curve.csv", load_curve_csv(r));
    common::write_file_atomically(dir / "cracks.csv", cracks_csv(r));
    common::write_file_atomically(dir / "macro.json", macro_json(r, c, k, strain_rate, rate_check, paste));
}

}  // namespace gradem::report
