#include "lab_data/channel_roles.hpp"

#include <optional>

#include "common/input_error.hpp"
#include "lab_data/units.hpp"

namespace gradem::lab {
namespace {

struct RoleRule {
    ChannelRole role;
    std::vector<std::string> exact;    // whole normalised name
    std::vector<std::string> words;    // token (<= 3 chars: equal; longer: contained)
    std::vector<std::string> exclude;  // substrings that disqualify
    std::vector<Dimension> quantities;  // acceptable unit quantities
};

const std::vector<RoleRule>& rules() {
    static const std::vector<std::string> kCommand = {"command", "cmd", "sollwert", "setpoint", "set point", "target", "rate", "limit"};
    auto with_command = [&](std::vector<std::string> v) { v.insert(v.end(), kCommand.begin(), kCommand.end()); return v; };
    static const std::vector<RoleRule> kRules = {
        {ChannelRole::load, {"load", "force", "axial force", "axial load", "kraft", "compressive load", "compressive force"},
         {"force", "load", "kraft"}, with_command({"max", "peak", "stress"}), {Dimension::force}},
        {ChannelRole::stress, {"stress", "axial stress", "compressive stress", "spannung"},
         {"stress", "spannung"}, with_command({"max", "peak"}), {Dimension::stress}},
        {ChannelRole::time, {"time", "running time", "elapsed time", "test time", "total time", "laufzeit", "zeit", "t"},
         {"time", "zeit"}, with_command({"tages", "of day", "date", "datum", "cycle", "segment"}), {Dimension::time}},
        {ChannelRole::lateral_strain, {"lateral strain", "transverse strain", "querdehnung"},
         {"lateral", "transverse", "querdehnung", "radial"}, with_command({}), {Dimension::strain, Dimension::length}},
        {ChannelRole::strain, {"strain", "axial strain", "strain 1", "axial ext", "ext", "extensometer", "dehnung", "e"},
         {"strain", "dehnung", "extensometer", "ext", "epsilon"},
         with_command({"lateral", "transverse", "quer", "radial", "extension", "crosshead", "displacement", "stress"}),
         {Dimension::strain, Dimension::length}},
        {ChannelRole::crosshead, {"crosshead", "extension", "displacement", "axial displacement", "position", "axial position",
                                  "stroke", "weg", "actuator", "deflection"},
         {"crosshead", "displacement", "extension", "position", "stroke", "weg", "actuator", "deflection", "travel"},
         with_command({"extensometer", "strain", "lateral"}), {Dimension::length}},
    };
    return kRules;
}

bool contains_word(const std::string& name, const std::string& word) {
    std::size_t start = 0;
    while (start <= name.size()) {
        std::size_t end = name.find(' ', start);
        if (end == std::string::npos) end = name.size();
        const std::string token = name.substr(start, end - start);
        if (word.size() <= 3 ? token == word : token.find(word) != std::string::npos) return true;
        start = end + 1;
    }
    return false;
}

// A column can take a role when its unit is compatible or not (yet) known; a known unit of
// another quantity rules it out ("Load" in mm is not a load).
bool unit_compatible(const RawColumn& col, const RoleRule& rule, const ChannelOverrides& overrides) {
    const auto it = overrides.unit.find(rule.role);
    std::string spelling = it != overrides.unit.end() ? it->second : col.unit;
    if (!spelling.empty() && spelling.front() == '!') spelling.erase(0, 1);  // a forced override
    const auto unit = parse_unit(spelling);
    if (!unit) return true;
    for (Dimension q : rule.quantities)
        if (unit->dimension == q) return true;
    return false;
}

bool name_matches(const std::string& name, const RoleRule& rule, bool exact) {
    for (const auto& x : rule.exclude)
        if (name.find(x) != std::string::npos) return false;
    if (exact) {
        for (const auto& e : rule.exact)
            if (name == e) return true;
        return false;
    }
    for (const auto& w : rule.words)
        if (contains_word(name, w)) return true;
    return false;
}

std::string describe(const RawColumn& c) { return c.unit.empty() ? c.name : c.name + " [" + c.unit + "]"; }

std::optional<Dimension> unit_quantity(const RawColumn& c) {
    const auto u = parse_unit(c.unit);
    return u ? std::optional<Dimension>(u->dimension) : std::nullopt;
}

}  // namespace

std::string normalise_channel_name(std::string_view raw) {
    std::string s = to_lower(trim(raw));
    for (char& c : s)
        if (c == '_' || c == '-' || c == '.' || c == ':') c = ' ';
    std::string out;
    for (char c : s)
        if (!(c == ' ' && (out.empty() || out.back() == ' '))) out.push_back(c);
    out = trim(out);
    for (const char* prefix : {"channel ", "ch "}) {
        const std::string p = prefix;
        if (out.rfind(p, 0) == 0) {
            std::size_t k = p.size();
            while (k < out.size() && out[k] >= '0' && out[k] <= '9') ++k;
            if (k > p.size() && k < out.size() && out[k] == ' ') out = out.substr(k + 1);
        }
    }
    return out;
}

RoleAssignment assign_roles(const RawTable& t, const ChannelOverrides& overrides) {
    RoleAssignment a;
    std::vector<bool> claimed(t.columns.size(), false);
    const int header_line = t.columns.empty() ? 0 : t.columns.front().header_line;
    for (const auto& [role, wanted] : overrides.column) {  // 1. explicit choices
        bool found = false;
        for (std::size_t c = 0; c < t.columns.size() && !found; ++c) {
            const auto& col = t.columns[c];
            const std::string w = to_lower(trim(wanted));
            if (to_lower(col.name) == w || to_lower(col.header) == w || to_lower(describe(col)) == w) {
                a.column[role] = c;
                claimed[c] = found = true;
            }
        }
        if (!found) {
            std::string names;
            for (const auto& col : t.columns) names += (names.empty() ? "" : ", ") + describe(col);
            throw InputError(t.file, header_line, "column '" + wanted + "' (configured as the " + to_string(role) +
                                                      " column) is not in the file; columns are: " + names);
        }
    }
    for (bool exact : {true, false}) {  // 2. names: exact aliases first, then words
        for (const auto& rule : rules()) {
            if (a.column.count(rule.role)) continue;
            std::vector<std::size_t> hits;
            for (std::size_t c = 0; c < t.columns.size(); ++c)
                if (!claimed[c] && name_matches(normalise_channel_name(t.columns[c].name), rule, exact) &&
                    unit_compatible(t.columns[c], rule, overrides))
                    hits.push_back(c);
            if (hits.empty()) continue;
            a.column[rule.role] = hits.front();
            claimed[hits.front()] = true;
            if (hits.size() > 1)
                a.notes.push_back(std::string("several columns could be ") + to_string(rule.role) + "; using '" +
                                  t.columns[hits.front()].name + "' (set [columns] " + to_string(rule.role) + " to choose)");
        }
    }
    for (const auto& rule : rules()) {  // 3. units alone, when exactly one free column fits
        if (a.column.count(rule.role) || rule.role == ChannelRole::lateral_strain) continue;
        std::vector<std::size_t> hits;
        for (std::size_t c = 0; c < t.columns.size(); ++c)
            if (!claimed[c] && unit_quantity(t.columns[c]) == rule.quantities.front()) hits.push_back(c);
        if (hits.size() != 1) continue;
        a.column[rule.role] = hits.front();
        claimed[hits.front()] = true;
        a.notes.push_back(std::string("column '") + t.columns[hits.front()].name + "' taken as " + to_string(rule.role) +
                          " from its unit");
    }
    return a;
}

}  // namespace gradem::lab
