#pragma once
// Typed, validating reads of one TOML table, shared by the config readers (cube configs,
// calibration problems). A Section remembers every key asked for, records where each value
// came from (line, text as written, or "(default)") for error messages, and finish() rejects
// keys nobody asked for. Errors are common::InputError "file:line: key 'table.key' = v ...".
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <limits>
#include <map>
#include <set>
#include <sstream>
#include <string>
#include <vector>
#include <toml++/toml.h>

#include "common/input_error.hpp"
#include "common/named_enum.hpp"

namespace gradem::common::toml_io {

namespace fs = std::filesystem;
using common::InputError;

inline int line_of(const toml::node& n) { return static_cast<int>(n.source().begin.line); }

inline std::string show(double v) {
    std::ostringstream os;
    os.precision(15);
    os << v;
    if (os.str().find_first_of(".eEni") == std::string::npos) os << ".0";  // keep it a float
    return os.str();
}

/// The value as the user wrote it (near enough): "text", 1.5, 3, true, or TOML for others.
inline std::string show(const toml::node& n) {
    if (n.is_floating_point()) return show(n.as_floating_point()->get());
    std::ostringstream os;
    if (n.is_string()) os << '"' << n.as_string()->get() << '"';
    else if (n.is_integer()) os << n.as_integer()->get();
    else if (n.is_boolean()) os << (n.as_boolean()->get() ? "true" : "false");
    else n.visit([&](const auto& v) { os << v; });
    return os.str();
}

/// Where a key was given (line 0: not given, the default applies) and its value as written.
struct KeyInfo {
    int line = 0;
    std::string text;
    bool converted = false;  ///< the struct holds the value in other units (SI, std from cv)
    bool path = false;       ///< a path, relative to the config file's folder unless absolute
};

struct Context {
    std::string file;                      ///< display name of the config file
    fs::path dir;                          ///< relative paths start here
    std::map<std::string, KeyInfo> keys;   ///< "table.key" -> KeyInfo
};

/// One [table]: typed getters that remember every key asked for, then finish() rejects the
/// keys nobody asked for.
class Section {
public:
    Section(Context& ctx, const toml::table& root, std::string name) : ctx_(ctx), name_(std::move(name)) {
        if (const toml::node* n = root.get(name_)) {
            if (!n->is_table()) throw InputError(ctx_.file, line_of(*n), "'" + name_ + "' must be a table ([" + name_ + "])");
            table_ = n->as_table();
        }
    }

    void real(const char* key, double& v, double to_si = 1.0) {
        const toml::node* n = find(key);
        if (!n) return record_default(key, show(v / to_si), to_si != 1.0);
        if (!n->is_integer() && !n->is_floating_point()) type_error(key, *n, "a number");
        if (!std::isfinite(n->value<double>().value())) type_error(key, *n, "a finite number");
        v = n->value<double>().value() * to_si;
        record(key, *n, to_si != 1.0);
    }

    template <typename Int>
    void integer(const char* key, Int& v, std::int64_t lo = std::numeric_limits<std::int64_t>::min()) {
        const toml::node* n = find(key);
        if (!n) return record_default(key, std::to_string(v), false);
        if (!n->is_integer()) type_error(key, *n, "an integer");
        const std::int64_t x = n->as_integer()->get();
        constexpr auto hi = static_cast<std::int64_t>(std::min<std::uint64_t>(std::numeric_limits<Int>::max(),
                                                                                std::numeric_limits<std::int64_t>::max()));
        lo = std::max<std::int64_t>(lo, std::is_signed_v<Int> ? std::numeric_limits<Int>::min() : 0);
        if (x < lo || x > hi)
            throw InputError(ctx_.file, line_of(*n), "key '" + full(key) + "' = " + std::to_string(x) + " violates in [" +
                                                         std::to_string(lo) + ", " + std::to_string(hi) + "]");
        v = static_cast<Int>(x);
        record(key, *n, false);
    }

    void boolean(const char* key, bool& v) {
        const toml::node* n = find(key);
        if (!n) return record_default(key, v ? "true" : "false", false);
        if (!n->is_boolean()) type_error(key, *n, "true or false");
        v = n->as_boolean()->get();
        record(key, *n, false);
    }

    void text(const char* key, std::string& v) {
        const toml::node* n = find(key);
        if (!n) return record_default(key, v, false);
        if (!n->is_string()) type_error(key, *n, "a string");
        v = n->as_string()->get();
        record(key, *n, false);
    }

    /// One name of a named enum (common/named_enum.hpp); the error lists the names it accepts.
    template <NamedEnum E>
    void choice(const char* key, E& v) {
        const toml::node* n = find(key);
        if (!n) return record_default(key, to_string(v), false);
        const auto parsed = n->is_string() ? parse_enum<E>(n->as_string()->get()) : std::nullopt;
        if (!parsed) type_error(key, *n, enum_names_text<E>(NameList::quoted_or));
        v = *parsed;
        record(key, *n, false);
    }

    /// A path, relative to the config file's folder unless absolute.
    void path(const char* key, fs::path& v) {
        std::string s;
        text(key, s);
        ctx_.keys[full(key)].path = true;
        if (!s.empty()) v = (ctx_.dir / fs::path(s)).lexically_normal();
    }

    /// The raw node (nullptr when absent), for keys with several accepted types.
    const toml::node* node(const char* key) { return find(key); }
    void record(const char* key, const toml::node& n, bool converted) {
        ctx_.keys[full(key)] = {line_of(n), show(n), converted};
    }
    void record_default(const char* key, const std::string& text, bool converted) {
        ctx_.keys[full(key)] = {0, text + " (default)", converted};
    }
    [[noreturn]] void type_error(const char* key, const toml::node& n, const std::string& expected) const {
        throw InputError(ctx_.file, line_of(n), "key '" + full(key) + "' = " + show(n) + ": expected " + expected);
    }
    [[nodiscard]] std::string full(const char* key) const { return name_ + "." + key; }

    void finish() const {
        if (!table_) return;
        for (auto&& [key, n] : *table_) {
            if (asked_.count(std::string(key.str()))) continue;
            std::string known;
            for (const auto& k : asked_) known += (known.empty() ? "" : ", ") + k;
            throw InputError(ctx_.file, line_of(n), "unknown key '" + full(std::string(key.str()).c_str()) + "' (known: " + known + ")");
        }
    }

private:
    const toml::node* find(const char* key) {
        asked_.insert(key);
        return table_ ? table_->get(key) : nullptr;
    }

    Context& ctx_;
    std::string name_;
    const toml::table* table_ = nullptr;
    std::set<std::string> asked_;
};

/// Parses a TOML file (decoded like every lab text file); parse errors become InputError with
/// the file and line.
toml::table parse_toml_file(const fs::path& file, Context& ctx);

/// Throws InputError naming unknown top-level tables or keys (the known ones are listed).
void check_tables(const Context& ctx, const toml::table& root, const std::vector<std::string>& known_tables);

}  // namespace gradem::common::toml_io

// The config readers of experiments/ name it toml_io (it lived in experiments/ before): the
// same namespace, not a copy.
namespace gradem::exp {
namespace toml_io = common::toml_io;
}  // namespace gradem::exp
