#pragma once
// A cube config read from a TOML document in memory rather than from its file: the same readers
// (cube_config.hpp, tension_config.hpp), the same messages, the same defaults. The Python module
// (python/) sets a key of the document and reads it again, so an override is exactly the key
// written into the file, checked by the reader that checks the file.
#include <filesystem>
#include <map>
#include <string>
#include <toml++/toml.h>

#include "common/toml_section.hpp"
#include "experiments/config/cube_config.hpp"
#include "experiments/config/tension_config.hpp"

namespace gradem::exp {

/// load_cube_config() of the document `root`, which stands for `toml_file`: messages name that
/// file (line 0, left out, for a key set in memory), relative paths start at its folder.
/// `keys` (optional) receives every key the reader asked for, "table.key" -> where it was given,
/// its value as written (or its default, "... (default)") and whether it is a path.
CubeConfig load_cube_config(const toml::table& root, const std::filesystem::path& toml_file,
                            std::map<std::string, common::toml_io::KeyInfo>* keys = nullptr);

/// load_tension_config() of the document `root` of `config` (as above).
TensionConfig load_tension_config(const CubeConfig& config, const toml::table& root,
                                  std::map<std::string, common::toml_io::KeyInfo>* keys = nullptr);

}  // namespace gradem::exp
