// Splitting-tension (ASTM C496) and flexural (ASTM C348) exports: the formulas, the fib Model
// Code 2010 direct-tension conversion, the per-sand statistics, lab_results.json and the errors.
// The fixtures are GENERATED with known peak loads (lab_data/tools/generate_tension_fixtures.py).
#include <catch2/catch.hpp>
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "app/lab_command.hpp"
#include "lab_command_run.hpp"
#include "common/input_error.hpp"
#include "lab_data/lab_stats.hpp"
#include "lab_data/tension.hpp"
#include "reports/lab_report.hpp"

using namespace gradem::lab;
using namespace gradem::report;
namespace fs = std::filesystem;

namespace {

const std::string kFixtures = GRADEM_LAB_FIXTURES;
std::string tension(const char* name) { return kFixtures + "/tension/" + name; }
const std::string kDataset = kFixtures + "/tension_dataset";

// α_fl for h = 40 mm: 0.06 · 40^0.7 = 0.793609; 0.793609 / 1.793609 = 0.442457.
constexpr double kAlpha40 = 0.44245731;

using Run = gradem::test::LabRun;
Run run(const std::vector<std::string>& args) { return gradem::test::run_lab(args); }
fs::path scratch(const std::string& name) { return gradem::test::lab_scratch("gradem_tensile_test_", name); }

// A dataset folder holding only `toml` (paths in it may point at the fixtures).
fs::path dataset_with(const std::string& name, const std::string& toml) {
    const fs::path dir = scratch(name);
    fs::create_directories(dir);
    std::ofstream(dir / "dataset.toml") << toml;
    return dir;
}

std::string error_of(const fs::path& dataset) {
    try {
        (void)analyse_lab_dataset(dataset);
    } catch (const InputError& e) {
        return e.what();
    }
    return "(no error)";
}

// `gradem lab DATASET --out OUT` on a bad dataset: exit 1, `message` on stderr, and OUT (which
// holds one file beforehand) left as it was.
void expect_refused_untouched(const fs::path& dataset, const std::string& message) {
    const fs::path out = scratch("untouched");
    fs::create_directories(out);
    std::ofstream(out / "keep.txt") << "untouched\n";
    const Run r = run({dataset.string(), "--out", out.string()});
    CHECK(r.status == 1);
    CHECK_THAT(r.err, Catch::Contains(message));
    std::vector<std::string> left;
    for (const auto& e : fs::directory_iterator(out)) left.push_back(e.path().filename().string());
    CHECK(left == std::vector<std::string>{"keep.txt"});
    fs::remove_all(out);
}

const nlohmann::json& sand(const nlohmann::json& j, const std::string& name) {
    for (const auto& s : j["sands"])
        if (s["name"] == name) return s;
    FAIL("no sand " << name);
    return j;
}

}  // namespace

TEST_CASE("lab: tensile: the ASTM formulas and the fib MC2010 factors against hand values", "[lab][tensile]") {
    // C496: P = 100 kN on a 100 × 200 mm cylinder: T = 2·1e5/(π·0.2·0.1) = 3.1831 MPa.
    CHECK(splitting_tensile_strength_pa(100e3, 0.200, 0.100) == Approx(3.18310e6).epsilon(1e-5));
    // C348: P = 3000 N on the 40 × 40 mm prism, span 120 mm: 3·3000·0.12/(2·0.04·0.04²) = 8.4375 MPa;
    // the standard's rounded coefficient gives 0.0028·3000 = 8.4 MPa.
    CHECK(flexural_strength_pa(3000, kC348Span, kC348PrismWidth, kC348PrismDepth) == Approx(8.4375e6).epsilon(1e-9));
    CHECK(flexural_strength_pa(3000, kC348Span, kC348PrismWidth, kC348PrismDepth) == Approx(0.0028 * 3000 * 1e6).epsilon(0.005));
    // Another prism: 100 × 100 mm on a 300 mm span, 10 kN: 3·1e4·0.3/(2·0.1·0.01) = 4.5 MPa.
    CHECK(flexural_strength_pa(10e3, 0.3, 0.1, 0.1) == Approx(4.5e6).epsilon(1e-9));
    CHECK(mc2010_alpha_flexural(0.040) == Approx(kAlpha40).epsilon(1e-6));
    // h = 150 mm: 0.06 · 150^0.7 = 2.00190; 2.00190 / 3.00190 = 0.666864.
    CHECK(mc2010_alpha_flexural(0.150) == Approx(0.666864).epsilon(1e-5));
    TensileGeometry prism;
    prism.depth_m = 0.040;
    CHECK(direct_tension_factor(TensileTestKind::splitting, prism) == 1.0);
    CHECK(direct_tension_factor(TensileTestKind::flexural, prism) == Approx(kAlpha40).epsilon(1e-6));
    CHECK(parse_tensile_test("Splitting") == TensileTestKind::splitting);
    CHECK(parse_tensile_test("flexural") == TensileTestKind::flexural);
    CHECK_FALSE(parse_tensile_test("brazilian"));
}

