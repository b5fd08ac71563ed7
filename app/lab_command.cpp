#include "app/lab_command.hpp"

#include <CLI/CLI.hpp>
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <iostream>
#include <map>
#include <optional>

#include "common/input_error.hpp"
#include "lab_data/text.hpp"
#include "reports/lab_report.hpp"

namespace gradem::lab {
namespace {

namespace fs = std::filesystem;

struct UsageError : std::runtime_error {
    using std::runtime_error::runtime_error;
};

struct CommandLine {
    std::vector<std::string> inputs;
    fs::path out = "lab_out";
    bool write = true, json = false, per_cube = false;
    std::optional<fs::path> config;
    fs::path c144;
    std::optional<std::string> format;
    std::vector<std::pair<std::string, std::string>> columns, units;
    std::optional<std::string> test;              ///< --test: the exports are tension tests of this kind
    std::map<std::string, double> dimensions_mm;  ///< --diameter-mm etc., by option name
};

// The geometry options of tension exports: option, the test it belongs to, TensileGeometry field.
struct DimensionOption {
    const char* option;
    TensileTestKind test;
    double TensileGeometry::*field;
};
const DimensionOption kDimensionOptions[] = {{"--diameter-mm", TensileTestKind::splitting, &TensileGeometry::diameter_m},
                                             {"--length-mm", TensileTestKind::splitting, &TensileGeometry::length_m},
                                             {"--width-mm", TensileTestKind::flexural, &TensileGeometry::width_m},
                                             {"--depth-mm", TensileTestKind::flexural, &TensileGeometry::depth_m},
                                             {"--span-mm", TensileTestKind::flexural, &TensileGeometry::span_m}};

std::pair<std::string, std::string> role_value(const std::string& opt, const std::string& arg) {
    const auto eq = arg.find('=');
    if (eq == std::string::npos || eq == 0) throw UsageError(opt + " expects ROLE=VALUE, got '" + arg + "'");
    return {arg.substr(0, eq), arg.substr(eq + 1)};
}

CommandLine parse(std::vector<std::string> args) {
    CommandLine c;
    std::vector<std::string> columns, units;
    std::string format, test;
    std::map<std::string, double> dimensions;
    fs::path config;
    CLI::App app{"Lab statistics from sieve analyses and load-frame exports.", "gradem lab"};
    app.set_help_flag();  // the usage text below is the help
    app.add_option("inputs", c.inputs)->required();
    app.add_option("--out", c.out);
    app.add_flag("--no-write", [&c](std::int64_t) { c.write = false; });
    app.add_flag("--json", c.json);
    app.add_flag("--cubes", c.per_cube);
    app.add_option("--config", config);
    app.add_option("--format", format);
    app.add_option("--c144", c.c144);
    app.add_option("--column", columns)->allow_extra_args(false);
    app.add_option("--unit", units)->allow_extra_args(false);
    app.add_option("--test", test);
    for (const auto& d : kDimensionOptions) app.add_option(d.option, dimensions[d.option]);
    std::reverse(args.begin(), args.end());  // CLI11 takes the arguments last-first
    try {
        app.parse(args);
    } catch (const CLI::RequiredError&) {
        throw UsageError("no input: give a dataset folder, a dataset .toml, or export files");
    } catch (const CLI::ParseError& e) {
        throw UsageError(e.what());
    }
    if (!config.empty()) c.config = config;
    if (!format.empty()) c.format = format;
    if (!test.empty()) c.test = test;
    for (const auto& d : kDimensionOptions)
        if (app.count(d.option)) c.dimensions_mm[d.option] = dimensions[d.option];
    for (const auto& v : columns) c.columns.push_back(role_value("--column", v));
    for (const auto& v : units) c.units.push_back(role_value("--unit", v));
    return c;
}

bool is_dataset(const std::string& input) {
    std::error_code ec;
    return fs::is_directory(input, ec) || fs::path(input).extension() == ".toml";
}

DatasetConfig options_for_files(const CommandLine& c) {
    DatasetConfig config = c.config ? load_dataset_config(*c.config, false) : DatasetConfig{};
    if (c.format) {
        const auto f = parse_format_name(*c.format);
        if (!f) throw UsageError("--format '" + *c.format + "': expected auto, mts-testsuite, mts793, instron-bluehill or plain-csv");
        config.read.format = *f;
    }
    for (const auto& [role, name] : c.columns) {
        const auto r = parse_role(role);
        if (!r) throw UsageError("--column: unknown role '" + role + "' (time, load, crosshead, strain, lateral_strain, stress)");
        config.read.channels.column[*r] = name;
    }
    for (const auto& [role, unit] : c.units) {
        const auto r = parse_role(role);
        if (!r) throw UsageError("--unit: unknown role '" + role + "'");
        config.read.channels.unit[*r] = unit;
    }
    return config;
}

// --test and its geometry options → the spec every tension export given is read with.
TensileSpec tension_spec(const CommandLine& c) {
    const auto kind = parse_tensile_test(*c.test);
    if (!kind) throw UsageError("--test '" + *c.test + "': expected " + kTensileTestNames);
    TensileSpec spec;
    spec.test = *kind;
    spec.nominal_source = "command line";
    for (const auto& d : kDimensionOptions) {
        const auto it = c.dimensions_mm.find(d.option);
        if (it == c.dimensions_mm.end()) continue;
        if (d.test != spec.test)
            throw UsageError(std::string(d.option) + " applies to " + tensile_test_name(d.test) + " tests, not to --test " + *c.test);
        if (!(it->second > 0) || !std::isfinite(it->second)) throw UsageError(std::string(d.option) + " must be > 0 (mm)");
        spec.nominal.*d.field = it->second * 1e-3;
    }
    return spec;
}

LabStats analyse(const CommandLine& c) {
    if (is_dataset(c.inputs.front())) {
        if (c.inputs.size() > 1) throw UsageError("a dataset folder or .toml must be the only input");
        if (c.config || c.format || !c.columns.empty() || !c.units.empty() || c.test || !c.dimensions_mm.empty())
            throw UsageError("--config/--format/--column/--unit/--test apply to export files; a dataset sets them in its TOML");
        return analyse_lab_dataset(c.inputs.front());
    }
    std::vector<fs::path> files(c.inputs.begin(), c.inputs.end());
    std::size_t sieves = 0;
    for (const auto& f : files) sieves += is_sieve_csv_file(f) ? 1 : 0;
    if (!c.test && !c.dimensions_mm.empty()) throw UsageError("the geometry options (--diameter-mm, ...) need --test splitting|flexural");
    if (c.test && sieves > 0) throw UsageError("--test applies to load-frame exports, not sieve analyses");
    if (sieves == files.size() && !c.test) {
        if (c.config || c.format || !c.columns.empty() || !c.units.empty())
            throw UsageError("--config/--format/--column/--unit apply to load-frame exports, not sieve analyses");
        return analyse_sieve_files(files, c.c144);
    }
    if (sieves > 0)
        throw UsageError("sieve analyses and load-frame exports given together: run them separately, or use a dataset");
    if (!c.c144.empty()) throw UsageError("--c144 applies to sieve analyses");
    if (c.test) {
        const TensileSpec spec = tension_spec(c);
        DatasetConfig config = options_for_files(c);
        TensileSpec with_config = spec;
        with_config.use_file_geometry = config.read.use_file_geometry;
        return analyse_tension_files(files, with_config, config);
    }
    return analyse_lab_files(files, options_for_files(c));
}

}  // namespace

const char* lab_command_usage() {
    return R"(usage: gradem lab [options] <dataset folder | dataset.toml | export file...>

Reads lab data and reduces it to the statistics calibration uses.
  dataset folder (holding dataset.toml) or a .toml file:
      sieve analyses and cube exports by sand and batch -> Table 2 (gradation, D-values,
      Cu, Cc, USCS, fineness modulus, ASTM C144 verdicts) and Table 4-style statistics
      (ASTM C109 strength, strain at peak, ASTM C469 chord modulus), Welch t-tests
      between sands, ASTM C109 permissible-range flags; [[sand.tension]] splitting and
      flexural exports -> tensile strengths and their direct-tension equivalent.
  sieve analysis files (CSV/TSV, any delimiter, decimal commas; a sieve or opening column
      - US/ISO designations, mm, um or in - and percent passing, cumulative or individual
      retained, or retained masses with a Pan row; several sands as columns, FILE#sand picks
      one; recognised from the header, lab_data/README.md lists the names): each file's
      gradation (Table 2, D-values, Cu, Cc, USCS, fineness modulus; ASTM C144 with --c144);
      impossible tables are rejected naming the file, line and rule.
  export files (MTS TestSuite CSV, MTS 793 specimen.dat, Instron Bluehill RawData, plain CSV;
      the format is detected from the content): each file is reduced, as a C109 cube, or
      with --test as a tension test: peak load -> ASTM C496 splitting tensile strength
      T = 2P/(pi l d) or ASTM C348 flexural strength Sf = 3PL/(2bd^2), and the fib Model Code
      2010 direct tensile strength (1.0 x T; 0.06h^0.7/(1 + 0.06h^0.7) x Sf, h in mm).

options:
  --out DIR           write lab_results.json, cubes.csv, tensile_tests.csv, sand_stats.csv,
                      gradation.csv, comparisons.csv and curves.csv into DIR (default:
                      ./lab_out), written atomically; then report.html (figures) when run by gradem
  --no-write          write no files
  --json              print lab_results.json to stdout instead of the tables
  --cubes             also print one row per cube (and per tension specimen)
  --config FILE       for export files: a TOML with [specimen], [reduction], [columns]
  --format NAME       for export files: auto, mts-testsuite, mts793, instron-bluehill, plain-csv
  --c144 FILE         for sieve analyses: ASTM C144 limits CSV to check them against
                      (e.g. lab_data/datasets/study/astm_c144_natural_sand.csv)
  --column ROLE=NAME  for export files: take column NAME as ROLE
                      (time, load, crosshead, strain, lateral_strain, stress)
  --unit ROLE=UNIT    for export files: unit of ROLE's column (e.g. load=kN)
  --test KIND         for export files: they are tension tests, KIND splitting (ASTM C496
                      cylinders) or flexural (ASTM C348 prisms, centre-point loading)
  --diameter-mm D, --length-mm L
                      splitting: cylinder dimensions where the export does not state them
  --width-mm B, --depth-mm D, --span-mm S
                      flexural: prism and span where the export does not state them
                      (default the C348 prism: 40 x 40 mm on a 120 mm span)
  -h, --help          show this text

exit status: 0 success, 1 bad input (message "file:line: what was expected"), 2 bad usage
)";
}

int run_lab_command(const std::vector<std::string>& args, const AfterLabOutputs& after_outputs) {
    for (const auto& a : args)
        if (a == "-h" || a == "--help") {
            std::cout << lab_command_usage();
            return 0;
        }
    try {
        const CommandLine c = parse(args);
        const LabStats lab = analyse(c);
        if (c.write) write_lab_outputs(c.out, lab);
        if (c.json) std::cout << lab_stats_to_json(lab).dump(2) << "\n";
        else print_lab_report(std::cout, lab, c.per_cube || lab.source == "files");
        if (c.write && !c.json) std::cout << "\nwrote " << (c.out / "lab_results.json").string() << " and CSV tables\n";
        if (c.write && after_outputs) after_outputs(c.out, c.json ? std::cerr : std::cout);
        return 0;
    } catch (const UsageError& e) {
        std::cerr << "gradem lab: " << e.what() << "\n(see gradem lab --help)\n";
        return 2;
    } catch (const InputError& e) {
        std::cerr << "gradem lab: " << e.what() << "\n";
        return 1;
    } catch (const std::exception& e) {
        std::cerr << "gradem lab: error: " << e.what() << "\n";
        return 1;
    }
}

}  // namespace gradem::lab
