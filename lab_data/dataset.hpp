#pragma once
// A lab dataset: one TOML file naming the sands, their sieve analyses, the cube exports of each
// batch, the nominal specimen, reduction options and column overrides. Paths are relative to the
// TOML file. Replacing the bundled representative exports by real ones needs no code change:
// put the files in place, point the globs at them, set representative = false.
//
//   [dataset]    name, description, representative (bool), note, export_format ("auto")
//   [specimen]   width_mm, depth_mm, height_mm, gauge_length_mm, use_file_geometry (bool)
//   [reduction]  chord_upper_fraction, chord_lower_strain, tangent_fraction, fit_popovics,
//                c109_group_size (2 or 3)
//   [gradation]  c144_limits (CSV path)
//   [columns]    time/load/crosshead/strain/lateral_strain/stress = "column name",
//                <role>_unit = "kN" (overrides of the inferred roles and units)
//   [[sand]]     name, sieve (CSV path; "file.csv#Sand B" picks one sand of a file with several),
//                specific_gravity
//   [[sand.batch]] name, files (glob or array of globs; '*' and '?' in the file-name part)
//   [[sand.tension]] name, test ("splitting" | "flexural"), files (as for batches), and the
//                nominal geometry used where an export does not state it: splitting
//                diameter_mm, length_mm; flexural width_mm, depth_mm, span_mm (default the
//                ASTM C348 prism, 40 × 40 mm on a 120 mm span). See tension.hpp.

#include <filesystem>
#include <string>
#include <vector>

#include "lab_data/curve_reduction.hpp"
#include "lab_data/load_frame_test.hpp"
#include "lab_data/tension.hpp"

namespace gradem::lab {

struct BatchSpec {
    std::string name;
    std::vector<std::filesystem::path> files;  ///< resolved and sorted
};

/// A group of tension specimens of one sand ([[sand.tension]]).
struct TensionBatchSpec {
    std::string name;
    TensileSpec spec;                          ///< the test, nominal geometry, and where it was set
    std::vector<std::filesystem::path> files;  ///< resolved and sorted
};

struct SandSpec {
    std::string name;
    std::filesystem::path sieve;  ///< empty: no gradation for this sand
    double specific_gravity = 0;  ///< 0: not given
    std::vector<BatchSpec> batches;
    std::vector<TensionBatchSpec> tension;
};

struct DatasetConfig {
    std::filesystem::path file;    ///< the TOML file (empty for defaults)
    std::filesystem::path folder;  ///< paths are relative to it
    std::string name = "lab", description, note;
    bool representative = false;
    ReadOptions read;              ///< format, nominal geometry, column overrides
    ReductionOptions reduction;
    std::size_t c109_group_size = 3;
    std::filesystem::path c144_limits;  ///< empty: no conformance check
    std::vector<SandSpec> sands;
};

/// Loads `path` (a .toml file, or a folder holding dataset.toml). With `require_sands`, at
/// least one [[sand]] is needed, each with one batch of cubes or of tension specimens. Throws InputError (file:line: ...) for TOML
/// syntax errors, unknown keys, wrong types, invalid values and globs that match nothing.
DatasetConfig load_dataset_config(const std::filesystem::path& path, bool require_sands = true);

/// The TOML file a dataset path stands for: the path itself, or <folder>/dataset.toml.
std::filesystem::path dataset_toml(const std::filesystem::path& path);

}  // namespace gradem::lab