TEST_CASE("lab: tensile: exports in MTS and Bluehill layouts give the generated peak loads", "[lab][tensile]") {
    TensileSpec split;
    split.nominal_source = "command line";
    const ReadOptions read;
    // MTS TestSuite, kN, compression negative; the file states 100 × 200 mm.
    const TensileResult a = read_tensile_file(tension("A-S1.csv"), "A-S1.csv", split, read);
    CHECK(a.format == "mts-testsuite");
    CHECK(a.peak_load_n == Approx(100e3).epsilon(1e-9));
    CHECK(a.geometry.diameter_m == Approx(0.100));
    CHECK(a.geometry.length_m == Approx(0.200));
    CHECK(a.geometry.source == "file");
    CHECK(a.strength_pa == Approx(3.18310e6).epsilon(1e-5));
    CHECK(a.direct_equivalent_pa == a.strength_pa);
    CHECK(a.peak_line == 52);  // header 11 lines, the peak is the 41st sample
    CHECK(a.flags.empty());

    // Bluehill, lbf with thousands separators, no dimensions stated: the C348 prism and span.
    TensileSpec flex;
    flex.test = TensileTestKind::flexural;
    const TensileResult f = read_tensile_file(tension("A-F1.csv"), "A-F1.csv", flex, read);
    CHECK(f.format == "instron-bluehill");
    CHECK(f.peak_load_n == Approx(3000).epsilon(1e-7));
    CHECK(f.geometry.source == "ASTM C348");
    CHECK(f.geometry.span_m == Approx(0.120));
    CHECK(f.strength_pa == Approx(8.4375e6).epsilon(1e-7));
    CHECK(f.direct_factor == Approx(kAlpha40).epsilon(1e-6));
    CHECK(f.direct_equivalent_pa == Approx(kAlpha40 * 8.4375e6).epsilon(1e-6));

    // The file's prism dimensions win over the given ones; its "Specimen Length" (160 mm) is not the span.
    flex.nominal.span_m = 0.100;
    flex.nominal.width_m = 0.050;
    flex.nominal_source = "dataset";
    const TensileResult b = read_tensile_file(tension("B-F1.csv"), "B-F1.csv", flex, read);
    CHECK(b.geometry.span_m == Approx(0.120));
    CHECK(b.geometry.width_m == Approx(0.040));
    CHECK(b.strength_pa == Approx(7.03125e6).epsilon(1e-7));
    // ... unless the file's geometry is not to be used.
    flex.use_file_geometry = false;
    const TensileResult c = read_tensile_file(tension("B-F1.csv"), "B-F1.csv", flex, read);
    CHECK(c.geometry.source == "dataset+ASTM C348");
    // 3·2500·0.1/(2·0.05·0.04²) = 4.6875 MPa
    CHECK(c.strength_pa == Approx(4.6875e6).epsilon(1e-7));
}

