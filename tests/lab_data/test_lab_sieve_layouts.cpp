// Sieve analyses in the layouts labs write: every fixture in fixtures/sieve_layouts/ describes
// the study's pre-blended sand (Table 2) at the ASTM E11 openings and must reduce to the same
// percent-passing curve; each rule an impossible table breaks is refused naming file, line, rule.
#include <catch2/catch.hpp>

#include <cmath>
#include <filesystem>
#include <set>
#include <string>

#include "common/input_error.hpp"
#include "common/text_file.hpp"
#include "lab_data/sieve_layout.hpp"
#include "lab_data/sieve_table.hpp"

using namespace gradem::lab;
using Catch::Matchers::Contains;
namespace fs = std::filesystem;

namespace {

const fs::path kLayouts = fs::path(GRADEM_LAB_FIXTURES) / "sieve_layouts";

struct Point {
    double opening_m, passing;
};
// Pre-blended sand, Table 2 of the study, at the ASTM E11 openings of its sieves.
const std::vector<Point> kPreBlended = {{4.75e-3, 1.000}, {2.36e-3, 0.996}, {1.18e-3, 0.981}, {0.600e-3, 0.919},
                                        {0.425e-3, 0.832}, {0.300e-3, 0.699}, {0.150e-3, 0.256}, {0.075e-3, 0.000}};
const std::vector<Point> kVanBuren = {{4.75e-3, 1.000}, {2.36e-3, 0.998}, {1.18e-3, 0.955}, {0.600e-3, 0.825},
                                      {0.425e-3, 0.519}, {0.300e-3, 0.144}, {0.150e-3, 0.006}, {0.075e-3, 0.000}};

struct Layout {
    const char* file;
    const char* sand;           // selector for files with several sands
    double opening_tolerance;   // relative; the inch file rounds E11's inch openings
};
const Layout kCorpus[] = {
    {"01_snake_case.csv", "", 1e-9},
    {"02_title_metadata_notes.csv", "", 1e-9},
    {"03_us_numbers_only.csv", "", 1e-9},
    {"04_semicolon_decimal_comma_bom_crlf.csv", "", 1e-9},
    {"05_micrometres_tab.csv", "", 1e-9},
    {"06_iso_designations_finest_first.csv", "", 1e-9},
    {"07_masses_pan_total.csv", "", 1e-9},
    {"08_retained_kg_sieve_size.csv", "", 1e-9},
    {"09_inch_openings_cumulative_percent.csv", "", 0.02},  // 0.0029 in = 0.0737 mm for 0.075 mm
    {"10_inch_designations_individual_percent.csv", "", 1e-9},
    {"11_two_sands_percent_passing.csv", "Pre-blended", 1e-9},
    {"12_two_sands_masses_semicolon.csv", "pre-blended", 1e-9},
    {"13_c136_worksheet_units_row.csv", "", 1e-9},
    {"14_us_sieve_no_tab_finest_first.csv", "", 1e-9},
    {"15_combined_designations_percent_signs.csv", "", 1e-9},
};

// Every reference sieve is in the analysis with the same passing; sieves the reference lacks
// lie above its coarsest sieve with 100 % passing (the same curve: 3/8" in some layouts).
void check_same_curve(const SieveAnalysis& s, const std::vector<Point>& reference, double opening_tolerance) {
    std::size_t matched = 0;
    for (const SieveRow& row : s.rows) {
        INFO("line " << row.line << ", opening " << row.opening_m * 1e3 << " mm");
        const auto ref = std::find_if(reference.begin(), reference.end(), [&](const Point& p) {
            return std::abs(p.opening_m - row.opening_m) <= opening_tolerance * p.opening_m;
        });
        if (ref == reference.end()) {
            CHECK(row.opening_m > reference.front().opening_m);
            CHECK(row.passing == 1.0);
            continue;
        }
        ++matched;
        CHECK(row.passing == Approx(ref->passing).margin(1e-9));
    }
    CHECK(matched == reference.size());
    CHECK(s.curve.size_m.size() == s.rows.size());
    if (opening_tolerance > 1e-9) return;  // rounded openings interpolate slightly differently
    CHECK(s.curve.passing_fraction(0.2e-3) == Approx(GradationCurve::from_points({0.3e-3, 0.15e-3}, {reference[5].passing, reference[6].passing})
                                                         .passing_fraction(0.2e-3))
                                                  .margin(1e-9));
}

// The InputError message of parsing `text` as the file `name`.
std::string error_of(const std::string& text, const std::string& name, std::string_view sand = {}) {
    try {
        parse_sieve_csv(text, name, sand);
    } catch (const gradem::common::InputError& e) {
        return e.what();
    }
    return "no error";
}

const std::string kHeader = "Sieve,Opening (mm),% Passing\n";

}  // namespace

