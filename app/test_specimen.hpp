#pragma once
// What the virtual-test commands (compress, tension) do before their test runs: read the cube
// config with the command line's --out and --vtk, and get the config's packing - from the
// packing cache, or made by genesis after a note saying so.
#include <cstdio>
#include <filesystem>
#include <string>

#include "app/console.hpp"
#include "experiments/config/cube_config.hpp"
#include "experiments/paste/paste_cache.hpp"
#include "experiments/specimen/packing_cache.hpp"

namespace gradem::app {

/// The cube config of `file`, its output folder replaced by `out` (when given) and with VTK
/// snapshots when `vtk`.
inline exp::CubeConfig load_test_config(const std::string& file, const std::string& out, bool vtk) {
    exp::CubeConfig config = exp::load_cube_config(file);
    if (!out.empty()) config.out_dir = out;
    if (vtk) config.vtk = true;
    return config;
}

/// The packing of `config` (notes prefixed with `command`); with `paste`, the explicit-paste
/// specimen and its fill's report.
inline exp::Packing load_test_packing(const exp::CubeConfig& config, const lab::GradationCurve& curve, const char* command,
                                      exp::PasteReport* paste = nullptr) {
    std::FILE* notes = console().notes();
    bool cached = false;
    if (!std::filesystem::exists(exp::packing_cache_path(config.cache_dir, exp::packing_key(curve, config.specimen))))
        std::fprintf(notes, "%s: generating the packing (genesis) ...\n", command);
    exp::Packing packing = paste ? exp::load_or_generate_paste(curve, config.specimen, config.cache_dir, &cached, paste)
                                 : exp::load_or_generate(curve, config.specimen, config.cache_dir, &cached);
    std::fprintf(notes, "%s: packing of %zu grains (%s)\n", command, packing.radius.size(), cached ? "cached" : "generated");
    return packing;
}

}  // namespace gradem::app
