#pragma once
// Reading a study file's [study] keys: the readers the study kinds share (lists of positive
// numbers, seeds, names; files that must exist). Every error is a common::InputError naming the
// file, line and key.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "calibrate/study/study_kind.hpp"
#include "common/toml_section.hpp"

namespace gradem::cal::study_keys {

using common::toml_io::Section;

/// The array `key` as a list of `T`, each checked by `read` (nullopt: not a valid item); empty
/// when the key is absent. Refuses an empty array and repeated values.
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

std::optional<double> positive_number(const toml::node& n);
std::optional<std::uint64_t> positive_integer(const toml::node& n);
std::optional<std::string> text_item(const toml::node& n);

/// InputError at `key` when `path` does not exist: "<path> not found; <what>".
void require_file(StudyKeys& keys, const std::string& key, const std::filesystem::path& path, const std::string& what);

/// InputError naming the study file and the line of `study.<key>`.
[[noreturn]] void refuse(const StudyKeys& keys, const char* key, const std::string& what);

}  // namespace gradem::cal::study_keys
