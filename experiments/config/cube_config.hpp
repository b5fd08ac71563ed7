#pragma once
// The TOML file behind `gradem specimen` and `gradem compress`: which sand, how the specimen is
// made, the micro-parameters, the test and where results go. Every key is documented (unit,
// default, meaning) in experiments/README.md; units are in the key names (_mm, _mpa, _gpa,
// _kg_m3, _per_s, _deg) and are converted to SI here, once.
//
//   [specimen]   dataset (folder or dataset.toml) + sand (name), or sieve_csv (a sieve table)
//   [size_rule]  min_diameter_mm, max_diameter_mm, scale
//   [genesis]    edge_mm, target_solid_fraction, locked_in_stress_mpa, ..., seed
//   [material]   model (bond law), effective_modulus_gpa, ..., tensile_strength_cv, ...; the keys are
//                the rows of experiments/config/material_table.hpp
//   [test]       strain_rate_per_s (number or "auto"), ramp_strain, stop_fraction, ...
//   [output]     dir, cache_dir, vtk, vtk_every
//
// Missing keys take the defaults of the structs (bond_modulus_gpa and bond_stiffness_ratio
// default to the contact's values). Paths are relative to the config file. Unknown tables and
// keys, wrong types and out-of-range values throw common::InputError "file:line: key 'x' = v
// violates rule" (the structs' own invalid_reason() supplies the rule).
#include <filesystem>
#include <string>

#include "common/named_enum.hpp"
#include "experiments/virtual_tests/cube_test.hpp"
#include "experiments/specimen/genesis.hpp"
#include "lab_data/gradation.hpp"

namespace gradem::exp {

/// [specimen] representation: how the cement paste is modelled. parallel_bonds: the sand grains
/// only, the paste as bonds between them; explicit_paste: the paste as particles of its own,
/// bonded to each other and to the sand ([mix], [paste]: paste_config.hpp).
enum class Representation { parallel_bonds, explicit_paste };
constexpr EnumNameTable<Representation, 2> enum_name_table(Representation) {
    return {{{Representation::parallel_bonds, "parallel_bonds"}, {Representation::explicit_paste, "explicit_paste"}}};
}

struct CubeConfig {
    std::filesystem::path file;        ///< the TOML file itself (for messages)
    std::filesystem::path dataset;     ///< lab dataset folder or TOML (with `sand`), or empty
    std::string sand;                  ///< sand name in the dataset
    std::filesystem::path sieve_csv;   ///< or a sieve table (then dataset is empty)
    /// Where the sand's source was given (specimen.dataset or specimen.sieve_csv), for the
    /// message when nothing is there: the key, its text as written, its line, and the folder
    /// a relative path was resolved against.
    struct SourceKey {
        std::string key, text;
        int line = 0;
        std::filesystem::path dir;
    } source_key;
    Representation representation = Representation::parallel_bonds;  ///< [mix], [paste] with explicit_paste (paste_config.hpp)
    SpecimenSpec specimen;
    MaterialParams material;
    CubeTestSpec test;                 ///< test.loading.platen_friction = material.platen_friction
    bool auto_strain_rate = false;     ///< test.strain_rate_per_s = "auto": see strain_rate_for()
    std::filesystem::path cache_dir;   ///< packing cache
    std::filesystem::path out_dir;     ///< result folder
    bool vtk = false;                  ///< ParaView output
    int vtk_every = 0;                 ///< curve points between ParaView snapshots (0: the test's default)
};

/// Reads and validates a config file (see above). Throws common::InputError.
CubeConfig load_cube_config(const std::filesystem::path& toml_file);

/// The gradation curve of the configured sand (dataset sand's sieve file, or sieve_csv).
/// Throws common::InputError naming the config file when the sand is not in the dataset, and the
/// readers' InputError for a bad dataset or sieve file; a source path with nothing there is an
/// InputError naming its key, line and the folder it was resolved against.
lab::GradationCurve load_gradation(const CubeConfig& config);

/// The strain rate [1/s] to run at: the configured one, or quasi_static_strain_rate() for
/// "auto" (it depends on the packing).
double strain_rate_for(const CubeConfig& config, const Packing& packing);

}  // namespace gradem::exp
