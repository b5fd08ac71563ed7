// Readers: text layer, units, each export format on its fixture, and every bad-input case.
#include <catch2/catch.hpp>

#include <cmath>
#include <string>

#include "common/input_error.hpp"
#include "lab_data/export_readers.hpp"
#include "lab_data/load_frame_test.hpp"
#include "lab_data/sieve_table.hpp"
#include "lab_data/text.hpp"
#include "lab_data/units.hpp"

using namespace gradem::lab;
using Catch::Matchers::Contains;

namespace {
std::string fixture(const char* name) { return std::string(GRADEM_LAB_FIXTURES) + "/" + name; }
constexpr double kLbf = 4.4482216152605;  // N
constexpr double kInch = 0.0254;          // m
}  // namespace

TEST_CASE("lab: text decoding: BOM Windows-1252 and UTF-16 become UTF-8", "[lab][readers]") {
    CHECK(decode_text("\xEF\xBB\xBFLoad").utf8 == "Load");
    CHECK(decode_text("\xEF\xBB\xBFLoad").encoding == "utf-8 (BOM)");
    const DecodedText latin = decode_text("H\xF6he \xB5m");  // "Höhe µm" in Latin-1
    CHECK(latin.utf8 == "H\xC3\xB6he \xC2\xB5m");
    CHECK(latin.encoding == "windows-1252");
    CHECK(decode_text(std::string("\xFF\xFEN\0k\0", 6)).utf8 == "Nk");
    CHECK(split_lines("a\r\nb\rc\nd").size() == 4);
}

TEST_CASE("lab: numbers in the file's locale", "[lab][readers]") {
    const Dialect dot{',', '.'}, comma{'\t', ','};
    CHECK(*parse_number("-12.5", dot) == -12.5);
    CHECK(*parse_number("1,234.5", dot, true) == 1234.5);
    CHECK(*parse_number("12,345,678", dot, true) == 12345678.0);
    CHECK_FALSE(parse_number("1,23", dot, true));  // bad grouping
    CHECK(*parse_number("-0,0032484531", comma) == Approx(-0.0032484531));
    CHECK(*parse_number("1.234,5", comma) == 1234.5);
    CHECK(*parse_number("2.5e-3", dot) == 0.0025);
    CHECK(*parse_number("+.5", dot) == 0.5);
    for (const char* text : {"abc", "", " ", "inf", "nan", "-", "1.2.3", "12 kN"}) CHECK_FALSE(parse_number(text, dot));
}

