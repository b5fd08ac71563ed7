// gradem._gradem.Config: a cube config as its TOML document plus what the reader made of it.
//
// An override is a key written into the document ("material.tensile_strength_mpa" = 12), after
// which the whole document is read again by the reader that reads the file
// (experiments/config/cube_config_source.hpp): the same names, units, defaults, ranges, model
// checks and messages, and the config a run gets is exactly the one `gradem compress` gets from
// the saved file. The [material] keys are the rows of the material table
// (experiments/config/material_table.hpp, each bond law's rows included): their values are read
// back through the table, in config units; the other keys as the reader recorded them.
#include <pybind11/stl.h>

#include <filesystem>
#include <map>
#include <sstream>
#include <string>
#include <toml++/toml.h>
#include <utility>
#include <variant>
#include <vector>

#include "common/atomic_file.hpp"
#include "common/input_error.hpp"
#include "common/toml_section.hpp"
#include "experiments/config/cube_config_source.hpp"
#include "experiments/config/material_table.hpp"
#include "python/bindings/common.hpp"
#include "python/bindings/config.hpp"

namespace gradem::py_api {

namespace {

namespace fs = std::filesystem;
using common::toml_io::KeyInfo;

constexpr std::string_view kDefaultSuffix = " (default)";

/// "table.key" -> (table, key); anything else is a ValueError.
std::pair<std::string, std::string> split_key(const std::string& key) {
    const auto dot = key.find('.');
    if (dot == std::string::npos || dot == 0 || dot + 1 == key.size() || key.find('.', dot + 1) != std::string::npos)
        throw py::value_error("override '" + key + "': expected 'table.key', e.g. 'material.tensile_strength_mpa'");
    return {key.substr(0, dot), key.substr(dot + 1)};
}

py::object node_to_python(const toml::node& n) {
    if (n.is_boolean()) return py::bool_(n.as_boolean()->get());
    if (n.is_integer()) return py::int_(n.as_integer()->get());
    if (n.is_floating_point()) return py::float_(n.as_floating_point()->get());
    if (n.is_string()) return py::str(n.as_string()->get());
    if (n.is_array()) {
        py::list out;
        for (const toml::node& e : *n.as_array()) out.append(node_to_python(e));
        return out;
    }
    std::ostringstream os;
    n.visit([&](const auto& v) { os << v; });
    return py::str(os.str());
}

/// A Python value as the TOML value it stands for: bool, int, float, str (and paths), lists of
/// these. Anything else is refused with the key.
using TomlValue = std::variant<bool, std::int64_t, double, std::string, toml::array>;

TomlValue python_to_toml(const py::handle& v, const std::string& key) {
    if (py::isinstance<py::bool_>(v)) return v.cast<bool>();
    if (py::isinstance<py::int_>(v)) {
        try {
            return v.cast<std::int64_t>();
        } catch (const py::cast_error&) {
            throw py::value_error("key '" + key + "' = " + py::repr(v).cast<std::string>() + ": an integer out of the 64-bit range");
        }
    }
    if (py::isinstance<py::float_>(v)) return v.cast<double>();
    if (py::isinstance<py::str>(v)) return v.cast<std::string>();
    if (py::hasattr(v, "__fspath__")) return py::module_::import("os").attr("fspath")(v).cast<std::string>();
    if (py::isinstance<py::list>(v) || py::isinstance<py::tuple>(v)) {
        toml::array a;
        for (const py::handle& e : v) std::visit([&](auto&& x) { a.push_back(std::move(x)); }, python_to_toml(e, key));
        return a;
    }
    if (py::hasattr(v, "item") && !py::isinstance<py::dict>(v)) return python_to_toml(v.attr("item")(), key);  // numpy scalars
    throw py::value_error("key '" + key + "' = " + py::repr(v).cast<std::string>() +
                          ": expected a TOML value (a number, true or false, a string or a list)");
}

/// The reader's text of a value ("3.5", "3.5 (default)", "\"auto\"") as a Python value.
py::object text_to_python(std::string text, bool path) {
    if (text.size() >= kDefaultSuffix.size() && text.compare(text.size() - kDefaultSuffix.size(), kDefaultSuffix.size(), kDefaultSuffix) == 0)
        text.resize(text.size() - kDefaultSuffix.size());
    if (path) {
        if (text.size() >= 2 && text.front() == '"' && text.back() == '"') text = text.substr(1, text.size() - 2);
        return py::str(text);
    }
    try {
        const toml::table t = toml::parse("v = " + text);
        if (const toml::node* n = t.get("v")) return node_to_python(*n);
    } catch (const toml::parse_error&) {
    }
    return py::str(text);
}

void add_range(std::string& message, const std::string& key) {
    // The reader names the rule when a value is out of range; for a value of the wrong type the
    // material table adds the allowed values.
    if (message.find(": expected ") == std::string::npos || !key.starts_with("material.")) return;
    const exp::MaterialParameter* p = exp::find_material_parameter(key.substr(9));
    if (!p || message.find("'" + key + "'") == std::string::npos) return;
    message += " (allowed: " + std::string(p->flag ? "true or false" : p->range.rule()) +
               (p->unit == "-" || p->flag ? std::string() : " " + std::string(p->unit)) + (p->integer && !p->flag ? ", an integer" : "") + ")";
}

}  // namespace

Config Config::load(const std::string& path) {
    Config c;
    c.file_ = path;
    common::toml_io::Context ctx;
    c.root_ = common::toml_io::parse_toml_file(path, ctx);
    c.read(c.root_);
    return c;
}

void Config::read(const toml::table& root) {
    std::map<std::string, KeyInfo> keys, tension_keys;
    exp::CubeConfig cube = exp::load_cube_config(root, file_, &keys);
    exp::TensionConfig tension = exp::load_tension_config(cube, root, &tension_keys);
    keys.insert(tension_keys.begin(), tension_keys.end());
    cube_ = std::move(cube);
    tension_ = std::move(tension);
    keys_ = std::move(keys);
}

void Config::set(const py::dict& overrides) {
    toml::table root = root_;
    std::vector<std::pair<std::string, std::string>> applied;
    for (const auto& [k, v] : overrides) {
        const std::string key = py::str(k).cast<std::string>();
        const auto [table, name] = split_key(key);
        if (!root.contains(table)) root.insert(table, toml::table{});
        toml::table* t = root[table].as_table();
        if (!t) throw common::InputError(file_.string(), 0, "'" + table + "' must be a table ([" + table + "])");
        if (v.is_none()) {
            t->erase(name);
            applied.emplace_back(key, "(default)");
            continue;
        }
        std::visit([&](auto&& x) { t->insert_or_assign(name, std::move(x)); }, python_to_toml(v, key));
        applied.emplace_back(key, common::toml_io::show(*t->get(name)));
    }
    try {
        read(root);
    } catch (const common::InputError& e) {
        std::string message = std::string(e.what()).substr(common::InputError::format(e.file(), e.line(), "").size());
        for (const auto& [key, shown] : applied) add_range(message, key);
        throw common::InputError(e.file(), e.line(), message);
    }
    root_ = std::move(root);
    for (auto& a : applied) {
        std::erase_if(overrides_, [&](const auto& o) { return o.first == a.first; });
        overrides_.push_back(std::move(a));
    }
}

py::object Config::get(const std::string& key) const {
    const auto [table, name] = split_key(key);
    const auto info = keys_.find(key);
    if (info == keys_.end()) {
        std::string known;
        for (const auto& [k, i] : keys_)
            if (k.starts_with(table + ".")) known += (known.empty() ? "" : ", ") + k.substr(table.size() + 1);
        if (table == "material")
            if (const exp::MaterialParameter* p = exp::find_material_parameter(name); p && p->in_config)
                throw py::attribute_error("key '" + key + "' belongs to bond model " + exp::model_names(p->models) +
                                          ", but material.model = \"" + bond_model_name(cube_.material.bond.model) + "\"");
        throw py::attribute_error("unknown key '" + key + "'" + (known.empty() ? " (no table [" + table + "])" : " (known: " + known + ")"));
    }
    if (table == "material") {
        if (name == "model") return py::str(bond_model_name(cube_.material.bond.model));
        if (const exp::MaterialParameter* p = exp::find_material_parameter(name)) {
            if (p->flag) return py::bool_(p->get_int(cube_.material) != 0);
            if (p->integer) return py::int_(p->get_int(cube_.material));
            return py::float_(exp::config_value(*p, cube_.material));
        }
    }
    if (const toml::node* n = root_.at_path(key).node(); n && !info->second.path) return node_to_python(*n);
    return text_to_python(info->second.text, info->second.path);
}

py::dict Config::keys() const {
    py::dict out;
    for (const auto& [key, info] : keys_) {
        py::dict row;
        row["value"] = get(key);
        row["line"] = info.line;
        row["default"] = info.line == 0 && root_.at_path(key).node() == nullptr;
        row["path"] = info.path;
        out[py::str(key)] = row;
    }
    return out;
}

std::string Config::document() const {
    std::ostringstream os;
    os << root_;
    return os.str();
}

std::string Config::saved_text() const {
    toml::table out = root_;
    // Paths as the reader resolved them, so the copy runs the same data from anywhere; the
    // packing cache too, so the copy shares it.
    for (const auto& [key, info] : keys_) {
        if (!info.path) continue;
        toml::node* n = out.at_path(key).node();
        if (!n || !n->is_string() || n->as_string()->get().empty()) continue;
        const fs::path p = (fs::absolute(file_).parent_path() / fs::path(n->as_string()->get())).lexically_normal();
        *n->as_string() = p.string();
    }
    if (!out.contains("output")) out.insert("output", toml::table{});
    if (toml::table* o = out["output"].as_table(); o && !o->contains("cache_dir"))
        o->insert("cache_dir", fs::absolute(cube_.cache_dir).lexically_normal().string());
    std::ostringstream text;
    text << "# The cube config " << fs::absolute(file_).lexically_normal().string() << (overrides_.empty() ? "" : " with")
         << (overrides_.empty() ? "" : " ") << (overrides_.empty() ? "" : std::to_string(overrides_.size()) + " override(s)")
         << ", saved by gradem's Python module\n# (comments dropped; paths made absolute).\n";
    for (const auto& [key, shown] : overrides_) text << "#   " << key << " = " << shown << "\n";
    text << "\n" << out << "\n";
    return text.str();
}

void Config::save(const std::string& path) const { common::write_file_atomically(path, saved_text()); }

py::list material_rows() {
    py::list rows;
    for (const exp::MaterialParameter& p : exp::material_table()) {
        if (!p.in_config) continue;
        py::dict r;
        r["key"] = std::string(p.key);
        r["unit"] = std::string(p.unit);
        r["description"] = std::string(p.description);
        r["type"] = p.flag ? "bool" : p.integer ? "int" : "float";
        r["range"] = p.flag ? std::string("true or false") : p.range.rule();
        py::list models;
        for (BondModel m : exp::bond_models())
            if (p.applies_to(m)) models.append(std::string(bond_model_name(m)));
        r["models"] = models;
        r["follows"] = std::string(p.follows);
        r["calibration"] = p.calibration == exp::Calibration::free ? "free" : p.calibration == exp::Calibration::fixed_only ? "fixed_only" : "none";
        rows.append(r);
    }
    return rows;
}

void register_config(py::module_& m) {
    py::class_<Config>(m, "Config", "A cube config: its TOML document and what the config reader made of it")
        .def_static("load", &Config::load, py::arg("path"), "Reads and checks a cube config TOML file")
        .def_property_readonly("file", [](const Config& c) { return c.file().string(); })
        .def("get", &Config::get, py::arg("key"), "The value of 'table.key' in config units (its default when not given)")
        .def("set", &Config::set, py::arg("overrides"),
             "Sets keys {'table.key': value} (None: back to the default), read again by the config reader; "
             "nothing changes when any is refused")
        .def("keys", &Config::keys, "Every key the reader knows: {'table.key': {value, line, default, path}}")
        .def_property_readonly("overrides", [](const Config& c) {
            py::dict d;
            for (const auto& [k, v] : c.overrides()) d[py::str(k)] = v;
            return d;
        })
        .def("document", &Config::document, "The TOML document as it stands (overrides applied)")
        .def("saved_text", &Config::saved_text, "The text save() writes")
        .def("save", &Config::save, py::arg("path"), "Writes the config (paths absolute) atomically")
        .def("copy", [](const Config& c) { return Config(c); })
        .def_property_readonly("bond_model", [](const Config& c) { return std::string(bond_model_name(c.cube().material.bond.model)); })
        .def_property_readonly("material_keys", [](const Config& c) {
            py::list keys;
            keys.append("model");
            for (const exp::MaterialParameter& p : exp::material_table())
                if (p.in_config && p.applies_to(c.cube().material.bond.model)) keys.append(std::string(p.key));
            return keys;
        });
    m.def("material_table", &material_rows, "The rows of the material table: every [material] key with its unit, range and models");
}

}  // namespace gradem::py_api
