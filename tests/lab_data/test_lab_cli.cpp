// `gradem lab` end to end through run_lab_command, on the bundled study dataset and fixtures.
#include <catch2/catch.hpp>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <iostream>
#include <map>
#include <nlohmann/json.hpp>
#include <sstream>

#include "app/lab_command.hpp"
#include "lab_command_run.hpp"
#include "lab_data/lab_stats.hpp"
#include "lab_data/text.hpp"
#include "reports/lab_report.hpp"

using namespace gradem::lab;
using namespace gradem::report;
namespace fs = std::filesystem;

namespace {

const std::string kStudy = GRADEM_LAB_STUDY;
std::string fixture(const char* name) { return std::string(GRADEM_LAB_FIXTURES) + "/" + name; }

using Run = gradem::test::LabRun;
Run run(const std::vector<std::string>& args) { return gradem::test::run_lab(args); }
fs::path scratch(const std::string& name) { return gradem::test::lab_scratch("gradem_lab_test_", name); }

// generator_truth.csv: the law parameters each representative cube was generated from.
std::map<std::string, std::map<std::string, double>> truth() {
    std::ifstream in(kStudy + "/generator_truth.csv");
    std::string line;
    std::vector<std::string> names;
    std::map<std::string, std::map<std::string, double>> rows;
    while (std::getline(in, line)) {
        if (line.empty() || line[0] == '#') continue;
        std::vector<std::string> cells;
        for (const auto& c : split_cells(line, ',').cells) cells.push_back(c.text);
        if (names.empty()) { names = cells; continue; }
        for (std::size_t i = 3; i < cells.size(); ++i) rows[cells[0]][names[i]] = std::stod(cells[i]);
    }
    return rows;
}

}  // namespace

TEST_CASE("lab: on the study dataset: JSON contract and the generating law recovered", "[lab][cli]") {
    const fs::path out = scratch("study");
    const Run r = run({kStudy, "--out", out.string(), "--json"});
    REQUIRE(r.status == 0);
    const auto j = nlohmann::json::parse(r.out);
    CHECK(j["representative_data"] == true);
    CHECK_THAT(j["note"].get<std::string>(), Catch::Contains("REPRESENTATIVE"));
    REQUIRE(j["sands"].size() == 2);
    CHECK(j["sands"][0]["name"] == "pre-blended");
    CHECK(j["sands"][0]["n"] == 27);
    CHECK(j["sands"][1]["n"] == 12);
    CHECK(j["sands"][0]["gradation"]["uscs"] == "SP");
    CHECK(j["sands"][0]["gradation"]["c144_conforms"] == false);
    CHECK(j["sands"][1]["gradation"]["c144_conforms"] == false);
    CHECK(j["sands"][1]["gradation"]["d10_mm"].get<double>() == Approx(0.240).epsilon(1e-3));
    // The generator rescales each sand's law peaks to mean 21.0 / 17.5 MPa; C109 peaks carry
    // only load noise (12 N on ~50 kN).
    CHECK(j["sands"][0]["peak_stress_mpa"]["mean"].get<double>() == Approx(21.0).epsilon(0.002));
    CHECK(j["sands"][1]["peak_stress_mpa"]["mean"].get<double>() == Approx(17.5).epsilon(0.002));
    CHECK(j["sands"][0]["chord_modulus_mpa"]["mean"].get<double>() == Approx(12000).epsilon(0.01));
    CHECK(j["sands"][1]["strain_at_peak"]["mean"].get<double>() == Approx(0.0037).epsilon(0.01));

    const auto t = truth();
    REQUIRE(j["cubes"].size() == 39);
    for (const auto& c : j["cubes"]) {
        const auto& law = t.at(c["file"].get<std::string>());
        CHECK(c["peak_stress_mpa"].get<double>() == Approx(law.at("fc_mpa")).epsilon(0.005));
        CHECK(c["chord_modulus_mpa"].get<double>() == Approx(law.at("chord_modulus_mpa")).epsilon(0.02));
        CHECK(c["strain_at_peak"].get<double>() == Approx(law.at("eps_c")).epsilon(0.03));
        CHECK(c["popovics"]["elastic_modulus_mpa"].get<double>() == Approx(law.at("initial_modulus_mpa")).epsilon(0.02));
        CHECK(c["strain_at_peak_crosshead"].get<double>() > c["strain_at_peak"].get<double>());
        CHECK(c["representative"] == true);
        CHECK(c["load_rate_n_per_s"].get<double>() > 900);
        CHECK(c["load_rate_n_per_s"].get<double>() < 1800);
    }
    for (const auto& c : j["comparisons"])
        if (c["quantity"] == "peak_stress_mpa") CHECK(c["p_value"].get<double>() < 0.05);
    for (const char* f : {"lab_results.json", "cubes.csv", "sand_stats.csv", "gradation.csv", "comparisons.csv", "curves.csv"})
        CHECK(fs::exists(out / f));
    fs::remove_all(out);
}

