#pragma once
// gradem._gradem.Config (config.cpp): a cube config's TOML document, its overrides, and the
// CubeConfig and TensionConfig the config readers make of it. The runs (virtual_tests.cpp) take
// cube() and tension().
#include <pybind11/pybind11.h>

#include <filesystem>
#include <map>
#include <string>
#include <toml++/toml.h>
#include <utility>
#include <vector>

#include "common/toml_section.hpp"
#include "experiments/config/cube_config.hpp"
#include "experiments/config/tension_config.hpp"

namespace gradem::py_api {

class Config {
public:
    static Config load(const std::string& path);

    /// Sets the keys of `overrides` ({"table.key": value}; None: back to the default) in the
    /// document and reads it again; throws (and changes nothing) when the reader refuses it.
    void set(const pybind11::dict& overrides);
    [[nodiscard]] pybind11::object get(const std::string& key) const;
    [[nodiscard]] pybind11::dict keys() const;
    [[nodiscard]] std::string document() const;
    [[nodiscard]] std::string saved_text() const;
    void save(const std::string& path) const;

    [[nodiscard]] const std::filesystem::path& file() const { return file_; }
    [[nodiscard]] const exp::CubeConfig& cube() const { return cube_; }
    [[nodiscard]] const exp::TensionConfig& tension() const { return tension_; }
    /// The overrides applied, in order: key and value as TOML ("(default)" for one removed).
    [[nodiscard]] const std::vector<std::pair<std::string, std::string>>& overrides() const { return overrides_; }

private:
    void read(const toml::table& root);

    std::filesystem::path file_;
    toml::table root_;
    exp::CubeConfig cube_;
    exp::TensionConfig tension_;
    std::map<std::string, common::toml_io::KeyInfo> keys_;
    std::vector<std::pair<std::string, std::string>> overrides_;
};

}  // namespace gradem::py_api
