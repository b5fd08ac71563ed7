#include "lab_data/dataset.hpp"

#include <fnmatch.h>

#include <algorithm>
#include <cmath>
#include <set>
#include <toml++/toml.h>

#include "common/input_error.hpp"
#include "lab_data/text.hpp"

namespace gradem::lab {
namespace {

namespace fs = std::filesystem;

int line_of(const toml::node& n) { return static_cast<int>(n.source().begin.line); }

void check_keys(const toml::table& t, const std::set<std::string>& allowed, const std::string& where, const std::string& file) {
    for (auto&& [key, node] : t) {
        if (allowed.count(std::string(key.str()))) continue;
        std::string list;
        for (const auto& a : allowed) list += (list.empty() ? "" : ", ") + a;
        throw InputError(file, line_of(node), "unknown key '" + std::string(key.str()) + "' in " + where + " (expected one of: " + list + ")");
    }
}

const toml::table* sub_table(const toml::table& t, const char* key, const std::string& file) {
    const toml::node* n = t.get(key);
    if (!n) return nullptr;
    if (!n->is_table()) throw InputError(file, line_of(*n), std::string("'") + key + "' must be a table");
    return n->as_table();
}

std::string get_string(const toml::table& t, const char* key, const std::string& file, std::string fallback = {}) {
    const toml::node* n = t.get(key);
    if (!n) return fallback;
    if (!n->is_string()) throw InputError(file, line_of(*n), std::string("key '") + key + "': expected a string");
    return std::string(n->as_string()->get());
}

double get_number(const toml::table& t, const char* key, const std::string& file, double fallback, bool positive = true) {
    const toml::node* n = t.get(key);
    if (!n) return fallback;
    const auto v = n->value<double>();
    if (!v || (!n->is_floating_point() && !n->is_integer()))
        throw InputError(file, line_of(*n), std::string("key '") + key + "': expected a number");
    if (!std::isfinite(*v))
        throw InputError(file, line_of(*n), std::string("key '") + key + "' = " + (std::isnan(*v) ? "nan" : *v > 0 ? "inf" : "-inf") +
                                                ": expected a finite number");
    if (positive && !(*v > 0)) throw InputError(file, line_of(*n), std::string("key '") + key + "' must be > 0");
    return *v;
}

bool get_bool(const toml::table& t, const char* key, const std::string& file, bool fallback) {
    const toml::node* n = t.get(key);
    if (!n) return fallback;
    if (!n->is_boolean()) throw InputError(file, line_of(*n), std::string("key '") + key + "': expected true or false");
    return n->as_boolean()->get();
}

// `what` names the key for the message (e.g. "key 'files' of [[sand.tension]] 'T1': "), or is empty.
std::vector<fs::path> glob(const fs::path& folder, const std::string& pattern, const std::string& file, int line,
                           const std::string& what = {}) {
    const fs::path full = folder / pattern;
    const fs::path dir = full.parent_path();
    const std::string name = full.filename().string();
    std::vector<fs::path> hits;
    std::error_code ec;
    if (fs::is_directory(dir, ec))
        for (const auto& entry : fs::directory_iterator(dir, ec))
            if (entry.is_regular_file() && fnmatch(name.c_str(), entry.path().filename().c_str(), 0) == 0) hits.push_back(entry.path());
    if (hits.empty()) throw InputError(file, line, what + "pattern '" + pattern + "' matches no file (in " + dir.string() + ")");
    std::sort(hits.begin(), hits.end());
    return hits;
}

void read_dataset_section(const toml::table& root, DatasetConfig& c, const std::string& file) {
    if (const auto* d = sub_table(root, "dataset", file)) {
        check_keys(*d, {"name", "description", "representative", "note", "export_format"}, "[dataset]", file);
        c.name = get_string(*d, "name", file, c.name);
        c.description = get_string(*d, "description", file);
        c.representative = get_bool(*d, "representative", file, false);
        c.note = get_string(*d, "note", file);
        const std::string format = get_string(*d, "export_format", file, "auto");
        const auto f = parse_format_name(format);
        if (!f) throw InputError(file, line_of(*d->get("export_format")), "export_format '" + format +
                                                                        "': expected " + enum_names_text<ExportFormat>(NameList::comma_or));
        c.read.format = *f;
    }
    if (const auto* s = sub_table(root, "specimen", file)) {
        check_keys(*s, {"width_mm", "depth_mm", "height_mm", "gauge_length_mm", "use_file_geometry"}, "[specimen]", file);
        auto& g = c.read.nominal;
        g.width_m = get_number(*s, "width_mm", file, g.width_m * 1e3) * 1e-3;
        g.depth_m = get_number(*s, "depth_mm", file, g.depth_m * 1e3) * 1e-3;
        g.height_m = get_number(*s, "height_mm", file, g.height_m * 1e3) * 1e-3;
        g.gauge_length_m = get_number(*s, "gauge_length_mm", file, 0.0, false) * 1e-3;
        g.source = "config";
        for (const char* name : {"width", "depth", "height"})
            if (s->get(std::string(name) + "_mm")) c.read.nominal_origin[name] = file + " [specimen]";
        c.read.use_file_geometry = get_bool(*s, "use_file_geometry", file, true);
    }
}

void read_options_sections(const toml::table& root, DatasetConfig& c, const std::string& file) {
    if (const auto* r = sub_table(root, "reduction", file)) {
        check_keys(*r, {"chord_upper_fraction", "chord_lower_strain", "tangent_fraction", "fit_popovics", "c109_group_size"}, "[reduction]", file);
        c.reduction.chord_upper_fraction = get_number(*r, "chord_upper_fraction", file, c.reduction.chord_upper_fraction);
        c.reduction.chord_lower_strain = get_number(*r, "chord_lower_strain", file, c.reduction.chord_lower_strain, false);
        c.reduction.tangent_fraction = get_number(*r, "tangent_fraction", file, c.reduction.tangent_fraction);
        c.reduction.fit_popovics = get_bool(*r, "fit_popovics", file, true);
        const double g = get_number(*r, "c109_group_size", file, 3);
        if (g != 2 && g != 3) throw InputError(file, line_of(*r->get("c109_group_size")), "c109_group_size must be 2 or 3");
        c.c109_group_size = static_cast<std::size_t>(g);
        if (auto why = c.reduction.invalid_reason()) throw InputError(file, line_of(*r), *why);
    }
    if (const auto* g = sub_table(root, "gradation", file)) {
        check_keys(*g, {"c144_limits"}, "[gradation]", file);
        const std::string limits = get_string(*g, "c144_limits", file);
        if (!limits.empty()) c.c144_limits = c.folder / limits;
    }
    if (const auto* cols = sub_table(root, "columns", file)) {
        for (auto&& [key, node] : *cols) {
            std::string k(key.str());
            const bool is_unit = k.size() > 5 && k.substr(k.size() - 5) == "_unit";
            const auto role = parse_role(is_unit ? k.substr(0, k.size() - 5) : k);
            if (!role) throw InputError(file, line_of(node), "unknown key '" + k + "' in [columns] (expected time, load, crosshead, strain, "
                                                                                   "lateral_strain, stress, or one of them + '_unit')");
            if (!node.is_string()) throw InputError(file, line_of(node), "key '" + k + "': expected a string");
            (is_unit ? c.read.channels.unit : c.read.channels.column)[*role] = std::string(node.as_string()->get());
        }
    }
}

// The files of `files = "glob"` or `files = ["glob", ...]`, resolved against the dataset folder.
std::vector<fs::path> files_of(const toml::node& files, const DatasetConfig& c, const std::string& file, const std::string& what) {
    std::vector<const toml::node*> patterns;
    if (const auto* arr = files.as_array()) for (const auto& p : *arr) patterns.push_back(&p);
    else patterns.push_back(&files);
    std::vector<fs::path> all;
    for (const toml::node* p : patterns) {
        if (!p->is_string()) throw InputError(file, line_of(*p), "files: expected a string or an array of strings");
        const auto hits = glob(c.folder, std::string(p->as_string()->get()), file, line_of(*p), what);
        all.insert(all.end(), hits.begin(), hits.end());
    }
    return all;
}

// The tables of an array of tables `key` ([[sand.tension]]); none when the key is absent.
std::vector<const toml::table*> tables_of(const toml::table& t, const char* key, const std::string& where, const std::string& file) {
    std::vector<const toml::table*> out;
    const toml::node* n = t.get(key);
    if (!n) return out;
    const toml::array* arr = n->as_array();
    if (!arr) throw InputError(file, line_of(*n), "'" + std::string(key) + "' must be an array of tables (" + where + ")");
    for (const auto& node : *arr) {
        if (!node.is_table()) throw InputError(file, line_of(node), where + " must be a table");
        out.push_back(node.as_table());
    }
    return out;
}

// [[sand.tension]]: name, test, files, and the nominal dimensions of that test (mm → m).
TensionBatchSpec read_tension(const toml::table& t, const DatasetConfig& c, const std::string& file, std::size_t index) {
    check_keys(t, {"name", "test", "files", "diameter_mm", "length_mm", "width_mm", "depth_mm", "span_mm"}, "[[sand.tension]]", file);
    TensionBatchSpec batch;
    batch.name = get_string(t, "name", file, "tension " + std::to_string(index + 1));
    TensileSpec& spec = batch.spec;
    spec.label = "[[sand.tension]] '" + batch.name + "'";
    spec.config_file = file;
    spec.config_line = line_of(t);
    spec.nominal_source = "dataset";
    spec.use_file_geometry = c.read.use_file_geometry;
    const toml::node* test = t.get("test");
    if (!test) throw InputError(file, spec.config_line, spec.label + " needs test = \"splitting\" or \"flexural\"");
    const std::string name = get_string(t, "test", file);
    const auto kind = parse_tensile_test(name);
    if (!kind) throw InputError(file, line_of(*test), "key 'test': '" + name + "' is not a tensile test (expected " + enum_names_text<TensileTestKind>(NameList::comma_or) + ")");
    spec.test = *kind;
    // A dimension of the other kind of test is a mistake, not something to ignore.
    const std::vector<std::string> splitting_keys{"diameter_mm", "length_mm"}, flexural_keys{"width_mm", "depth_mm", "span_mm"};
    const bool splitting = spec.test == TensileTestKind::splitting;
    const auto& own = splitting ? splitting_keys : flexural_keys;
    std::string own_list;
    for (const auto& k : own) own_list += (own_list.empty() ? "" : ", ") + k;
    for (const auto& key : splitting ? flexural_keys : splitting_keys)
        if (const toml::node* n = t.get(key))
            throw InputError(file, line_of(*n), "key '" + key + "' does not apply to a " + to_string(spec.test) + " test (its keys: " +
                                                    own_list + ")");
    TensileGeometry& g = spec.nominal;  // 0: not given (the export's, or for prisms ASTM C348's, is used)
    g.diameter_m = get_number(t, "diameter_mm", file, 0.0) * 1e-3;
    g.length_m = get_number(t, "length_mm", file, 0.0) * 1e-3;
    g.width_m = get_number(t, "width_mm", file, 0.0) * 1e-3;
    g.depth_m = get_number(t, "depth_mm", file, 0.0) * 1e-3;
    g.span_m = get_number(t, "span_mm", file, 0.0) * 1e-3;
    const toml::node* files = t.get("files");
    if (!files) throw InputError(file, spec.config_line, spec.label + " needs files = \"glob\"");
    batch.files = files_of(*files, c, file, "key 'files' of " + spec.label + ": ");
    return batch;
}

SandSpec read_sand(const toml::table& s, const DatasetConfig& c, const std::string& file, int line) {
    check_keys(s, {"name", "sieve", "specific_gravity", "batch", "tension"}, "[[sand]]", file);
    SandSpec sand;
    sand.name = get_string(s, "name", file);
    if (sand.name.empty()) throw InputError(file, line, "[[sand]] needs a name");
    const std::string sieve = get_string(s, "sieve", file);
    if (!sieve.empty()) sand.sieve = c.folder / sieve;
    sand.specific_gravity = get_number(s, "specific_gravity", file, 0.0, false);
    for (const toml::table* b : tables_of(s, "batch", "[[sand.batch]]", file)) {
        check_keys(*b, {"name", "files"}, "[[sand.batch]]", file);
        BatchSpec batch{get_string(*b, "name", file, "batch " + std::to_string(sand.batches.size() + 1)), {}};
        const toml::node* files = b->get("files");
        if (!files) throw InputError(file, line_of(*b), "batch '" + batch.name + "' needs files = \"glob\"");
        batch.files = files_of(*files, c, file, {});
        sand.batches.push_back(std::move(batch));
    }
    for (const toml::table* t : tables_of(s, "tension", "[[sand.tension]]", file))
        sand.tension.push_back(read_tension(*t, c, file, sand.tension.size()));
    return sand;
}

}  // namespace

fs::path dataset_toml(const fs::path& path) {
    std::error_code ec;
    return fs::is_directory(path, ec) ? path / "dataset.toml" : path;
}

DatasetConfig load_dataset_config(const fs::path& path, bool require_sands) {
    DatasetConfig c;
    c.file = dataset_toml(path);
    c.folder = c.file.parent_path();
    const std::string file = c.file.string();
    const std::string text = decode_text(read_file_bytes(c.file)).utf8;
    toml::table root;
    try {
        root = toml::parse(text, file);
    } catch (const toml::parse_error& e) {
        throw InputError(file, static_cast<int>(e.source().begin.line), std::string(e.description()));
    }
    check_keys(root, {"dataset", "specimen", "reduction", "gradation", "columns", "sand"}, "the top level", file);
    read_dataset_section(root, c, file);
    read_options_sections(root, c, file);
    if (const toml::node* sands = root.get("sand")) {
        const toml::array* arr = sands->as_array();
        if (!arr) throw InputError(file, line_of(*sands), "'sand' must be an array of tables ([[sand]])");
        for (const auto& node : *arr) {
            if (!node.is_table()) throw InputError(file, line_of(node), "[[sand]] must be a table");
            c.sands.push_back(read_sand(*node.as_table(), c, file, line_of(node)));
        }
    }
    if (require_sands) {
        if (c.sands.empty()) throw InputError(file, 0, "no [[sand]] defined");
        for (const auto& s : c.sands)
            if (s.batches.empty() && s.tension.empty())
                throw InputError(file, 0, "sand '" + s.name + "' has no [[sand.batch]] with cube files and no [[sand.tension]]");
    }
    return c;
}

}  // namespace gradem::lab