TEST_CASE("lab: curves.csv holds every cube's curve, thinned, with its peak, the app hook sees the folder", "[lab][cli]") {
    const fs::path out = scratch("curves");
    std::vector<fs::path> hooked;
    std::ostringstream sink;
    auto* old_out = std::cout.rdbuf(sink.rdbuf());
    const int status = gradem::app::run_lab_command({kStudy, "--out", out.string()},
                                       [&](const fs::path& dir, std::ostream&) { hooked.push_back(dir); });
    std::cout.rdbuf(old_out);
    REQUIRE(status == 0);
    CHECK(hooked == std::vector<fs::path>{out});

    const auto j = nlohmann::json::parse(std::ifstream(out / "lab_results.json"));
    std::map<std::string, std::pair<std::size_t, double>> curves;  // file -> (samples, largest stress [MPa])
    std::ifstream in(out / "curves.csv");
    std::string line;
    bool header = false;
    while (std::getline(in, line)) {
        if (line.empty() || line[0] == '#') continue;
        if (!header) {
            CHECK(line == "file,sand,batch,strain,stress_mpa");
            header = true;
            continue;
        }
        const auto cells = split_cells(line, ',').cells;
        REQUIRE(cells.size() == 5);
        auto& [samples, peak] = curves[cells[0].text];
        ++samples;
        peak = std::max(peak, std::stod(cells[4].text));
    }
    REQUIRE(curves.size() == j["cubes"].size());
    for (const auto& c : j["cubes"]) {
        const auto& [samples, peak] = curves.at(c["file"].get<std::string>());
        CHECK(samples > 50);
        CHECK(samples <= gradem::report::kCurvePointsPerCube);
        CHECK(peak == Approx(c["peak_stress_mpa"].get<double>()).epsilon(1e-7));  // the peak sample is kept
    }
    fs::remove_all(out);

    hooked.clear();
    auto* old_out2 = std::cout.rdbuf(sink.rdbuf());
    gradem::app::run_lab_command({kStudy, "--no-write"}, [&](const fs::path& dir, std::ostream&) { hooked.push_back(dir); });
    std::cout.rdbuf(old_out2);
    CHECK(hooked.empty());
}

TEST_CASE("lab: prints Table 2 and Table 4 and marks representative data", "[lab][cli]") {
    const Run r = run({kStudy, "--no-write"});
    REQUIRE(r.status == 0);
    CHECK_THAT(r.out, Catch::Contains("REPRESENTATIVE DATA") && Catch::Contains("Table 2") && Catch::Contains("Table 4") &&
                          Catch::Contains("does not conform") && Catch::Contains("Welch"));
}

TEST_CASE("lab: on single export files reduces each", "[lab][cli]") {
    const Run r = run({fixture("plain.csv"), fixture("mts793_deu.dat"), "--no-write", "--json"});
    REQUIRE(r.status == 0);
    const auto j = nlohmann::json::parse(r.out);
    REQUIRE(j["cubes"].size() == 2);
    // plain.csv: 12.5 kN on the nominal 50 × 50 mm face; 5 kN per 200 µε.
    CHECK(j["cubes"][0]["peak_stress_mpa"].get<double>() == Approx(5.0));
    CHECK(j["cubes"][0]["chord_modulus_mpa"].get<double>() == Approx(10000.0));
    CHECK(j["cubes"][0]["strain_at_peak"].get<double>() == Approx(0.0006));
    CHECK(j["representative_data"] == false);
}

TEST_CASE("lab: bad input: non-zero exit file:line message no partial result", "[lab][cli][errors]") {
    const fs::path out = scratch("bad");
    const Run r = run({fixture("plain.csv"), fixture("text_in_cell.csv"), "--out", out.string()});
    CHECK(r.status == 1);
    CHECK_THAT(r.err, Catch::Contains("text_in_cell.csv:6: column 'load': 'abc' is not a number"));
    CHECK_FALSE(fs::exists(out / "lab_results.json"));
    CHECK_FALSE(fs::exists(out / "cubes.csv"));

    const Run w = run({fixture("window_not_reached.csv"), "--no-write"});
    CHECK(w.status == 1);
    CHECK_THAT(w.err, Catch::Contains("window_not_reached.csv:5: the ascending branch never reaches the lower chord strain"));

    const fs::path toml = scratch("toml");
    fs::create_directories(toml);
    std::ofstream(toml / "dataset.toml") << "[dataset]\nname = \"x\"\nrepresentativ = true\n";
    const Run t = run({toml.string(), "--no-write"});
    CHECK(t.status == 1);
    CHECK_THAT(t.err, Catch::Contains("dataset.toml:3: unknown key 'representativ' in [dataset]"));
    std::ofstream(toml / "dataset.toml") << "[[sand]]\nname = \"s\"\n[[sand.batch]]\nfiles = \"cubes/*.csv\"\n";
    CHECK_THAT(run({toml.string(), "--no-write"}).err, Catch::Contains("dataset.toml:4: pattern 'cubes/*.csv' matches no file"));
    fs::remove_all(toml);
}