TEST_CASE("lab: sieve layouts: every layout of the corpus gives the pre-blended curve", "[lab][sieve][layouts]") {
    std::set<std::string> listed, present;
    for (const Layout& l : kCorpus) listed.insert(l.file);
    for (const auto& e : fs::directory_iterator(kLayouts))
        if (e.path().extension() == ".csv") present.insert(e.path().filename().string());
    CHECK(present == listed);  // a new fixture needs a row in kCorpus
    CHECK(listed.size() >= 12);
    for (const Layout& l : kCorpus) {
        INFO(l.file);
        const fs::path path = kLayouts / l.file;
        const SieveAnalysis s = read_sieve_csv(path, l.sand);
        check_same_curve(s, kPreBlended, l.opening_tolerance);
        CHECK(is_sieve_csv_file(path));
    }
}

TEST_CASE("lab: sieve layouts: what each layout records besides the curve", "[lab][sieve][layouts]") {
    const SieveAnalysis masses = read_sieve_csv(kLayouts / "07_masses_pan_total.csv");
    CHECK(masses.from_masses);
    CHECK(masses.total_g == 500.0);
    CHECK(masses.pan_g == 0.0);
    CHECK(masses.rows[1].retained_g == 2.0);
    CHECK(masses.rows[1].designation == "No. 8");
    const SieveAnalysis kg = read_sieve_csv(kLayouts / "08_retained_kg_sieve_size.csv");
    CHECK(kg.total_g == Approx(500.0).epsilon(1e-12));  // kg converted to g once, at read
    const SieveAnalysis worksheet = read_sieve_csv(kLayouts / "13_c136_worksheet_units_row.csv");
    CHECK(worksheet.sand == "pre-blended");  // from "Sample:,pre-blended"
    CHECK(worksheet.columns.size() == 4);    // masses used, the other three checked against them
    CHECK(worksheet.from_masses);
    CHECK(worksheet.rows.front().opening_m == Approx(9.5e-3));  // 3/8 in: the E11 nominal opening
    const SieveAnalysis metadata = read_sieve_csv(kLayouts / "02_title_metadata_notes.csv");
    CHECK(metadata.sand == "pre-blended");
    CHECK(metadata.rows.size() == 8);
    CHECK(read_sieve_csv(kLayouts / "01_snake_case.csv").provenance.empty());
}

TEST_CASE("lab: sieve layouts: specification limit columns beside a sand are not read", "[lab][sieve][layouts]") {
    const std::vector<SieveAnalysis> all =
        parse_sieve_csv_all("Sieve,% Passing,C144 min % passing,C144 max % passing\nNo. 4,100,95,100\nNo. 16,80,50,85\n", "spec.csv");
    REQUIRE(all.size() == 1);
    CHECK(all[0].columns == std::vector<std::string>{"% Passing"});
    CHECK(all[0].rows[1].passing == Approx(0.80));
}

TEST_CASE("lab: sieve layouts: rows that only look like Pan or Total, units rows with '-'", "[lab][sieve][layouts]") {
    // "Total mass before washing: ..." below the table holds no number in a value column: not a
    // second Total row. A units row may mark unitless columns with '-'.
    const SieveAnalysis s = parse_sieve_csv("Sieve,Mass Retained,Remark\n-,(g),-\n#4,0,\n#16,100,\n#50,300,\nPan,100,\n"
                                            "Total,500,\n\nTotal mass before washing: 501 g\n",
                                            "notes.csv");
    CHECK(s.total_g == 500.0);
    CHECK(s.rows.size() == 3);
    CHECK(s.rows[2].passing == Approx(0.2));
}

