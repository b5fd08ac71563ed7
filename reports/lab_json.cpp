#include <cmath>

#include "common/json_number.hpp"
#include "reports/lab_report.hpp"

namespace gradem::report {

using namespace gradem::lab;  // the lab statistics' types these outputs are written from

namespace {

using nlohmann::json;
constexpr auto number = common::json_number<json>;  // a number, or null when it is not finite

json summary(const SampleSummary& s, double scale) {
    return {{"n", s.n}, {"mean", number(s.mean * scale)}, {"std", number(s.std * scale)}, {"cv", number(s.cv)},
            {"min", number(s.min * scale)}, {"max", number(s.max * scale)}};
}

json popovics(const PopovicsFit& p) {
    return {{"converged", p.converged},
            {"elastic_modulus_mpa", number(p.elastic_modulus_pa / 1e6)},
            {"elastic_modulus_se_mpa", number(p.elastic_modulus_se_pa / 1e6)},
            {"peak_stress_mpa", number(p.peak_stress_pa / 1e6)},
            {"peak_stress_se_mpa", number(p.peak_stress_se_pa / 1e6)},
            {"strain_at_peak", number(p.strain_at_peak)},
            {"strain_at_peak_se", number(p.strain_at_peak_se)},
            {"n", number(p.n)},
            {"rms_residual_mpa", number(p.rms_residual_pa / 1e6)},
            {"points", p.points}};
}

json gradation(const SandResult& s) {
    const SieveAnalysis& sv = *s.sieve;
    const GradationIndices& g = *s.gradation;
    json sizes = json::array(), passing = json::array(), names = json::array();
    for (const auto& r : sv.rows) {  // coarsest first, as sieved
        sizes.push_back(r.opening_m * 1e3);
        passing.push_back(r.passing * 100);
        names.push_back(r.designation);
    }
    json j = {{"file", sv.file}, {"provenance", sv.provenance}, {"order", "coarsest first"},
              {"sieves", names}, {"sieves_mm", sizes}, {"percent_passing", passing},
              {"d10_mm", number(g.d10_m * 1e3)}, {"d30_mm", number(g.d30_m * 1e3)}, {"d50_mm", number(g.d50_m * 1e3)},
              {"d60_mm", number(g.d60_m * 1e3)}, {"cu", number(g.cu)}, {"cc", number(g.cc)},
              {"uscs", g.uscs}, {"uscs_name", g.uscs_name}, {"fineness_modulus", number(g.fineness_modulus)},
              {"gravel_pct", number(g.gravel_fraction * 100)}, {"sand_pct", number(g.sand_fraction * 100)},
              {"fines_pct", number(g.fines_fraction * 100)}, {"notes", g.notes}};
    if (s.c144) {
        json checks = json::array();
        for (const auto& c : s.c144->sieves)
            checks.push_back({{"sieve", c.designation}, {"opening_mm", c.opening_m * 1e3}, {"percent_passing", number(c.passing * 100)},
                              {"min_pct", c.min_passing * 100}, {"max_pct", c.max_passing * 100}, {"ok", c.ok}});
        j["c144_conforms"] = s.c144->conforms;
        j["c144_checks"] = checks;
        j["c144_violations"] = s.c144->violations;
        j["c144_max_retained_consecutive_pct"] = number(s.c144->max_retained_consecutive * 100);
        j["c144_retained_no50_to_no100_pct"] = number(s.c144->retained_no50_to_no100 * 100);
    } else {
        j["c144_conforms"] = nullptr;
    }
    return j;
}

// Splitting, flexural and direct-equivalent statistics, each only when the sand has such specimens.
void tensile_statistics(json& j, const SandResult& s, const LabStats& lab) {
    if (s.tensile.empty()) return;
    j["tension_batches"] = s.tension_batches;
    if (s.tensile_stats.splitting_pa.n) j["splitting_tensile_strength_mpa"] = summary(s.tensile_stats.splitting_pa, 1e-6);
    if (s.tensile_stats.flexural_pa.n) j["flexural_strength_mpa"] = summary(s.tensile_stats.flexural_pa, 1e-6);
    j["tensile_strength_mpa"] = summary(s.tensile_stats.direct_pa, 1e-6);
    j["tensile_strength_mpa"]["conversion"] = direct_tension_conversion(lab.tensile_tests, s.tensile);
}

json sand(const SandResult& s) {
    json j = {{"name", s.name}, {"n", s.cubes.size()}, {"batches", s.batches},
              {"specific_gravity", s.specific_gravity > 0 ? json(s.specific_gravity) : json(nullptr)},
              {"peak_stress_mpa", summary(s.stats.peak_stress_pa, 1e-6)},
              {"strain_at_peak", summary(s.stats.strain_at_peak, 1.0)},
              {"chord_modulus_mpa", summary(s.stats.chord_modulus_pa, 1e-6)},
              {"tangent_modulus_mpa", summary(s.stats.tangent_modulus_pa, 1e-6)},
              {"strain_at_peak_crosshead", summary(s.stats.strain_at_peak_crosshead, 1.0)}};
    json checks = json::array();
    for (const auto& b : s.range_checks)
        checks.push_back({{"batch", b.batch}, {"files", b.files}, {"mean_mpa", b.check.mean / 1e6},
                          {"range_pct", b.check.range_fraction * 100}, {"permissible_pct", number(b.check.permissible_fraction * 100)},
                          {"ok", b.check.ok}, {"discarded", b.discarded_file.empty() ? json(nullptr) : json(b.discarded_file)},
                          {"retest_required", b.check.retest_required}});
    j["c109_range_checks"] = checks;
    j["gradation"] = s.sieve ? gradation(s) : json(nullptr);
    return j;
}

json tensile_test(const TensileResult& t) {
    const TensileGeometry& g = t.geometry;
    json j = {{"file", t.file}, {"sand", t.sand}, {"batch", t.batch}, {"test", to_string(t.test)}, {"format", t.format},
              {"representative", t.representative}, {"columns", t.columns}, {"peak_load_n", number(t.peak_load_n)},
              {"peak_line", t.peak_line}};
    if (t.test == TensileTestKind::splitting) {
        j["diameter_mm"] = number(g.diameter_m * 1e3);
        j["length_mm"] = number(g.length_m * 1e3);
    } else {
        j["width_mm"] = number(g.width_m * 1e3);
        j["depth_mm"] = number(g.depth_m * 1e3);
        j["span_mm"] = number(g.span_m * 1e3);
    }
    j["geometry_source"] = g.source;
    j["strength_mpa"] = number(t.strength_pa / 1e6);
    j["conversion_factor"] = number(t.direct_factor);
    j["direct_equivalent_mpa"] = number(t.direct_equivalent_pa / 1e6);
    j["flags"] = t.flags;
    j["notes"] = t.notes;
    return j;
}

json cube(const CubeResult& c) {
    const CurveReduction& r = c.reduction;
    return {{"file", c.file}, {"sand", c.sand}, {"batch", c.batch}, {"format", c.format}, {"representative", c.representative},
            {"loaded_area_mm2", c.geometry.loaded_area_m2() * 1e6}, {"height_mm", c.geometry.height_m * 1e3},
            {"geometry_source", c.geometry.source}, {"columns", c.columns},
            {"peak_stress_mpa", number(r.peak_stress_pa / 1e6)}, {"strain_at_peak", number(r.strain_at_peak)},
            {"strain_at_peak_crosshead", number(r.strain_at_peak_crosshead)},
            {"chord_modulus_mpa", number(r.chord_modulus_pa / 1e6)}, {"chord_s1_mpa", number(r.chord_s1_pa / 1e6)},
            {"chord_s2_mpa", number(r.chord_s2_pa / 1e6)}, {"chord_strain2", number(r.chord_strain2)},
            {"tangent_modulus_mpa", number(r.tangent_modulus_pa / 1e6)}, {"poisson_ratio", number(r.poisson_ratio)},
            {"load_rate_n_per_s", number(c.load_rate_n_per_s)}, {"popovics", popovics(r.popovics)},
            {"flags", c.flags}, {"notes", c.notes}};
}

double scale_of(const std::string& quantity) { return quantity.find("_mpa") != std::string::npos ? 1e-6 : 1.0; }

}  // namespace

nlohmann::json lab_stats_to_json(const LabStats& lab) {
    json j;
    j["schema"] = "gradem-lab-results/1";
    j["dataset"] = lab.dataset;
    j["source"] = lab.source;
    j["representative_data"] = lab.representative;
    j["note"] = lab.note;
    j["definitions"] = {
        {"peak_stress_mpa", "ASTM C109: maximum load / loaded area"},
        {"strain_at_peak", "extensometer strain at the peak (vertex of a parabola through the ascending samples within 1 % of peak)"},
        {"strain_at_peak_crosshead", "crosshead displacement / specimen height at the peak sample"},
        {"chord_modulus_mpa", "ASTM C469: (S2 - S1)/(eps2 - 0.000050), S2 = " + std::to_string(lab.reduction.chord_upper_fraction) +
                                  " x peak, S1 = stress at strain " + std::to_string(lab.reduction.chord_lower_strain)},
        {"tangent_modulus_mpa", "slope of stress vs strain at " + std::to_string(lab.reduction.tangent_fraction) + " x peak"},
        {"popovics", "Popovics (1973) law fitted to the ascending branch (Ceres), standard errors from the fit covariance"},
        {"statistics", "std is the sample standard deviation (n - 1); all cubes included, flags do not exclude"}};
    if (!lab.tensile_tests.empty()) {
        j["definitions"]["splitting_tensile_strength_mpa"] = "ASTM C496: T = 2P/(pi l d), P maximum load, l length, d diameter";
        j["definitions"]["flexural_strength_mpa"] =
            "ASTM C348 (centre-point loading): Sf = 3PL/(2bd^2), L span, b width, d depth; 0.0028 P for the 40 x 40 mm prism on 120 mm";
        j["definitions"]["tensile_strength_mpa"] =
            "direct tensile strength per fib Model Code 2010 5.1.5.1: alpha_sp = 1.0 x splitting, alpha_fl = 0.06 h^0.7/(1 + 0.06 h^0.7) "
            "x flexural (h depth in mm); a sand with both kinds pools the converted values of every specimen";
    }
    j["sands"] = json::array();
    for (const auto& s : lab.sands) {
        j["sands"].push_back(sand(s));
        tensile_statistics(j["sands"].back(), s, lab);
    }
    j["cubes"] = json::array();
    for (const auto& c : lab.cubes) j["cubes"].push_back(cube(c));
    j["tensile_tests"] = json::array();
    for (const auto& t : lab.tensile_tests) j["tensile_tests"].push_back(tensile_test(t));
    j["comparisons"] = json::array();
    for (const auto& c : lab.comparisons) {
        const double k = scale_of(c.quantity);
        j["comparisons"].push_back({{"quantity", c.quantity}, {"sand_a", c.sand_a}, {"sand_b", c.sand_b},
                                    {"n_a", c.test.n1}, {"n_b", c.test.n2}, {"mean_difference", number(c.test.mean_difference * k)},
                                    {"welch_t", number(c.test.t)}, {"dof", number(c.test.dof)}, {"p_value", number(c.test.p_value)},
                                    {"cohens_d", number(c.test.cohens_d)}, {"hedges_g", number(c.test.hedges_g)}});
    }
    return j;
}

}  // namespace gradem::report