TEST_CASE("lab: cells: quotes doubled quotes trailing spaces trailing delimiter", "[lab][readers]") {
    const auto s = split_cells(R"("Running Time ","a ""b""",3,)", ',');
    REQUIRE(s.cells.size() == 4);
    CHECK(s.cells[0].text == "Running Time ");
    CHECK(s.cells[0].quoted);
    CHECK(s.cells[1].text == "a \"b\"");
    CHECK(s.cells[2].text == "3");
    CHECK(s.cells[3].text.empty());
    CHECK(split_cells("\"open", ',').unterminated_quote);
}

TEST_CASE("lab: dialect sniffing: semicolon implies decimal comma", "[lab][readers]") {
    const std::string text = "Zeit;Kraft\ns;kN\n0,1;2,5\n0,2;3,5\n0,3;4,5\n";
    const Dialect d = sniff_dialect(split_lines(text));
    CHECK(d.delimiter == ';');
    CHECK(d.decimal == ',');
}

TEST_CASE("lab: units convert to SI", "[lab][readers]") {
    CHECK(parse_unit("(sec)")->dimension == Dimension::time);
    CHECK(parse_unit("kN")->to_si == 1e3);
    CHECK(parse_unit("lbf")->to_si == Approx(kLbf));
    CHECK(parse_unit("[in]")->to_si == Approx(kInch));
    CHECK(parse_unit("%")->to_si == 0.01);
    CHECK(parse_unit("\xC2\xB5\xCE\xB5")->to_si == 1e-6);  // µε with MICRO SIGN
    CHECK(parse_unit("\xCE\xBC\xCE\xB5")->to_si == 1e-6);  // με with GREEK MU
    CHECK(parse_unit("in/in")->dimension == Dimension::strain);
    CHECK(parse_unit("psi")->to_si == Approx(kLbf / (kInch * kInch)));
    CHECK(parse_unit("MPa")->to_si == 1e6);
    CHECK_FALSE(parse_unit("kp"));
    CHECK(split_name_unit("Load (kN)").name == "Load");
    CHECK(split_name_unit("Load (kN)").unit == "kN");
    CHECK(split_name_unit("load_kN").unit == "kN");
    CHECK(split_name_unit("Tensile strain (Extension)").unit.empty());
}

TEST_CASE("lab: MTS TestSuite CSV: BOM quoted names with spaces units row inch geometry", "[lab][readers]") {
    const LoadFrameTest t = read_load_frame_test(fixture("mts_testsuite.csv"));
    CHECK(t.format == "mts-testsuite");
    REQUIRE(t.load_n.size() == 6);
    CHECK(t.load_n[3] == Approx(12500.0));  // -12.500 kN, compression made positive
    CHECK(t.strain[3] == Approx(0.0006));
    CHECK(t.crosshead_m[3] == Approx(0.030e-3));
    CHECK(t.time_s[5] == Approx(5.0));
    CHECK(t.geometry.width_m == Approx(2 * kInch));
    CHECK(t.geometry.source == "file");
    CHECK(t.columns.at("load") == "Axial Force [kN]");
}

TEST_CASE("lab: MTS 793 specimen.dat: German locale Latin-1 two blocks with different columns", "[lab][readers]") {
    const LoadFrameTest t = read_load_frame_test(fixture("mts793_deu.dat"));
    CHECK(t.format == "mts793");
    CHECK(t.encoding == "windows-1252");
    REQUIRE(t.load_n.size() == 6);
    CHECK(t.load_n[0] == Approx(100.0));
    CHECK(t.load_n[3] == Approx(12500.0));
    CHECK(t.strain[5] == Approx(1000e-6));  // µm/m
    CHECK(t.crosshead_m[5] == Approx(0.05e-3));
    CHECK(t.geometry.width_m == Approx(0.0502));
    CHECK(t.geometry.depth_m == Approx(0.0498));
    CHECK(std::isnan(t.time_s[0]));  // the first block has no time column
    CHECK(t.time_s[5] == Approx(2.0));  // Laufzeit 5,0 s from the first value 3,0 s
    CHECK(t.columns.at("load") == "Ch 1 Kraft [kN]");  // not the "Kraft Sollwert" command
}

TEST_CASE("lab: Instron Bluehill RawData: parenthesised units thousands separators lbf and %", "[lab][readers]") {
    const LoadFrameTest t = read_load_frame_test(fixture("bluehill_raw.csv"));
    CHECK(t.format == "instron-bluehill");
    REQUIRE(t.load_n.size() == 6);
    CHECK(t.load_n[3] == Approx(2810.112 * kLbf));
    CHECK(t.strain[3] == Approx(0.0006));
    CHECK(t.geometry.width_m == Approx(0.050));
    CHECK(t.geometry.depth_m == Approx(0.040));
    CHECK(t.columns.at("crosshead") == "Extension [mm]");  // Bluehill's Extension is the crosshead
}

TEST_CASE("lab: Instron Bluehill Universal: Raw Data marker and Name (unit) headers", "[lab][readers]") {
    const LoadFrameTest t = read_load_frame_test(fixture("bluehill_universal.csv"));
    CHECK(t.format == "instron-bluehill");
    REQUIRE(t.load_n.size() == 6);
    CHECK(t.load_n[3] == Approx(12500.0));
    CHECK(t.strain[5] == Approx(0.001));
    CHECK(t.geometry.source == "nominal");
}

TEST_CASE("lab: plain CSV with units in the names and overrides of roles and units", "[lab][readers]") {
    const LoadFrameTest t = read_load_frame_test(fixture("plain.csv"));
    CHECK(t.format == "plain-csv");
    CHECK(t.load_n[2] == Approx(10000.0));
    CHECK(t.strain[2] == Approx(400e-6));
    CHECK(t.notes.empty());

    const std::string no_units = "Time,Force,Ext\n0,0,0\n1,5,0.02\n2,10,0.04\n3,12,0.06\n4,11,0.08\n";
    REQUIRE_THROWS_WITH(read_load_frame_bytes(no_units, "x.csv"), Contains("x.csv:1: column 'Time': no unit given"));
    ReadOptions o;
    o.channels.unit = {{ChannelRole::time, "s"}, {ChannelRole::load, "kN"}, {ChannelRole::strain, "%"}};
    const LoadFrameTest u = read_load_frame_bytes(no_units, "x.csv", o);
    CHECK(u.load_n[3] == Approx(12000.0));
    CHECK(u.strain[3] == Approx(0.0006));

    // An override that contradicts the header's unit is refused, unless forced with '!'.
    const std::string kn = "Time (s),Force (kN),Strain (%)\n0,0,0\n1,5,0.02\n2,10,0.04\n3,12,0.06\n4,11,0.08\n";
    ReadOptions wrong;
    wrong.channels.unit = {{ChannelRole::load, "N"}};
    REQUIRE_THROWS_WITH(read_load_frame_bytes(kn, "kn.csv", wrong),
                        Contains("kn.csv:1: column 'Force'") && Contains("override 'N' for load contradicts the header's unit 'kN'") &&
                            Contains("'!N'"));
    wrong.channels.unit = {{ChannelRole::load, "!N"}};
    CHECK(read_load_frame_bytes(kn, "kn.csv", wrong).load_n[3] == Approx(12.0));
    wrong.channels.unit = {{ChannelRole::load, "kN"}};  // agreeing with the header: fine
    CHECK(read_load_frame_bytes(kn, "kn.csv", wrong).load_n[3] == Approx(12000.0));

    o.channels.column.emplace(ChannelRole::load, "Missing Column");
    REQUIRE_THROWS_WITH(read_load_frame_bytes(no_units, "x.csv", o), Contains("column 'Missing Column' (configured as the load column)"));
}

TEST_CASE("lab: format detection does not depend on the file name", "[lab][readers]") {
    const std::string bytes = read_file_bytes(fixture("mts793_deu.dat"));
    CHECK(read_raw_export(bytes, "renamed.csv").format == "mts793");
}

TEST_CASE("lab: bad export files: error names file line and what was expected", "[lab][readers][errors]") {
    auto message = [](const char* name) {
        try {
            read_load_frame_test(fixture(name));
        } catch (const InputError& e) {
            return std::string(e.what());
        }
        return std::string("no error");
    };
    CHECK_THAT(message("empty.csv"), Contains("empty.csv:1: file is empty"));
    CHECK_THAT(message("missing_load.csv"), Contains("missing_load.csv:1: no load column"));
    CHECK_THAT(message("text_in_cell.csv"), Contains("text_in_cell.csv:6: column 'load': 'abc' is not a number"));
    CHECK_THAT(message("truncated_row.csv"), Contains("truncated_row.csv:9: truncated row: found 2 cells, expected 4"));
    CHECK_THAT(message("unknown_unit.csv"), Contains("unknown_unit.csv:1: column 'Load': unit 'kp' is unknown; expected a force unit"));
    CHECK_THAT(message("no_such_file.csv"), Contains("no_such_file.csv: cannot open file"));
}

TEST_CASE("lab: sieve tables: percent passing and masses retained give the same curve", "[lab][readers][sieve]") {
    const SieveAnalysis p = read_sieve_csv(fixture("sieve_passing.csv"));
    const SieveAnalysis m = read_sieve_csv(fixture("sieve_masses.csv"));
    CHECK(p.provenance.find("Van Buren") != std::string::npos);
    CHECK(m.from_masses);
    CHECK(m.total_g == Approx(500.0));
    REQUIRE(p.rows.size() == 8);
    REQUIRE(m.rows.size() == 8);
    for (std::size_t i = 0; i < 8; ++i) {
        CHECK(m.rows[i].opening_m == Approx(p.rows[i].opening_m));
        CHECK(m.rows[i].passing == Approx(p.rows[i].passing).margin(1e-12));
    }
    CHECK(p.rows[0].designation == "#4");  // a row starting with '#' is data, not a comment
    CHECK(p.curve.size_m.front() == Approx(75e-6));  // ascending
}

TEST_CASE("lab: bad sieve tables", "[lab][readers][sieve][errors]") {
    auto message = [](const char* name) {
        try {
            read_sieve_csv(fixture(name));
        } catch (const InputError& e) {
            return std::string(e.what());
        }
        return std::string("no error");
    };
    CHECK_THAT(message("sieve_nonmonotonic.csv"), Contains("sieve_nonmonotonic.csv:4: column 'percent_passing'") &&
                                                      Contains("must not increase"));
    CHECK_THAT(message("sieve_over_100.csv"), Contains("sieve_over_100.csv:2: column 'percent_passing': 104.2 is outside [0, 100]"));
    CHECK_THAT(message("sieve_text.csv"), Contains("sieve_text.csv:3: column 'percent_passing': 'eighty' is not a number"));
    CHECK_THAT(message("sieve_masses_bad_sum.csv"), Contains("sieve_masses_bad_sum.csv:1: masses retained incl. pan add up to 500 g"));
    CHECK_THAT(message("sieve_masses_no_pan.csv"), Contains("need a 'Pan' row"));
    CHECK_THAT(message("empty.csv"), Contains("empty.csv:1: file is empty"));
    CHECK_THROWS_WITH(parse_sieve_csv("opening_mm,percent_passing\n4.75,100\n1.18\n", "t.csv"), Contains("t.csv:3: truncated row"));
}
