// The lab readers' warnings: each record names the file, the lines and the count of the rows
// skipped, or the dimensions taken from a nominal value with where they were set; the same
// record gives the JSON note and the stderr line, and the sink prints each once.
#include <catch2/catch.hpp>

#include <fstream>
#include <string>
#include <vector>

#include "common/input_error.hpp"
#include "lab_data/dataset.hpp"
#include "lab_data/lab_stats.hpp"
#include "lab_data/lab_warning.hpp"
#include "lab_data/load_frame_test.hpp"
#include "lab_data/sieve_table.hpp"
#include "../temp_dir.hpp"

using namespace gradem::lab;
using Catch::Matchers::Contains;
using Catch::Matchers::EndsWith;

namespace {

std::string fixture(const std::string& name) { return std::string(GRADEM_LAB_FIXTURES) + "/warnings/" + name; }

bool has_note(const std::vector<std::string>& notes, const std::string& text) {
    for (const auto& n : notes)
        if (n == text) return true;
    return false;
}

// The sink's printer for one test: the lines it was given.
struct CollectedWarnings {
    std::vector<std::string> lines;
    CollectedWarnings() {
        warning_sink().start([this](const LabWarning& w) { lines.push_back(w.line()); });
    }
    ~CollectedWarnings() { warning_sink().start({}); }
};

}  // namespace

TEST_CASE("lab warnings: rows without load are skipped, the record has the file, lines and count", "[lab][warnings]") {
    CollectedWarnings printed;
    const LoadFrameTest t = read_load_frame_test(fixture("skipped_rows.csv"));
    REQUIRE(t.warnings.size() == 1);
    const LabWarning& w = t.warnings.front();
    CHECK(w.kind == LabWarning::Kind::rows_skipped);
    CHECK(w.file == fixture("skipped_rows.csv"));
    CHECK(w.lines == std::vector<int>{17, 18, 19, 20});
    CHECK(w.count() == 4);
    CHECK(w.message() == "4 rows skipped (lines 17-20: no load or strain value)");
    CHECK(has_note(t.notes, w.message()));  // the JSON's note is the record's message
    CHECK(t.load_n.size() == 49);           // 53 samples, 4 skipped
    CHECK(t.nominal_dimensions.empty());    // the file states its dimensions
    REQUIRE(printed.lines.size() == 1);
    CHECK(printed.lines.front() == "warning: " + fixture("skipped_rows.csv") + ": 4 rows skipped (lines 17-20: no load or strain value)");
}

TEST_CASE("lab warnings: a cube without dimensions in the file gets the nominal ones, named with their origin", "[lab][warnings]") {
    CollectedWarnings printed;
    const LoadFrameTest t = read_load_frame_test(fixture("no_dimensions.csv"));
    CHECK(t.warnings.empty());
    REQUIRE(t.nominal_dimensions.size() == 3);
    CHECK(t.no_file_dimensions);
    const LabWarning w = cube_geometry_warning(t);
    CHECK(w.kind == LabWarning::Kind::nominal_geometry);
    CHECK(w.file == fixture("no_dimensions.csv"));
    CHECK(w.message() == "no specimen dimensions in the file; nominal 50 x 50 x 50 mm (width x depth x height) from "
                         "gradem's default (the ASTM C109 50 mm cube)");

    // In a dataset: the [specimen] values, the file and the keys.
    const LabStats lab = analyse_lab_dataset(fixture("dataset.toml"));
    REQUIRE(lab.cubes.size() == 2);
    const CubeResult& silent = lab.cubes[1];
    CHECK_THAT(silent.file, EndsWith("no_dimensions.csv"));
    REQUIRE(silent.warnings.size() == 1);
    const LabWarning& g = silent.warnings.front();
    REQUIRE(g.dimensions.size() == 3);
    CHECK(g.dimensions[0].name == "width");
    CHECK(g.dimensions[0].value_m == Approx(0.0508));
    CHECK(g.dimensions[0].origin == fixture("dataset.toml") + " [specimen]");
    CHECK(g.dimensions[2].key == "height_mm");
    CHECK(g.message() == "no specimen dimensions in the file; nominal 50.8 x 50.8 x 50.8 mm (width x depth x height) from " +
                             fixture("dataset.toml") + " [specimen] width_mm, depth_mm, height_mm");
    CHECK(has_note(silent.notes, g.message()));
    CHECK(silent.geometry.loaded_area_m2() == Approx(0.0508 * 0.0508));
    CHECK(lab.cubes[0].warnings.size() == 1);  // the skipped rows; its dimensions are the file's
    // The sink printed every record once: the sieve row, the skipped rows, the nominal cube.
    CHECK(printed.lines.size() == 3);
}

TEST_CASE("lab warnings: a sieve row below the end of the table is not read and is a warning", "[lab][warnings][sieve]") {
    CollectedWarnings printed;
    const SieveAnalysis s = read_sieve_csv(fixture("sieve_row_after_table.csv"));
    CHECK(s.rows.size() == 7);  // No. 4 to No. 100: the No. 200 row is not read
    REQUIRE(s.warnings.size() == 1);
    const LabWarning& w = s.warnings.front();
    CHECK(w.file == fixture("sieve_row_after_table.csv"));
    CHECK(w.lines == std::vector<int>{12});
    CHECK(w.message() == "1 row skipped (line 12: they name a sieve but follow line 11, which ends the table)");
    REQUIRE(printed.lines.size() == 1);
}

TEST_CASE("lab warnings: many rows give one bounded line with the full count", "[lab][warnings]") {
    CHECK(describe_lines({7}) == "line 7");
    CHECK(describe_lines({3, 4, 5}) == "lines 3-5");
    const LabWarning w = rows_skipped("f.csv", {15, 1, 2, 3, 5, 7, 9, 11, 13}, "no load or strain value");
    CHECK(w.lines.front() == 1);  // sorted
    CHECK(w.count() == 9);
    CHECK(w.line() == "warning: f.csv: 9 rows skipped (lines 1-3, 5, 7, 9, 11, ...: no load or strain value)");
}

TEST_CASE("lab warnings: the sink prints each record once per start, none without a printer", "[lab][warnings]") {
    std::vector<std::string> got;
    warning_sink().start([&](const LabWarning& w) { got.push_back(w.message()); });
    const LabWarning w = rows_skipped("f.csv", {4}, "x");
    warning_sink().add(w);
    warning_sink().add(w);
    CHECK(got.size() == 1);
    warning_sink().start([&](const LabWarning& x) { got.push_back(x.message()); });
    warning_sink().add(w);  // a new command: printed again
    CHECK(got.size() == 2);
    warning_sink().start({});
    warning_sink().add(rows_skipped("g.csv", {1}, "x"));
    CHECK(got.size() == 2);
}

TEST_CASE("lab warnings: a dataset's non-finite number is refused naming file, line and key", "[lab][warnings][errors]") {
    gradem::test::TempDir dir("lab-inf");
    const auto toml = dir.path / "dataset.toml";
    std::ofstream(toml) << "[dataset]\nname = \"x\"\n[specimen]\nwidth_mm = inf\n";
    CHECK_THROWS_WITH(load_dataset_config(toml, false),
                      Contains(toml.string() + ":4: key 'width_mm' = inf: expected a finite number"));
    std::ofstream(toml) << "[reduction]\nchord_lower_strain = nan\n";
    CHECK_THROWS_WITH(load_dataset_config(toml, false), Contains(":2: key 'chord_lower_strain' = nan: expected a finite number"));
}