TEST_CASE("lab: sieve layouts: several sands in one file", "[lab][sieve][layouts]") {
    for (const char* file : {"11_two_sands_percent_passing.csv", "12_two_sands_masses_semicolon.csv"}) {
        INFO(file);
        const fs::path path = kLayouts / file;
        const std::vector<SieveAnalysis> all = read_sieve_csv_all(path);
        REQUIRE(all.size() == 2);
        CHECK(all[0].sand == "Pre-blended");
        CHECK(all[1].sand == "Van Buren");
        check_same_curve(all[1], kVanBuren, 1e-9);
        // A single-sand reader names the sand after '#' (datasets and configs), or gets an error.
        check_same_curve(read_sieve_csv(path.string() + "#Van Buren"), kVanBuren, 1e-9);
        CHECK(read_sieve_csv_all(path.string() + "#van buren").size() == 1);
        CHECK_THROWS_WITH(read_sieve_csv(path), Contains(std::string(file) + ":2: 2 sands in this file (columns '") &&
                                                    Contains("Van Buren") && Contains("#Pre-blended"));
        CHECK_THROWS_WITH(read_sieve_csv(path, "Sand C"), Contains(":2: no sand 'Sand C' in this file (sands: 'Pre-blended', 'Van Buren')"));
    }
}

TEST_CASE("lab: sieve layouts: recognised by content, load-frame exports are not", "[lab][sieve][layouts]") {
    const fs::path fixtures(GRADEM_LAB_FIXTURES);
    for (const char* f : {"plain.csv", "mts_testsuite.csv", "bluehill_raw.csv", "bluehill_universal.csv", "mts793_deu.dat"}) {
        INFO(f);
        CHECK_FALSE(is_sieve_csv_file(fixtures / f));
    }
    CHECK(is_sieve_csv_file(fixtures / "sieve_passing.csv"));
    CHECK(looks_like_sieve_csv("Sieve,Mass (g)\nNo. 4,0\n"));  // refused later, saying what it needs
    CHECK_FALSE(looks_like_sieve_csv("Time (s),Load (kN)\n0,0\n"));
}

TEST_CASE("lab: sieve designations: ASTM E11 numbers, inch and metric sizes, Pan and Total", "[lab][sieve][layouts]") {
    const Dialect dot;
    auto mm = [&](const char* text, BareNumbers bare = {}) {
        const auto d = parse_sieve_designation(text, dot, bare);
        REQUIRE(d);
        INFO(text << ": " << d->problem);
        REQUIRE(d->problem.empty());
        return d->opening_m * 1e3;
    };
    CHECK(mm("No. 4") == Approx(4.75));
    CHECK(mm("no.16") == Approx(1.18));
    CHECK(mm("#30") == Approx(0.600));
    CHECK(mm("# 140") == Approx(0.106));
    CHECK(mm("No 200") == Approx(0.075));
    CHECK(mm("80", {true, 0}) == Approx(0.180));
    CHECK(mm("3/8\"") == Approx(9.5));        // E11 nominal, not 9.525
    CHECK(mm("3/8 in") == Approx(9.5));
    CHECK(mm("1 1/2 in") == Approx(37.5));
    CHECK(mm("3/4", {false, 0.0254}) == Approx(19.0));
    CHECK(mm("4.75 mm") == Approx(4.75));
    CHECK(mm("600 \xC2\xB5m") == Approx(0.600));
    CHECK(mm("75um") == Approx(0.075));
    CHECK(mm("No. 4 (4.75 mm)") == Approx(4.75));
    CHECK(mm("0.6", {false, 1e-3}) == Approx(0.600));
    CHECK(parse_sieve_designation("4,75 mm", Dialect{';', ','})->opening_m == Approx(4.75e-3));
    CHECK(parse_sieve_designation("Pan", dot)->kind == SieveRowKind::pan);
    CHECK(parse_sieve_designation("Total:", dot)->kind == SieveRowKind::total);
    CHECK_THAT(parse_sieve_designation("No. 13", dot)->problem, Contains("not an ASTM E11 sieve number"));
    CHECK_THAT(parse_sieve_designation("4", dot)->problem, Contains("ambiguous"));
    CHECK_FALSE(parse_sieve_designation("Notes: washed", dot));
    CHECK_FALSE(parse_sieve_designation("No wash", dot));
}

