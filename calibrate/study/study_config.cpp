#include "calibrate/study/study_config.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "common/input_error.hpp"
#include "common/toml_section.hpp"

namespace gradem::cal {
namespace {

namespace fs = std::filesystem;
using common::InputError;
using namespace common::toml_io;

const std::vector<std::string> kTables = {"study", "run", "output"};

StudyKind parse_kind(const std::string& text, Context& ctx) {
    if (const auto kind = parse_enum<StudyKind>(text)) return *kind;
    throw InputError(ctx.file, ctx.keys["study.kind"].line,
                     "key 'study.kind' = \"" + text + "\": expected " + enum_names_text<StudyKind>(NameList::quoted_or));
}

/// The array `key` as a list of `T`, each checked by `read` (which throws on a bad item).
template <typename T, typename Read>
std::vector<T> read_list(Section& s, const char* key, const char* expected, Read&& read) {
    const toml::node* n = s.node(key);
    if (!n) return {};
    if (!n->is_array() || n->as_array()->empty()) s.type_error(key, *n, expected);
    std::vector<T> out;
    for (const toml::node& item : *n->as_array()) {
        const auto v = read(item);
        if (!v) s.type_error(key, *n, expected);
        if (std::find(out.begin(), out.end(), *v) != out.end()) s.type_error(key, *n, std::string(expected) + " (distinct values)");
        out.push_back(*v);
    }
    s.record(key, *n, false);
    return out;
}

std::optional<double> positive_number(const toml::node& n) {
    const auto v = n.value<double>();
    if (!v || !std::isfinite(*v) || *v <= 0.0) return std::nullopt;
    return v;
}

std::optional<std::uint64_t> positive_integer(const toml::node& n) {
    if (!n.is_integer() || n.as_integer()->get() < 1) return std::nullopt;
    return static_cast<std::uint64_t>(n.as_integer()->get());
}

std::optional<std::string> text_item(const toml::node& n) {
    if (!n.is_string()) return std::nullopt;
    return n.as_string()->get();
}

void require_file(Context& ctx, const std::string& key, const fs::path& path, const std::string& what) {
    if (!fs::exists(path))
        throw InputError(ctx.file, ctx.keys[key].line, "key '" + key + "': " + path.string() + " not found; " + what);
}

void read_study(Context& ctx, const toml::table& root, StudyConfig& c) {
    Section s(ctx, root, "study");
    std::string kind;
    s.text("kind", kind);
    s.path("calibration", c.calibration);
    const auto summaries = read_list<std::string>(s, "calibrations", "an array of summary.json paths", text_item);
    for (const auto& p : summaries) c.calibrations.push_back((ctx.dir / p).lexically_normal());
    if (auto seeds = read_list<std::uint64_t>(s, "seeds", "a non-empty array of positive integers", positive_integer);
        !seeds.empty())
        c.seeds = seeds;
    c.sands = read_list<std::string>(s, "sands", "an array of sand names", text_item);
    const auto edges = read_list<double>(s, "edges_mm", "a non-empty array of positive numbers [mm]", positive_number);
    const auto mins = read_list<double>(s, "min_diameters_mm", "a non-empty array of positive numbers [mm]", positive_number);
    c.parameters = read_list<std::string>(s, "parameters", "an array of parameter names", text_item);
    s.real("step", c.step);
    s.real("tolerance", c.tolerance);
    s.finish();
    if (kind.empty()) throw InputError(ctx.file, 0, "key 'study.kind' is required");
    c.kind = parse_kind(kind, ctx);
    auto line = [&](const char* key) { return ctx.keys[std::string("study.") + key].line; };
    c.sands_line = line("sands");
    if (!c.sands.empty() && c.kind != StudyKind::resolution && c.kind != StudyKind::fines_truncation)
        throw InputError(ctx.file, line("sands"),
                         "key 'study.sands' belongs to kinds \"resolution\" and \"fines_truncation\" (the others compare every sand)");
    const bool needs_summary = c.kind != StudyKind::model_form;
    if (needs_summary) {
        if (c.calibration.empty())
            throw InputError(ctx.file, 0, "key 'study.calibration' is required: the summary.json of a `gradem calibrate` run");
        require_file(ctx, "study.calibration", c.calibration, "run the calibration first (gradem calibrate <config>)");
    } else {
        if (c.calibrations.size() < 1)
            throw InputError(ctx.file, line("calibrations"), "key 'study.calibrations' is required: one summary.json per model");
        for (const auto& p : c.calibrations) require_file(ctx, "study.calibrations", p, "run that calibration first");
    }
    if (c.kind == StudyKind::resolution) {
        if (edges.size() < 2) throw InputError(ctx.file, line("edges_mm"), "key 'study.edges_mm' needs at least two cube edges [mm]");
        c.sweep_mm = edges;
        if (!(c.tolerance >= 0.0 && c.tolerance < 1.0))
            throw InputError(ctx.file, line("tolerance"), "key 'study.tolerance' must be a relative change in [0, 1)");
    } else if (!edges.empty()) {
        throw InputError(ctx.file, line("edges_mm"), "key 'study.edges_mm' belongs to kind \"resolution\"");
    } else if (line("tolerance") > 0) {
        throw InputError(ctx.file, line("tolerance"), "key 'study.tolerance' belongs to kind \"resolution\"");
    }
    if (c.kind == StudyKind::fines_truncation) {
        if (mins.size() < 2)
            throw InputError(ctx.file, line("min_diameters_mm"), "key 'study.min_diameters_mm' needs at least two sizes [mm]");
        c.sweep_mm = mins;
    } else if (!mins.empty()) {
        throw InputError(ctx.file, line("min_diameters_mm"), "key 'study.min_diameters_mm' belongs to kind \"fines_truncation\"");
    }
    if (!(c.step > 0.0 && c.step <= 0.5)) throw InputError(ctx.file, line("step"), "key 'study.step' must be in (0, 0.5]");
    if (c.kind == StudyKind::gradation_effect && c.seeds.size() < 2)
        throw InputError(ctx.file, line("seeds"), "key 'study.seeds': a 95 % interval needs at least two seeds per sand");
    std::sort(c.sweep_mm.begin(), c.sweep_mm.end());
}

void read_run_and_output(Context& ctx, const toml::table& root, StudyConfig& c) {
    Section run(ctx, root, "run");
    run.integer("workers", c.workers, 1);
    run.real("timeout_s", c.timeout_s);
    run.finish();
    if (!(c.timeout_s >= 0.0)) throw InputError(ctx.file, ctx.keys["run.timeout_s"].line, "key 'run.timeout_s' must be >= 0");
    Section out(ctx, root, "output");
    out.path("dir", c.out_dir);
    out.path("ledger", c.ledger);
    out.finish();
    if (c.out_dir.empty()) c.out_dir = fs::path("out") / ("study-" + std::string(to_string(c.kind)));
    if (c.ledger.empty()) c.ledger = c.out_dir / "ledger.sqlite";
}

}  // namespace

std::string StudyConfig::describe() const {
    std::ostringstream d;
    d.precision(17);
    d << "study " << to_string(kind) << "\ncalibration " << calibration.string() << "\nseeds";
    for (auto s : seeds) d << " " << s;
    d << "\nsweep_mm";
    for (double v : sweep_mm) d << " " << v;
    d << "\nparameters";
    for (const auto& p : parameters) d << " " << p;
    d << "\nstep " << step << "\n";
    if (!sands.empty()) {  // only when given, so the ledgers of studies without the key stay valid
        d << "sands";
        for (const auto& s : sands) d << " " << s;
        d << "\n";
    }
    return d.str();
}

StudyConfig load_study_config(const fs::path& toml_file) {
    Context ctx;
    ctx.file = toml_file.string();
    ctx.dir = toml_file.parent_path();
    if (!fs::exists(toml_file)) throw InputError(ctx.file, 0, "study file not found");
    const toml::table root = parse_toml_file(toml_file, ctx);
    check_tables(ctx, root, kTables);
    StudyConfig c;
    c.file = toml_file;
    read_study(ctx, root, c);
    read_run_and_output(ctx, root, c);
    return c;
}

}  // namespace gradem::cal