TEST_CASE("lab: tensile: dataset: per-sand statistics, pooled direct equivalent, Welch between sands", "[lab][tensile]") {
    const LabStats lab = analyse_lab_dataset(kDataset);
    REQUIRE(lab.sands.size() == 2);
    REQUIRE(lab.tensile_tests.size() == 12);
    CHECK(lab.cubes.empty());
    const SandResult& a = lab.sands[0];
    CHECK(a.name == "Sand A");
    // Splitting: P = 100, 95, 105 kN on 100 × 200 mm (A-S3 from the dataset): T = P/(0.01 π).
    CHECK(a.tensile_stats.splitting_pa.n == 3);
    CHECK(a.tensile_stats.splitting_pa.mean == Approx(3.183099e6).epsilon(1e-6));
    CHECK(a.tensile_stats.splitting_pa.std == Approx(0.1591549e6).epsilon(1e-5));
    CHECK(a.tensile_stats.splitting_pa.min == Approx(3.023944e6).epsilon(1e-6));
    CHECK(a.tensile_stats.splitting_pa.max == Approx(3.342254e6).epsilon(1e-6));
    // Flexural: 3000, 2800, 3200 N → 8.4375, 7.875, 9.0 MPa.
    CHECK(a.tensile_stats.flexural_pa.n == 3);
    CHECK(a.tensile_stats.flexural_pa.mean == Approx(8.4375e6).epsilon(1e-6));
    CHECK(a.tensile_stats.flexural_pa.std == Approx(0.5625e6).epsilon(1e-5));
    // Direct equivalent pooled over the six: 3.183099, 3.023944, 3.342254 and
    // 0.442457 × (8.4375, 7.875, 9.0) = 3.733234, 3.484351, 3.982116 MPa.
    CHECK(a.tensile_stats.direct_pa.n == 6);
    CHECK(a.tensile_stats.direct_pa.mean == Approx(3.458166e6).epsilon(1e-6));
    CHECK(a.tensile_stats.direct_pa.std == Approx(0.3545469e6).epsilon(1e-5));
    CHECK(a.tensile_stats.direct_pa.cv == Approx(0.1025245).epsilon(1e-5));
    CHECK(a.tensile_stats.direct_pa.min == Approx(3.023944e6).epsilon(1e-6));
    CHECK(a.tensile_stats.direct_pa.max == Approx(3.982116e6).epsilon(1e-6));
    const SandResult& b = lab.sands[1];
    CHECK(b.tensile_stats.splitting_pa.mean == Approx(3.183099e6).epsilon(1e-6));  // 25, 24, 26 kN on 50 × 100 mm
    CHECK(b.tensile_stats.flexural_pa.mean == Approx(7.03125e6).epsilon(1e-6));
    CHECK(b.tensile_stats.direct_pa.mean == Approx(3.147063e6).epsilon(1e-6));
    CHECK(b.tensile_stats.direct_pa.std == Approx(0.1193191e6).epsilon(1e-5));

    // Only the tensile quantity is compared (no sand has cubes): Welch t = 2.03708, dof 6.1182.
    REQUIRE(lab.comparisons.size() == 1);
    const Comparison& c = lab.comparisons[0];
    CHECK(c.quantity == "tensile_strength_mpa");
    CHECK(c.test.mean_difference == Approx(0.3111028e6).epsilon(1e-5));
    CHECK(c.test.t == Approx(2.037078).epsilon(1e-5));
    CHECK(c.test.dof == Approx(6.118246).epsilon(1e-5));
}

TEST_CASE("lab: tensile: lab_results.json, tensile_tests.csv and the printed tables", "[lab][tensile][cli]") {
    const fs::path out = scratch("json");
    const Run r = run({kDataset, "--out", out.string(), "--json"});
    REQUIRE(r.status == 0);
    const auto j = nlohmann::json::parse(r.out);
    const auto& a = sand(j, "Sand A");
    for (const char* key : {"splitting_tensile_strength_mpa", "flexural_strength_mpa", "tensile_strength_mpa"})
        for (const char* field : {"n", "mean", "std", "cv", "min", "max"}) CHECK(a[key].contains(field));
    CHECK(a["splitting_tensile_strength_mpa"]["mean"].get<double>() == Approx(3.183099).epsilon(1e-6));
    CHECK(a["flexural_strength_mpa"]["max"].get<double>() == Approx(9.0).epsilon(1e-6));
    CHECK(a["tensile_strength_mpa"]["n"] == 6);
    CHECK(a["tensile_strength_mpa"]["mean"].get<double>() == Approx(3.458166).epsilon(1e-6));
    CHECK_THAT(a["tensile_strength_mpa"]["conversion"].get<std::string>(),
               Catch::Contains("alpha_sp = 1.0") && Catch::Contains("0.06 h^0.7") && Catch::Contains("pooled"));
    REQUIRE(j["tensile_tests"].size() == 12);
    const auto& t = j["tensile_tests"][0];
    CHECK(t["file"] == "../tension/A-S1.csv");
    CHECK(t["sand"] == "Sand A");
    CHECK(t["batch"] == "AS");
    CHECK(t["test"] == "splitting");
    CHECK(t["peak_load_n"].get<double>() == Approx(100e3).epsilon(1e-9));
    CHECK(t["diameter_mm"].get<double>() == Approx(100.0));
    CHECK(t["length_mm"].get<double>() == Approx(200.0));
    CHECK(t["strength_mpa"].get<double>() == Approx(3.183099).epsilon(1e-6));
    CHECK(t["direct_equivalent_mpa"].get<double>() == Approx(3.183099).epsilon(1e-6));
    CHECK(t["flags"].is_array());
    CHECK(t["notes"].is_array());
    const auto& s3 = j["tensile_tests"][2];  // A-S3 states no dimensions: the dataset's
    CHECK(s3["geometry_source"] == "dataset");
    const auto& f = j["tensile_tests"][3];
    CHECK(f["test"] == "flexural");
    CHECK(f["span_mm"].get<double>() == Approx(120.0));
    CHECK(f["depth_mm"].get<double>() == Approx(40.0));
    CHECK(f["direct_equivalent_mpa"].get<double>() == Approx(3.733234).epsilon(1e-6));
    bool compared = false;
    for (const auto& c : j["comparisons"])
        if (c["quantity"] == "tensile_strength_mpa") {
            compared = true;
            CHECK(c["mean_difference"].get<double>() == Approx(0.3111028).epsilon(1e-5));
            CHECK(c["welch_t"].get<double>() == Approx(2.037078).epsilon(1e-5));
        }
    CHECK(compared);

    std::ifstream csv(out / "tensile_tests.csv");
    std::string line, header;
    std::size_t rows = 0;
    while (std::getline(csv, line)) {
        if (line.empty() || line[0] == '#') continue;
        if (header.empty()) header = line;
        else ++rows;
    }
    CHECK_THAT(header, Catch::StartsWith("file,sand,batch,test,") && Catch::Contains("strength_mpa,conversion_factor,direct_equivalent_mpa"));
    CHECK(rows == 12);

    const Run table = run({kDataset, "--no-write"});
    REQUIRE(table.status == 0);
    CHECK_THAT(table.out, Catch::Contains("12 tensile specimens") && Catch::Contains("Splitting tensile strength (MPa), ASTM C496") &&
                              Catch::Contains("Flexural strength (MPa), ASTM C348") &&
                              Catch::Contains("Direct tensile strength") && Catch::Contains("tensile_strength_mpa"));
    CHECK_THAT(table.out, !Catch::Contains("Table 4"));
    fs::remove_all(out);
}