TEST_CASE("lab: sieve headers: aliases, units and sand names", "[lab][sieve][layouts]") {
    auto column = [](const char* header) {
        const auto c = classify_sieve_header(header, 0);
        REQUIRE(c);
        return *c;
    };
    CHECK(column("Opening (mm)").to_si == 1e-3);
    CHECK(column("Opening (in)").to_si == 0.0254);
    CHECK(column("Particle Size (\xC2\xB5m)").to_si == Approx(1e-6));
    CHECK(column("Sieve Size").measure == SieveMeasure::opening);
    CHECK(column("Sieve (mm)").measure == SieveMeasure::opening);
    CHECK(column("Sieve No.").bare_numbers_are_us_sieves);
    CHECK(column("PERCENT PASSING (%)").measure == SieveMeasure::passing);
    CHECK(column("% Finer").measure == SieveMeasure::passing);
    CHECK(column("Weight Retained (g)").basis == SieveBasis::mass);
    CHECK(column("Retained (kg)").to_si == 1e3);  // grams per kg
    CHECK(column("Weight Retained (%)").basis == SieveBasis::percent);
    CHECK(column("Cumulative Retained (%)").measure == SieveMeasure::cumulative_retained);
    CHECK(column("% Retained").measure == SieveMeasure::retained);
    CHECK(column("mass_retained_g").basis == SieveBasis::mass);
    CHECK(column("Sand A % passing").sand == "Sand A");
    CHECK(column("% Passing - Sand B").sand == "Sand B");
    CHECK(column("% Passing (Sand B)").sand == "Sand B");
    CHECK_THAT(column("Retained").problem, Contains("give its unit"));
    CHECK_THAT(column("% Retained (g)").problem, Contains("is a mass but the column is a percentage"));
    CHECK(column("C144 min % passing").limit);  // a specification limit, not a sand
    CHECK_FALSE(column("Sand A % passing").limit);
    CHECK_FALSE(classify_sieve_header("Load (kN)", 0));
}

// ---- One test per rule an impossible table breaks --------------------------------------------

TEST_CASE("lab: bad sieve table: percent passing that rises as the sieve gets finer", "[lab][sieve][errors]") {
    CHECK_THAT(error_of(kHeader + "No. 4,4.75,100\nNo. 16,1.18,80\nNo. 50,0.3,85\n", "rise.csv"),
               Contains("rise.csv:4: column '% Passing': 85 % through the finer sieve is more than 80 %") &&
                   Contains("percent passing must not increase as the opening gets smaller"));
    CHECK_THAT(error_of("Sieve,Cumulative Retained (%)\n#4,0\n#16,20\n#50,10\n", "cum.csv"),
               Contains("cum.csv:4: column 'Cumulative Retained (%)'") && Contains("cumulative retained must not decrease"));
}

TEST_CASE("lab: bad sieve table: masses that do not add up to the stated Total", "[lab][sieve][errors]") {
    CHECK_THAT(error_of("Sieve,Mass Retained (g)\n#4,0\n#16,100\n#50,300\nPan,50\nTotal,480\n", "total.csv"),
               Contains("total.csv:6: column 'Mass Retained (g)': the Total row says 480 g but the sieves and pan add up to 450 g") &&
                   Contains("must add up to the stated Total"));
    CHECK_THAT(error_of("# initial_dry_mass_g: 520\nSieve,Mass Retained (g)\n#4,0\n#16,100\nPan,400\n", "initial.csv"),
               Contains("initial.csv:1: masses retained incl. pan add up to 500 g but the initial dry mass is 520 g") &&
                   Contains("at most 0.3 %"));
}

TEST_CASE("lab: bad sieve table: percentages over 100 or below 0", "[lab][sieve][errors]") {
    CHECK_THAT(error_of(kHeader + "No. 4,4.75,104.2\nNo. 16,1.18,80\n", "over.csv"),
               Contains("over.csv:2: column '% Passing': 104.2 is outside [0, 100]"));
    CHECK_THAT(error_of("Sieve;% Retained\n#4;0\n#16;-1,5\n", "below.csv"), Contains("below.csv:3: column '% Retained': -1,5 is outside [0, 100]"));
}

TEST_CASE("lab: bad sieve table: negative masses", "[lab][sieve][errors]") {
    CHECK_THAT(error_of("Sieve,Weight Retained (g)\n#4,0\n#16,-2.5\nPan,10\n", "negative.csv"),
               Contains("negative.csv:3: column 'Weight Retained (g)': -2.5 is negative"));
}

