#include <algorithm>
#include <cmath>
#include <cstdio>
#include <ostream>
#include <sstream>

#include "common/atomic_file.hpp"
#include "common/input_error.hpp"
#include "common/number_format.hpp"
#include "reports/lab_report.hpp"

namespace gradem::report {

using namespace gradem::lab;  // the lab statistics' types these outputs are written from

namespace {

namespace fs = std::filesystem;

/// Tables: `decimals` after the point, "-" when missing; CSV cells: 8 significant digits, empty when missing.
std::string f(double v, int decimals) { return common::format_fixed(v, decimals); }
std::string g(double v) { return common::format_significant(v, 8, ""); }

std::string csv_text(const std::string& s) {
    if (s.find_first_of(",\"\n") == std::string::npos) return s;
    std::string out = "\"";
    for (char c : s) out += c == '"' ? std::string("\"\"") : std::string(1, c);
    return out + "\"";
}

std::string banner(const LabStats& lab) {
    return lab.representative ? "# REPRESENTATIVE DATA (not measurements): " + lab.note + "\n" : std::string();
}

std::string pad(const std::string& s, std::size_t w) { return s.size() >= w ? s + " " : s + std::string(w - s.size(), ' '); }

struct Row {
    const char* label;
    const SampleSummary SandStatistics::*field;
    double scale;
    int decimals;
    const char* csv_name;
};
const Row kRows[] = {{"Compressive strength (MPa), ASTM C109", &SandStatistics::peak_stress_pa, 1e-6, 2, "peak_stress_mpa"},
                     {"Strain at peak, extensometer (-)", &SandStatistics::strain_at_peak, 1.0, 5, "strain_at_peak"},
                     {"Chord modulus (MPa), ASTM C469", &SandStatistics::chord_modulus_pa, 1e-6, 0, "chord_modulus_mpa"},
                     {"Tangent modulus at 50 % of peak (MPa)", &SandStatistics::tangent_modulus_pa, 1e-6, 0, "tangent_modulus_mpa"},
                     {"Strain at peak, crosshead (-)", &SandStatistics::strain_at_peak_crosshead, 1.0, 5, "strain_at_peak_crosshead"}};

struct TensileRow {
    const char* label;
    const SampleSummary TensileStatistics::*field;
    const char* csv_name;
};
const TensileRow kTensileRows[] = {
    {"Splitting tensile strength (MPa), ASTM C496", &TensileStatistics::splitting_pa, "splitting_tensile_strength_mpa"},
    {"Flexural strength (MPa), ASTM C348", &TensileStatistics::flexural_pa, "flexural_strength_mpa"},
    {"Direct tensile strength equivalent (MPa), fib Model Code 2010 5.1.5.1", &TensileStatistics::direct_pa, "tensile_strength_mpa"}};

void print_gradation(std::ostream& out, const LabStats& lab) {
    std::vector<const SandResult*> sands;
    for (const auto& s : lab.sands)
        if (s.sieve) sands.push_back(&s);
    if (sands.empty()) return;
    out << "\nTable 2 - Sieve analysis, percent passing\n" << pad("Sieve", 9) << pad("Opening (mm)", 14);
    for (const auto* s : sands) out << pad(s->name, 14);
    out << "C144 limits\n";
    const SieveAnalysis& first = *sands.front()->sieve;
    for (const auto& row : first.rows) {
        out << pad(row.designation, 9) << pad(f(row.opening_m * 1e3, 3), 14);
        for (const auto* s : sands) {
            const auto i = s->sieve->curve.find_sieve(row.opening_m);
            out << pad(i ? f(s->sieve->curve.passing[*i] * 100, 1) : "-", 14);
        }
        std::string lim = "-";
        if (sands.front()->c144)
            for (const auto& c : sands.front()->c144->sieves)
                if (std::abs(c.opening_m - row.opening_m) <= 0.03 * c.opening_m)
                    lim = f(c.min_passing * 100, 0) + "-" + f(c.max_passing * 100, 0);
        out << lim << "\n";
    }
    if (!first.provenance.empty()) out << "Source: " << first.provenance << "\n";
    out << "\nGradation indices\n" << pad("Sand", 14) << pad("D10 mm", 9) << pad("D30 mm", 9) << pad("D50 mm", 9) << pad("D60 mm", 9)
        << pad("Cu", 7) << pad("Cc", 7) << pad("USCS", 7) << pad("FM", 7) << "ASTM C144\n";
    for (const auto* s : sands) {
        const auto& gi = *s->gradation;
        out << pad(s->name, 14) << pad(f(gi.d10_m * 1e3, 3), 9) << pad(f(gi.d30_m * 1e3, 3), 9) << pad(f(gi.d50_m * 1e3, 3), 9)
            << pad(f(gi.d60_m * 1e3, 3), 9) << pad(f(gi.cu, 2), 7) << pad(f(gi.cc, 2), 7) << pad(gi.uscs, 7)
            << pad(f(gi.fineness_modulus, 2), 7) << (s->c144 ? (s->c144->conforms ? "conforms" : "does not conform") : "-") << "\n";
    }
    for (const auto* s : sands)
        if (s->c144)
            for (const auto& v : s->c144->violations) out << "  " << s->name << ": " << v << "\n";
}

void print_statistics(std::ostream& out, const LabStats& lab) {
    out << "\nTable 4 - Compressive properties of 50-mm mortar cubes (per sand)\n";
    for (const Row& row : kRows) {
        out << row.label << "\n  " << pad("Sand", 14) << pad("n", 4) << pad("mean", 11) << pad("std", 11) << pad("CV %", 7)
            << pad("min", 11) << "max\n";
        for (const auto& s : lab.sands) {
            const SampleSummary& m = s.stats.*row.field;
            out << "  " << pad(s.name, 14) << pad(std::to_string(m.n), 4) << pad(f(m.mean * row.scale, row.decimals), 11)
                << pad(f(m.std * row.scale, row.decimals), 11) << pad(f(m.cv * 100, 1), 7) << pad(f(m.min * row.scale, row.decimals), 11)
                << f(m.max * row.scale, row.decimals) << "\n";
        }
    }
}

void print_summary_row(std::ostream& out, const std::string& sand, const SampleSummary& m, double scale, int decimals) {
    out << "  " << pad(sand, 14) << pad(std::to_string(m.n), 4) << pad(f(m.mean * scale, decimals), 11) << pad(f(m.std * scale, decimals), 11)
        << pad(f(m.cv * 100, 1), 7) << pad(f(m.min * scale, decimals), 11) << f(m.max * scale, decimals) << "\n";
}

void print_tensile(std::ostream& out, const LabStats& lab) {
    out << "\nTensile strength (per sand); the direct equivalent pools the converted values of both kinds of test\n";
    for (const TensileRow& row : kTensileRows) {
        bool any = false;
        for (const auto& s : lab.sands) any = any || (s.tensile_stats.*row.field).n > 0;
        if (!any) continue;
        out << row.label << "\n  " << pad("Sand", 14) << pad("n", 4) << pad("mean", 11) << pad("std", 11) << pad("CV %", 7)
            << pad("min", 11) << "max\n";
        for (const auto& s : lab.sands)
            if ((s.tensile_stats.*row.field).n) print_summary_row(out, s.name, s.tensile_stats.*row.field, 1e-6, 3);
    }
    for (const auto& s : lab.sands)
        if (!s.tensile.empty()) out << "  " << s.name << ": " << direct_tension_conversion(lab.tensile_tests, s.tensile) << "\n";
}

void print_comparisons(std::ostream& out, const LabStats& lab) {
    if (lab.comparisons.empty()) return;
    out << "\nWelch t-tests (two-sided)\n  " << pad("Quantity", 22) << pad("Sands", 26) << pad("t", 8) << pad("dof", 7)
        << pad("p", 11) << "Hedges g\n";
    for (const auto& c : lab.comparisons)
        out << "  " << pad(c.quantity, 22) << pad(c.sand_a + " vs " + c.sand_b, 26) << pad(f(c.test.t, 2), 8) << pad(f(c.test.dof, 1), 7)
            << pad(c.test.p_value < 1e-4 ? "<0.0001" : f(c.test.p_value, 4), 11) << f(c.test.hedges_g, 2) << "\n";
}

void print_flags(std::ostream& out, const LabStats& lab) {
    std::size_t groups = 0, failed = 0;
    for (const auto& s : lab.sands)
        for (const auto& b : s.range_checks) { ++groups; failed += b.check.ok ? 0 : 1; }
    if (groups)
        out << "\nASTM C109 permissible range (8.7 % of the mean for 3 cubes, 7.6 % for 2): " << failed << " of " << groups
            << " groups of cubes exceed it\n";
    for (const auto& c : lab.cubes) {
        if (c.flags.empty()) continue;
        out << "  " << c.file << ":";
        for (const auto& fl : c.flags) out << " " << fl;
        out << "\n";
    }
    for (const auto& t : lab.tensile_tests) {
        if (t.flags.empty()) continue;
        out << "  " << t.file << ":";
        for (const auto& fl : t.flags) out << " " << fl;
        out << "\n";
    }
}

void print_tensile_tests(std::ostream& out, const LabStats& lab) {
    out << "\nPer tension specimen\n  " << pad("File", 34) << pad("test", 11) << pad("P_max kN", 10) << pad("geometry mm", 22)
        << pad("strength MPa", 14) << pad("factor", 8) << "direct MPa\n";
    for (const auto& t : lab.tensile_tests) {
        const TensileGeometry& gm = t.geometry;
        const std::string geometry = t.test == TensileTestKind::splitting
                                         ? "d " + f(gm.diameter_m * 1e3, 1) + " l " + f(gm.length_m * 1e3, 1)
                                         : f(gm.width_m * 1e3, 1) + "x" + f(gm.depth_m * 1e3, 1) + " L " + f(gm.span_m * 1e3, 1);
        out << "  " << pad(t.file, 34) << pad(to_string(t.test), 11) << pad(f(t.peak_load_n / 1e3, 3), 10) << pad(geometry, 22)
            << pad(f(t.strength_pa / 1e6, 3), 14) << pad(f(t.direct_factor, 4), 8) << f(t.direct_equivalent_pa / 1e6, 3) << "\n";
    }
}

void print_cubes(std::ostream& out, const LabStats& lab) {
    out << "\nPer cube\n  " << pad("File", 34) << pad("peak MPa", 10) << pad("eps_peak", 10) << pad("E_chord MPa", 12)
        << pad("E_tan MPa", 11) << pad("eps_xhead", 10) << "load N/s\n";
    for (const auto& c : lab.cubes) {
        const auto& r = c.reduction;
        out << "  " << pad(c.file, 34) << pad(f(r.peak_stress_pa / 1e6, 2), 10) << pad(f(r.strain_at_peak, 5), 10)
            << pad(f(r.chord_modulus_pa / 1e6, 0), 12) << pad(f(r.tangent_modulus_pa / 1e6, 0), 11)
            << pad(f(r.strain_at_peak_crosshead, 5), 10) << f(c.load_rate_n_per_s, 0) << "\n";
    }
}

}  // namespace

std::string cubes_csv(const LabStats& lab) {
    std::ostringstream o;
    o << banner(lab)
      << "file,sand,batch,format,representative,loaded_area_mm2,peak_stress_mpa,strain_at_peak,strain_at_peak_crosshead,"
         "chord_modulus_mpa,tangent_modulus_mpa,poisson_ratio,load_rate_n_per_s,popovics_modulus_mpa,popovics_modulus_se_mpa,"
         "popovics_peak_stress_mpa,popovics_peak_stress_se_mpa,popovics_strain_at_peak,popovics_strain_at_peak_se,popovics_n,flags\n";
    for (const auto& c : lab.cubes) {
        const auto& r = c.reduction;
        const auto& p = r.popovics;
        std::string flags;
        for (const auto& fl : c.flags) flags += (flags.empty() ? "" : ";") + fl;
        o << csv_text(c.file) << ',' << csv_text(c.sand) << ',' << csv_text(c.batch) << ',' << c.format << ','
          << (c.representative ? "true" : "false") << ',' << g(c.geometry.loaded_area_m2() * 1e6) << ',' << g(r.peak_stress_pa / 1e6)
          << ',' << g(r.strain_at_peak) << ',' << g(r.strain_at_peak_crosshead) << ',' << g(r.chord_modulus_pa / 1e6) << ','
          << g(r.tangent_modulus_pa / 1e6) << ',' << g(r.poisson_ratio) << ',' << g(c.load_rate_n_per_s) << ','
          << g(p.elastic_modulus_pa / 1e6) << ',' << g(p.elastic_modulus_se_pa / 1e6) << ',' << g(p.peak_stress_pa / 1e6) << ','
          << g(p.peak_stress_se_pa / 1e6) << ',' << g(p.strain_at_peak) << ',' << g(p.strain_at_peak_se) << ',' << g(p.n) << ','
          << csv_text(flags) << '\n';
    }
    return o.str();
}

std::string tensile_tests_csv(const LabStats& lab) {
    std::ostringstream o;
    o << banner(lab)
      << "file,sand,batch,test,format,representative,peak_load_n,diameter_mm,length_mm,width_mm,depth_mm,span_mm,geometry_source,"
         "strength_mpa,conversion_factor,direct_equivalent_mpa,flags\n";
    for (const auto& t : lab.tensile_tests) {
        const TensileGeometry& gm = t.geometry;
        const bool splitting = t.test == TensileTestKind::splitting;
        auto dim = [](bool used, double m) { return used ? g(m * 1e3) : std::string(); };
        std::string flags;
        for (const auto& fl : t.flags) flags += (flags.empty() ? "" : ";") + fl;
        o << csv_text(t.file) << ',' << csv_text(t.sand) << ',' << csv_text(t.batch) << ',' << to_string(t.test) << ','
          << t.format << ',' << (t.representative ? "true" : "false") << ',' << g(t.peak_load_n) << ',' << dim(splitting, gm.diameter_m)
          << ',' << dim(splitting, gm.length_m) << ',' << dim(!splitting, gm.width_m) << ',' << dim(!splitting, gm.depth_m) << ','
          << dim(!splitting, gm.span_m) << ',' << csv_text(gm.source) << ',' << g(t.strength_pa / 1e6) << ',' << g(t.direct_factor) << ','
          << g(t.direct_equivalent_pa / 1e6) << ',' << csv_text(flags) << '\n';
    }
    return o.str();
}

std::string sand_stats_csv(const LabStats& lab) {
    std::ostringstream o;
    o << banner(lab) << "sand,quantity,n,mean,std,cv,min,max,representative\n";
    for (const auto& s : lab.sands)
        for (const Row& row : kRows) {
            const SampleSummary& m = s.stats.*row.field;
            o << csv_text(s.name) << ',' << row.csv_name << ',' << m.n << ',' << g(m.mean * row.scale) << ',' << g(m.std * row.scale)
              << ',' << g(m.cv) << ',' << g(m.min * row.scale) << ',' << g(m.max * row.scale) << ','
              << (lab.representative ? "true" : "false") << '\n';
        }
    for (const auto& s : lab.sands)  // tension rows only for sands that have such specimens
        for (const TensileRow& row : kTensileRows) {
            const SampleSummary& m = s.tensile_stats.*row.field;
            if (!m.n) continue;
            o << csv_text(s.name) << ',' << row.csv_name << ',' << m.n << ',' << g(m.mean * 1e-6) << ',' << g(m.std * 1e-6) << ','
              << g(m.cv) << ',' << g(m.min * 1e-6) << ',' << g(m.max * 1e-6) << ',' << (lab.representative ? "true" : "false") << '\n';
        }
    return o.str();
}

std::string gradation_csv(const LabStats& lab) {
    std::ostringstream o;
    o << "sand,sieve,opening_mm,percent_passing,c144_min_pct,c144_max_pct,c144_ok\n";
    for (const auto& s : lab.sands) {
        if (!s.sieve) continue;
        for (const auto& r : s.sieve->rows) {
            std::string lo, hi, ok;
            if (s.c144)
                for (const auto& c : s.c144->sieves)
                    if (std::abs(c.opening_m - r.opening_m) <= 0.03 * c.opening_m) {
                        lo = g(c.min_passing * 100);
                        hi = g(c.max_passing * 100);
                        ok = c.ok ? "true" : "false";
                    }
            o << csv_text(s.name) << ',' << csv_text(r.designation) << ',' << g(r.opening_m * 1e3) << ',' << g(r.passing * 100) << ','
              << lo << ',' << hi << ',' << ok << '\n';
        }
    }
    return o.str();
}

std::string comparisons_csv(const LabStats& lab) {
    std::ostringstream o;
    o << banner(lab) << "quantity,sand_a,sand_b,n_a,n_b,mean_difference,welch_t,dof,p_value,cohens_d,hedges_g\n";
    for (const auto& c : lab.comparisons) {
        const double k = c.quantity.find("_mpa") != std::string::npos ? 1e-6 : 1.0;
        o << c.quantity << ',' << csv_text(c.sand_a) << ',' << csv_text(c.sand_b) << ',' << c.test.n1 << ',' << c.test.n2 << ','
          << g(c.test.mean_difference * k) << ',' << g(c.test.t) << ',' << g(c.test.dof) << ',' << g(c.test.p_value) << ','
          << g(c.test.cohens_d) << ',' << g(c.test.hedges_g) << '\n';
    }
    return o.str();
}

std::string curves_csv(const LabStats& lab) {
    std::ostringstream o;
    o << banner(lab) << "file,sand,batch,strain,stress_mpa\n";
    for (const auto& c : lab.cubes) {
        const std::size_t n = std::min(c.curve.strain.size(), c.curve.stress_pa.size());
        const std::size_t stride = (n + kCurvePointsPerCube - 2) / (kCurvePointsPerCube - 1);  // room for the peak
        for (std::size_t i = 0; i < n; ++i)
            if (i % std::max<std::size_t>(stride, 1) == 0 || i == c.reduction.peak_index)
                o << csv_text(c.file) << ',' << csv_text(c.sand) << ',' << csv_text(c.batch) << ',' << g(c.curve.strain[i]) << ','
                  << g(c.curve.stress_pa[i] / 1e6) << '\n';
    }
    return o.str();
}

void write_lab_outputs(const fs::path& dir, const LabStats& lab) {
    std::error_code ec;
    fs::create_directories(dir, ec);
    if (ec) throw InputError(dir.string(), 0, "cannot create output directory: " + ec.message());
    common::write_files_atomically({{dir / "lab_results.json", lab_stats_to_json(lab).dump(2) + "\n"},
                      {dir / "cubes.csv", cubes_csv(lab)},
                      {dir / "tensile_tests.csv", tensile_tests_csv(lab)},
                      {dir / "sand_stats.csv", sand_stats_csv(lab)},
                      {dir / "gradation.csv", gradation_csv(lab)},
                      {dir / "comparisons.csv", comparisons_csv(lab)},
                      {dir / "curves.csv", curves_csv(lab)}});
}

void print_lab_report(std::ostream& out, const LabStats& lab, bool per_cube) {
    if (lab.cubes.empty() && lab.tensile_tests.empty()) out << "gradem lab: " << lab.sands.size() << " sieve analyses\n";
    else {
        out << "gradem lab: " << lab.dataset << " (" << lab.source << ")";
        if (!lab.cubes.empty() || lab.tensile_tests.empty()) out << ", " << lab.cubes.size() << " cubes";
        if (!lab.tensile_tests.empty()) out << ", " << lab.tensile_tests.size() << " tensile specimens";
        out << "\n";
    }
    if (lab.representative)
        out << "*** REPRESENTATIVE DATA, NOT MEASUREMENTS: " << (lab.note.empty() ? "see the dataset README" : lab.note) << " ***\n";
    print_gradation(out, lab);
    if (lab.cubes.empty() && lab.tensile_tests.empty()) return;  // sieve analyses only: no strength statistics
    if (!lab.cubes.empty()) print_statistics(out, lab);
    if (!lab.tensile_tests.empty()) print_tensile(out, lab);
    print_comparisons(out, lab);
    print_flags(out, lab);
    if (per_cube && !lab.cubes.empty()) print_cubes(out, lab);
    if (per_cube && !lab.tensile_tests.empty()) print_tensile_tests(out, lab);
}

}  // namespace gradem::report