TEST_CASE("lab: tensile: export files on the command line with --test and geometry options", "[lab][tensile][cli]") {
    const Run s = run({tension("A-S3.csv"), "--test", "splitting", "--diameter-mm", "100", "--length-mm", "200", "--no-write", "--json"});
    REQUIRE(s.status == 0);
    const auto j = nlohmann::json::parse(s.out);
    CHECK(j["cubes"].empty());
    REQUIRE(j["tensile_tests"].size() == 1);
    CHECK(j["tensile_tests"][0]["strength_mpa"].get<double>() == Approx(3.342254).epsilon(1e-6));
    CHECK(j["tensile_tests"][0]["geometry_source"] == "command line");
    CHECK(j["sands"][0]["tensile_strength_mpa"]["mean"].get<double>() == Approx(3.342254).epsilon(1e-6));

    // A different prism: 3·3000·0.1/(2·0.04·0.04²) = 7.03125 MPa on a 100 mm span.
    const Run f = run({tension("A-F1.csv"), "--test", "flexural", "--span-mm", "100", "--no-write", "--json"});
    REQUIRE(f.status == 0);
    CHECK(nlohmann::json::parse(f.out)["tensile_tests"][0]["strength_mpa"].get<double>() == Approx(7.03125).epsilon(1e-6));

    // Without --test an export is reduced as a cube, as before.
    const Run cube = run({tension("A-S1.csv"), "--no-write", "--json"});
    REQUIRE(cube.status == 0);
    const auto k = nlohmann::json::parse(cube.out);
    CHECK(k["cubes"].size() == 1);
    CHECK(k["tensile_tests"].empty());
    // Usage errors: an unknown test, a dimension of the other kind, geometry without --test.
    const Run u = run({tension("A-S1.csv"), "--test", "brazilian", "--no-write"});
    CHECK(u.status == 2);
    CHECK_THAT(u.err, Catch::Contains("--test 'brazilian': expected splitting or flexural"));
    CHECK(run({tension("A-S1.csv"), "--test", "splitting", "--span-mm", "100", "--no-write"}).status == 2);
    CHECK(run({tension("A-S1.csv"), "--diameter-mm", "100", "--no-write"}).status == 2);
    CHECK(run({tension("A-S1.csv"), "--test", "splitting", "--diameter-mm", "-5", "--no-write"}).status == 2);
    // The export states no diameter and none is given.
    const Run m = run({tension("A-S3.csv"), "--test", "splitting", "--no-write"});
    CHECK(m.status == 1);
    CHECK_THAT(m.err, Catch::Contains("A-S3.csv: splitting test: the export states no specimen diameter; give --diameter-mm (mm)"));
}