TEST_CASE("lab: bad sieve table: duplicate sieves", "[lab][sieve][errors]") {
    CHECK_THAT(error_of("Sieve,% Passing\nNo. 16,98\nNo. 30,90\n600 um,90\n", "dup.csv"),
               Contains("dup.csv:4: duplicate sieve: opening 0.6 mm repeats line 3"));
    CHECK_THAT(error_of("Sieve,Mass Retained (g)\n#4,0\n#16,10\nPan,1\nPan,2\n", "pans.csv"), Contains("pans.csv:5: a second 'Pan' row (line 4 has one)"));
}

TEST_CASE("lab: bad sieve table: a table without the columns it needs says which it accepts", "[lab][sieve][errors]") {
    CHECK_THAT(error_of("Project: x\nSieve,Mass (g)\nNo. 4,0\n", "cols.csv"),
               Contains("cols.csv:2: this row names 'Sieve' but a sieve table needs a sieve column (Sieve, Sieve No.") &&
                   Contains("% Passing") && Contains("Mass Retained (g|kg)"));
    CHECK_THAT(error_of("Sieve,Retained\n#4,0\n", "unit.csv"), Contains("unit.csv:1: column 'Retained': give its unit: (g), (kg) or (%)"));
    CHECK_THAT(error_of("a,b\n1,2\n", "none.csv"), Contains("none.csv:1: no sieve-table header found"));
    const std::string c144 = std::string(GRADEM_LAB_STUDY) + "/astm_c144_natural_sand.csv";
    CHECK_THAT(error_of(gradem::common::read_file_bytes(c144), "c144.csv"),
               Contains("c144.csv:3: this row names 'sieve', 'opening_mm' ('min_passing_pct', 'max_passing_pct' are specification limits"));
    CHECK_THAT(error_of("\n\n", "empty.csv"), Contains("empty.csv:1: file is empty"));
}

TEST_CASE("lab: bad sieve table: sieves the reader does not know", "[lab][sieve][errors]") {
    CHECK_THAT(error_of("Sieve,% Passing\nNo. 4,100\nNo. 13,80\n", "e11.csv"), Contains("e11.csv:3: 'No. 13' is not an ASTM E11 sieve number"));
    CHECK_THAT(error_of("Sieve,% Passing\n4,100\n16,80\n", "bare.csv"), Contains("bare.csv:2: '4' is ambiguous") && Contains("Sieve No."));
    CHECK_THAT(error_of("Sieve,% Passing\nNo. 4,100\nWash loss,2\n", "wash.csv"), Contains("wash.csv:3: 'Wash loss' is not a sieve: expected No. 4"));
}

TEST_CASE("lab: bad sieve table: percentages retained that do not add up to 100", "[lab][sieve][errors]") {
    CHECK_THAT(error_of("Sieve,% Retained\n#4,0\n#16,40\n#50,50\nPan,5\n", "sum.csv"),
               Contains("sum.csv:5: column '% Retained': the percentages retained incl. pan add up to 95 %, not 100 %"));
}

TEST_CASE("lab: bad sieve table: columns of one sand that disagree", "[lab][sieve][errors]") {
    CHECK_THAT(error_of("Sieve,Mass Retained (g),% Passing\n#4,0,100\n#16,100,80\n#50,300,25\nPan,100,\n", "disagree.csv"),
               Contains("disagree.csv:4: columns 'Mass Retained (g)' and '% Passing' disagree: 20 % and 25 % passing") &&
                   Contains("within 1 percentage point"));
}

TEST_CASE("lab: bad sieve table: cumulative masses without the total, truncated rows, a second table", "[lab][sieve][errors]") {
    CHECK_THAT(error_of("Sieve,Cumulative Retained (g)\n#4,0\n#16,100\n", "cumg.csv"), Contains("cumg.csv:3:") && Contains("need a 'Pan' or 'Total' row"));
    CHECK_THAT(error_of(kHeader + "#4,4.75,100\n#16,1.18\n", "short.csv"), Contains("short.csv:3: truncated row: found 2 cells, expected 3"));
    CHECK_THAT(error_of(kHeader + "#4,4.75,100\n#16,1.18,80\n\nSample B\n" + kHeader + "#4,4.75,100\n", "two.csv"),
               Contains("two.csv:6: a second sieve table starts here") && Contains("one table per file"));
}
