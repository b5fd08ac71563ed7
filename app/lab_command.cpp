#include "app/lab_command.hpp"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <iostream>
#include <map>
#include <memory>
#include <optional>
#include <utility>

#include "app/cli.hpp"
#include "common/input_error.hpp"
#include "lab_data/text.hpp"
#include "reports/lab_report.hpp"

namespace gradem::app {

using namespace gradem::lab;  // the readers and statistics the command drives

namespace {

namespace fs = std::filesystem;

using UsageError = app::UsageError;

struct CommandLine {
    std::vector<std::string> inputs;
    fs::path out = "lab_out";
    bool write = true, per_cube = false;
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
    const char* help;
    TensileTestKind test;
    double TensileGeometry::*field;
};
const DimensionOption kDimensionOptions[] = {
    {"--diameter-mm", "splitting: cylinder diameter where the export does not state it", TensileTestKind::splitting, &TensileGeometry::diameter_m},
    {"--length-mm", "splitting: cylinder length where the export does not state it", TensileTestKind::splitting, &TensileGeometry::length_m},
    {"--width-mm", "flexural: prism width where the export does not state it (default 40, ASTM C348)", TensileTestKind::flexural, &TensileGeometry::width_m},
    {"--depth-mm", "flexural: prism depth where the export does not state it (default 40, ASTM C348)", TensileTestKind::flexural, &TensileGeometry::depth_m},
    {"--span-mm", "flexural: support span where the export does not state it (default 120, ASTM C348)", TensileTestKind::flexural, &TensileGeometry::span_m}};

std::pair<std::string, std::string> role_value(const std::string& opt, const std::string& arg) {
    const auto eq = arg.find('=');
    if (eq == std::string::npos || eq == 0) throw UsageError(opt + " expects ROLE=VALUE, got '" + arg + "'");
    return {arg.substr(0, eq), arg.substr(eq + 1)};
}

bool is_dataset(const std::string& input) {
    std::error_code ec;
    return fs::is_directory(input, ec) || fs::path(input).extension() == ".toml";
}

DatasetConfig options_for_files(const CommandLine& c) {
    DatasetConfig config = c.config ? load_dataset_config(*c.config, false) : DatasetConfig{};
    if (c.format) {
        const auto f = parse_format_name(*c.format);
        if (!f) throw UsageError("--format '" + *c.format + "': expected " + enum_names_text<ExportFormat>(NameList::comma_or));
        config.read.format = *f;
    }
    for (const auto& [role, name] : c.columns) {
        const auto r = parse_role(role);
        if (!r) throw UsageError("--column: unknown role '" + role + "' (" + enum_names_text<ChannelRole>() + ")");
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
    if (!kind) throw UsageError("--test '" + *c.test + "': expected " + enum_names_text<TensileTestKind>(NameList::comma_or));
    TensileSpec spec;
    spec.test = *kind;
    spec.nominal_source = "command line";
    for (const auto& d : kDimensionOptions) {
        const auto it = c.dimensions_mm.find(d.option);
        if (it == c.dimensions_mm.end()) continue;
        if (d.test != spec.test)
            throw UsageError(std::string(d.option) + " applies to " + to_string(d.test) + " tests, not to --test " + *c.test);
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


class LabCommand final : public app::Command {
public:
    explicit LabCommand(AfterLabOutputs after_outputs) : after_outputs_(std::move(after_outputs)) {}

    void declare(CLI::App& app) override {
        app.add_option("inputs", c_.inputs, "a dataset folder (holding dataset.toml), a dataset .toml, export files or sieve analysis files")
            ->required()
            ->type_name("input");
        out_ = app.add_option("--out", c_.out,
                              "write lab_results.json, cubes.csv, tensile_tests.csv, sand_stats.csv, gradation.csv, comparisons.csv and curves.csv "
                              "into DIR (default: ./lab_out; with --json, none unless --out is given), atomically; then "
                              "report.html (figures)")
                   ->type_name("DIR");
        app.add_flag_function("--no-write", [this](std::int64_t) { c_.write = false; }, "write no files");
        app.add_flag("--cubes", c_.per_cube, "also print one row per cube (and per tension specimen)");
        app.add_option("--config", config_, "for export files: a TOML with [specimen], [reduction], [columns]")->type_name("FILE");
        app.add_option("--format", format_, "for export files: " + enum_names_text<ExportFormat>())
            ->type_name("NAME");
        app.add_option("--c144", c_.c144,
                       "for sieve analyses: ASTM C144 limits CSV to check them against "
                       "(e.g. lab_data/datasets/study/astm_c144_natural_sand.csv)")
            ->type_name("FILE");
        app.add_option("--column", columns_,
                       "for export files: take column NAME as ROLE (time, load, crosshead, strain, lateral_strain, stress)")
            ->allow_extra_args(false)
            ->type_name("ROLE=NAME");
        app.add_option("--unit", units_, "for export files: unit of ROLE's column (e.g. load=kN)")
            ->allow_extra_args(false)
            ->type_name("ROLE=UNIT");
        app.add_option("--test", test_,
                       "for export files: they are tension tests, KIND splitting (ASTM C496 cylinders) or flexural "
                       "(ASTM C348 prisms, centre-point loading); without it an export is a C109 cube")
            ->type_name("KIND");
        for (const auto& d : kDimensionOptions) dimension_options_.push_back(app.add_option(d.option, dimensions_[d.option], d.help)->type_name("MM"));
    }

    [[nodiscard]] std::string details() const override {
        return R"(Reads lab data and reduces it to the statistics calibration uses.
  dataset folder (holding dataset.toml) or a .toml file:
      sieve analyses and cube exports by sand and batch -> Table 2 (gradation, D-values,
      Cu, Cc, USCS, fineness modulus, ASTM C144 verdicts) and Table 4-style statistics
      (ASTM C109 strength, strain at peak, ASTM C469 chord modulus), Welch t-tests
      between sands, ASTM C109 permissible-range flags.
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
  warnings (stderr, one line per file and event, none with --quiet; also among the JSON's
      notes): data rows skipped, with their lines and count, and specimen dimensions a file
      does not state, with the nominal value used and where it was set.
)";
    }

    int run() override {
        if (!config_.empty()) c_.config = config_;
        if (!format_.empty()) c_.format = format_;
        for (const auto& v : columns_) c_.columns.push_back(role_value("--column", v));
        for (const auto& v : units_) c_.units.push_back(role_value("--unit", v));
        if (!test_.empty()) c_.test = test_;
        for (std::size_t k = 0; k < dimension_options_.size(); ++k)
            if (dimension_options_[k]->count()) c_.dimensions_mm[kDimensionOptions[k].option] = dimensions_[kDimensionOptions[k].option];
        const app::Console& con = app::console();
        // --json prints the results instead of writing them, unless --out asks for the files too.
        const bool write = c_.write && (!con.json() || out_->count() > 0);
        const LabStats lab = analyse(c_);
        if (write) report::write_lab_outputs(c_.out, lab);
        if (con.json()) app::Console::print_json(report::lab_stats_to_json(lab).dump(2));
        else report::print_lab_report(con.text_stream(), lab, c_.per_cube || lab.source == "files");
        if (write && !con.json()) con.text_stream() << "\nwrote " << (c_.out / "lab_results.json").string() << " and CSV tables\n";
        if (write && after_outputs_) after_outputs_(c_.out, con.announce());
        return common::exit_success;
    }

private:
    AfterLabOutputs after_outputs_;
    CommandLine c_;
    CLI::Option* out_ = nullptr;
    std::vector<std::string> columns_, units_;
    std::string format_, test_;
    std::map<std::string, double> dimensions_;
    std::vector<CLI::Option*> dimension_options_;
    fs::path config_;
};

}  // namespace

std::unique_ptr<app::Command> make_lab_command(AfterLabOutputs after_outputs) {
    return std::make_unique<LabCommand>(std::move(after_outputs));
}

int run_lab_command(const std::vector<std::string>& args, const AfterLabOutputs& after_outputs) {
    LabCommand command(after_outputs);
    return app::run_command(app::command_info("lab"), command, args);
}

}  // namespace gradem::app
