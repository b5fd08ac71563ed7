#include "calibrate/study/study_config.hpp"

#include <algorithm>
#include <sstream>

#include "calibrate/study/study_keys.hpp"
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

/// "kind \"a\"" or "kinds \"a\" and \"b\"": the kinds whose own keys include `key`.
std::string owners_of(const std::string& key) {
    std::vector<std::string> owners;
    for (const std::string& name : enum_names<StudyKind>()) {
        const StudyKindSpec& spec = study_kind(*parse_enum<StudyKind>(name));
        if (std::find(spec.keys.begin(), spec.keys.end(), key) != spec.keys.end()) owners.push_back("\"" + name + "\"");
    }
    std::string out = owners.size() == 1 ? "kind " : "kinds ";
    for (std::size_t k = 0; k < owners.size(); ++k) out += (k == 0 ? "" : k + 1 == owners.size() ? " and " : ", ") + owners[k];
    return out;
}

/// A key of another kind in this kind's study: refused, naming the kinds it belongs to.
void refuse_other_kinds_keys(Context& ctx, Section& s, const StudyKindSpec& own) {
    for (const std::string& name : enum_names<StudyKind>())
        for (const std::string& key : study_kind(*parse_enum<StudyKind>(name)).keys) {
            const toml::node* n = s.node(key.c_str());
            if (n && std::find(own.keys.begin(), own.keys.end(), key) == own.keys.end())
                throw InputError(ctx.file, line_of(*n), "key 'study." + key + "' belongs to " + owners_of(key));
        }
}

/// The calibration(s) studied: study.calibration, or study.calibrations for kinds comparing several.
void read_calibrations(StudyKeys& keys, const StudyKindSpec& spec) {
    Section& s = keys.section;
    StudyConfig& c = keys.config;
    s.path("calibration", c.calibration);
    const auto summaries =
        study_keys::read_list<std::string>(s, "calibrations", "an array of summary.json paths", study_keys::text_item);
    for (const auto& p : summaries) c.calibrations.push_back((keys.context.dir / p).lexically_normal());
    if (spec.one_calibration) {
        if (c.calibration.empty())
            throw InputError(keys.context.file, 0, "key 'study.calibration' is required: the summary.json of a `gradem calibrate` run");
        study_keys::require_file(keys, "study.calibration", c.calibration, "run the calibration first (gradem calibrate <config>)");
    } else {
        if (c.calibrations.empty()) study_keys::refuse(keys, "calibrations", "key 'study.calibrations' is required: one summary.json per model");
        for (const auto& p : c.calibrations) study_keys::require_file(keys, "study.calibrations", p, "run that calibration first");
    }
}

void read_study(Context& ctx, const toml::table& root, StudyConfig& c) {
    Section s(ctx, root, "study");
    std::string kind;
    s.text("kind", kind);
    if (kind.empty()) throw InputError(ctx.file, 0, "key 'study.kind' is required");
    c.kind = parse_kind(kind, ctx);
    const StudyKindSpec& spec = study_kind(c.kind);
    refuse_other_kinds_keys(ctx, s, spec);
    if (auto seeds = study_keys::read_list<std::uint64_t>(s, "seeds", "a non-empty array of positive integers",
                                                          study_keys::positive_integer);
        !seeds.empty())
        c.seeds = seeds;
    StudyKeys keys{s, ctx, c};
    spec.read_keys(keys);
    read_calibrations(keys, spec);
    s.finish();
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

int StudyKeys::line(const char* key) const { return context.keys[std::string("study.") + key].line; }

namespace study_keys {

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

void require_file(StudyKeys& keys, const std::string& key, const fs::path& path, const std::string& what) {
    if (!fs::exists(path))
        throw InputError(keys.context.file, keys.context.keys[key].line, "key '" + key + "': " + path.string() + " not found; " + what);
}

void refuse(const StudyKeys& keys, const char* key, const std::string& what) {
    throw InputError(keys.context.file, keys.line(key), what);
}

}  // namespace study_keys

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