TEST_CASE("lab: usage: --help unknown options overrides from the command line", "[lab][cli]") {
    const Run h = run({"--help"});
    CHECK(h.status == 0);
    CHECK_THAT(h.out, Catch::Contains("usage: gradem lab"));
    CHECK(run({"--bogus", "x"}).status == 2);
    CHECK(run({}).status == 2);
    const Run o = run({fixture("plain.csv"), "--no-write", "--json", "--column", "load=crosshead_mm"});
    CHECK(o.status == 1);  // a length column cannot be the load
    CHECK_THAT(o.err, Catch::Contains("unit 'mm' is a length unit; expected a force unit"));
}

TEST_CASE("lab: sieve analysis files are recognised and their gradation printed", "[lab][cli][sieve]") {
    // The masses fixture reproduces Van Buren's Table 2 passing: D50 0.394 mm as for the dataset.
    const Run r = run({fixture("sieve_masses.csv"), "--no-write", "--json"});
    REQUIRE(r.status == 0);
    const auto j = nlohmann::json::parse(r.out);
    REQUIRE(j["sands"].size() == 1);
    CHECK(j["cubes"].empty());
    const Run table = run({fixture("sieve_passing.csv"), kStudy + "/sieve_van_buren.csv", "--no-write", "--c144",
                           kStudy + "/astm_c144_natural_sand.csv"});
    REQUIRE(table.status == 0);
    CHECK_THAT(table.out, Catch::Contains("2 sieve analyses") && Catch::Contains("Table 2") &&
                              Catch::Contains("Van Buren") && Catch::Contains("does not conform"));
    CHECK_THAT(table.out, !Catch::Contains("Table 4"));

    // Impossible tables: named by file, line and rule; nothing written.
    const fs::path out = scratch("sieve_bad");
    const Run up = run({fixture("sieve_nonmonotonic.csv"), "--out", out.string()});
    CHECK(up.status == 1);
    CHECK_THAT(up.err, Catch::Contains("sieve_nonmonotonic.csv:4:") &&
                           Catch::Contains("must not increase as the opening gets smaller"));
    const Run sum = run({fixture("sieve_masses_bad_sum.csv"), "--out", out.string()});
    CHECK(sum.status == 1);
    CHECK_THAT(sum.err, Catch::Contains("sieve_masses_bad_sum.csv:") && Catch::Contains("add up to"));
    CHECK_FALSE(fs::exists(out / "lab_results.json"));

    // Mixed inputs are a usage error.
    CHECK(run({fixture("sieve_passing.csv"), fixture("plain.csv"), "--no-write"}).status == 2);
}

TEST_CASE("lab: sieve files in lab layouts: every sand of a file, or the one named after '#'", "[lab][cli][sieve]") {
    const std::string two = fixture("sieve_layouts/12_two_sands_masses_semicolon.csv");
    const Run all = run({two, fixture("sieve_layouts/04_semicolon_decimal_comma_bom_crlf.csv"), "--no-write", "--json"});
    REQUIRE(all.status == 0);
    const auto j = nlohmann::json::parse(all.out);
    REQUIRE(j["sands"].size() == 3);
    CHECK(j["sands"][0]["name"] == "Pre-blended");
    CHECK(j["sands"][1]["name"] == "Van Buren");
    CHECK(j["sands"][2]["name"] == "04_semicolon_decimal_comma_bom_crlf");  // no sand named: the file stem
    // Van Buren's Table 2 curve at the E11 openings, read from masses: D50 between No. 50
    // (0.300 mm, 14.4 %) and No. 40 (0.425 mm, 51.9 %) = 0.3 · (0.425/0.3)^(35.6/37.5) = 0.41757 mm.
    CHECK(j["sands"][1]["gradation"]["d50_mm"].get<double>() == Approx(0.41757).epsilon(1e-4));
    const Run one = run({two + "#Van Buren", "--no-write", "--json"});
    REQUIRE(one.status == 0);
    const auto k = nlohmann::json::parse(one.out);
    REQUIRE(k["sands"].size() == 1);
    CHECK(k["sands"][0]["name"] == "Van Buren");
    CHECK(k["sands"][0]["gradation"]["d50_mm"] == j["sands"][1]["gradation"]["d50_mm"]);
    const Run none = run({two + "#Sand C", "--no-write"});
    CHECK(none.status == 1);
    CHECK_THAT(none.err, Catch::Contains("12_two_sands_masses_semicolon.csv:2: no sand 'Sand C'"));
}