TEST_CASE("lab: tensile: bad dataset input names file, line and key, and writes nothing", "[lab][tensile][errors]") {
    const std::string fixtures = kFixtures + "/tension/";
    auto table = [&](const std::string& body) {
        return "[dataset]\nname = \"bad\"\n\n[[sand]]\nname = \"s\"\n\n[[sand.tension]]\nname = \"T1\"\n" + body;
    };

    SECTION("unknown test name") {
        const fs::path d = dataset_with("test_name", table("test = \"brazilian\"\nfiles = \"" + fixtures + "A-S1.csv\"\n"));
        CHECK_THAT(error_of(d), Catch::Contains("dataset.toml:9: key 'test': 'brazilian' is not a tensile test (expected splitting or flexural)"));
        expect_refused_untouched(d, "dataset.toml:9: key 'test': 'brazilian' is not a tensile test (expected splitting or flexural)");
        fs::remove_all(d);
    }
    SECTION("missing diameter") {
        const fs::path d = dataset_with("diameter", table("test = \"splitting\"\nfiles = \"" + fixtures + "A-S3.csv\"\nlength_mm = 200\n"));
        CHECK_THAT(error_of(d), Catch::Contains("dataset.toml:7: [[sand.tension]] 'T1': ") &&
                                    Catch::Contains("A-S3.csv: splitting test: the export states no specimen diameter; set diameter_mm (mm)"));
        expect_refused_untouched(d, "A-S3.csv: splitting test: the export states no specimen diameter; set diameter_mm (mm)");
        fs::remove_all(d);
    }
    SECTION("non-positive dimension") {
        const fs::path d = dataset_with("negative", table("test = \"flexural\"\nfiles = \"" + fixtures + "A-F1.csv\"\nspan_mm = 0\n"));
        CHECK_THAT(error_of(d), Catch::Contains("dataset.toml:11: key 'span_mm' must be > 0"));
        expect_refused_untouched(d, "dataset.toml:11: key 'span_mm' must be > 0");
        fs::remove_all(d);
    }
    SECTION("a dimension of the other kind of test") {
        const fs::path d = dataset_with("other_kind", table("test = \"splitting\"\nfiles = \"" + fixtures + "A-S1.csv\"\nspan_mm = 100\n"));
        CHECK_THAT(error_of(d), Catch::Contains("dataset.toml:11: key 'span_mm' does not apply to a splitting test (its keys: diameter_mm, length_mm)"));
        expect_refused_untouched(d, "dataset.toml:11: key 'span_mm' does not apply to a splitting test");
        fs::remove_all(d);
    }
    SECTION("unknown key") {
        const fs::path d = dataset_with("unknown", table("test = \"splitting\"\nfiles = \"" + fixtures + "A-S1.csv\"\ndiametre_mm = 50\n"));
        CHECK_THAT(error_of(d), Catch::Contains("dataset.toml:11: unknown key 'diametre_mm' in [[sand.tension]] (expected one of:") &&
                                    Catch::Contains("diameter_mm"));
        expect_refused_untouched(d, "dataset.toml:11: unknown key 'diametre_mm' in [[sand.tension]]");
        fs::remove_all(d);
    }
    SECTION("a glob that matches nothing") {
        const fs::path d = dataset_with("glob", table("test = \"splitting\"\nfiles = \"tension/PBT1-*.csv\"\n"));
        const std::string e = error_of(d);
        CHECK_THAT(e, Catch::Contains("dataset.toml:10: key 'files' of [[sand.tension]] 'T1': pattern 'tension/PBT1-*.csv' matches no file"));
        CHECK_THAT(e, Catch::Contains("(in " + (d / "tension").string() + ")"));
        expect_refused_untouched(d, "pattern 'tension/PBT1-*.csv' matches no file");
        fs::remove_all(d);
    }
    SECTION("test missing") {
        const fs::path d = dataset_with("no_test", table("files = \"" + fixtures + "A-S1.csv\"\n"));
        CHECK_THAT(error_of(d), Catch::Contains("dataset.toml:7: [[sand.tension]] 'T1' needs test = \"splitting\" or \"flexural\""));
        expect_refused_untouched(d, "needs test = \"splitting\" or \"flexural\"");
        fs::remove_all(d);
    }
    SECTION("a file with no load column") {
        // A good export first: nothing of it is written either.
        const fs::path d = dataset_with("no_load", table("test = \"splitting\"\nfiles = [\"" + fixtures + "A-S1.csv\", \"" + kFixtures +
                                                         "/missing_load.csv\"]\ndiameter_mm = 50\nlength_mm = 100\n"));
        CHECK_THAT(error_of(d), Catch::Contains("missing_load.csv:1: no load column"));
        expect_refused_untouched(d, "no load column");
        fs::remove_all(d);
    }
}
