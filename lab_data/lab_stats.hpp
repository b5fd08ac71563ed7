#pragma once
// The study's lab statistics: per cube reductions, per sand gradation and summary statistics
// (Table 2 and Table 4 of the study, and more), and Welch tests between the sands.
// Calibration reads these through analyse_lab_dataset() (or the JSON written by `gradem lab`).

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "lab_data/c144.hpp"
#include "lab_data/curve_reduction.hpp"
#include "lab_data/dataset.hpp"
#include "lab_data/gradation.hpp"
#include "lab_data/load_frame_test.hpp"
#include "lab_data/sieve_table.hpp"
#include "lab_data/statistics.hpp"
#include "lab_data/tension.hpp"

namespace gradem::lab {

/// ASTM C109 §10 [check]: load rate 900 to 1800 N/s.
inline constexpr double kC109MinLoadRate = 900.0;   // N/s
inline constexpr double kC109MaxLoadRate = 1800.0;  // N/s

struct CubeResult {
    std::string file;  ///< as given, or relative to the dataset folder
    std::string sand, batch;
    std::string format;
    SpecimenGeometry geometry;
    std::map<std::string, std::string> columns;  ///< role -> column used
    bool representative = false;                 ///< the dataset or the file says the data are representative
    CurveReduction reduction;
    StressStrainCurve curve;                     ///< the curve as read (SI, compression positive); for plots (curves.csv)
    double load_rate_n_per_s = 0;                ///< mean between 10 % and 50 % of peak; NaN without time
    std::vector<std::string> flags;              ///< e.g. "c109_range_discarded", "load_rate_outside_c109"
    std::vector<std::string> notes;              ///< what the reader did (sign flips, decoding, ...)
    std::vector<LabWarning> warnings;            ///< rows skipped, nominal dimensions (also in `notes`)
};

/// The statistics of one quantity over a sand's cubes (display units are chosen by writers).
struct SandStatistics {
    SampleSummary peak_stress_pa, strain_at_peak, chord_modulus_pa, tangent_modulus_pa, strain_at_peak_crosshead;
};

/// A sand's tension specimens: the strengths of each kind of test and the direct-tension
/// equivalent, which pools the converted values of both kinds (tension.hpp).
struct TensileStatistics {
    SampleSummary splitting_pa;  ///< ASTM C496 splitting tensile strength T
    SampleSummary flexural_pa;   ///< ASTM C348 flexural strength Sf
    SampleSummary direct_pa;     ///< fib MC2010 direct tensile strength f_ct of every specimen
};

struct BatchRangeCheck {
    std::string batch;
    std::vector<std::string> files;  ///< the group's cubes
    std::string discarded_file;      ///< the cube C109 says to discard (empty if none)
    RangeCheck check;
};

struct SandResult {
    std::string name;
    double specific_gravity = 0;
    std::optional<SieveAnalysis> sieve;
    std::optional<GradationIndices> gradation;
    std::optional<C144Verdict> c144;
    std::vector<std::size_t> cubes;  ///< indices into LabStats::cubes
    std::vector<std::string> batches;
    SandStatistics stats;
    std::vector<BatchRangeCheck> range_checks;
    std::vector<std::size_t> tensile;          ///< indices into LabStats::tensile_tests
    std::vector<std::string> tension_batches;  ///< names of its [[sand.tension]] groups
    TensileStatistics tensile_stats;
};

struct Comparison {
    std::string quantity;  ///< "peak_stress_mpa", "strain_at_peak", "chord_modulus_mpa", "tangent_modulus_mpa", "tensile_strength_mpa"
    std::string sand_a, sand_b;
    WelchTest test;        ///< in SI; mean_difference = a − b
};

struct LabStats {
    std::string dataset;
    std::string source;  ///< dataset TOML or "files"
    bool representative = false;
    std::string note;
    ReductionOptions reduction;
    std::vector<SandResult> sands;
    std::vector<CubeResult> cubes;
    std::vector<TensileResult> tensile_tests;
    std::vector<Comparison> comparisons;  ///< cube quantities between sands with cubes, the direct tensile strength between sands with tension specimens
};

/// Reads and reduces a whole dataset (see dataset.hpp). Throws InputError naming the file and
/// line of the first problem; nothing is returned partially.
LabStats analyse_lab_dataset(const std::filesystem::path& folder_or_toml);
LabStats analyse_lab_dataset(const DatasetConfig& config);

/// Reduces individual export files with the options of `config` (its sands are ignored);
/// the result has one pseudo-sand "files" with their statistics.
LabStats analyse_lab_files(const std::vector<std::filesystem::path>& files, const DatasetConfig& config);

/// Tension-test exports given as files (`gradem lab --test splitting FILE...`), all of the kind
/// and nominal geometry of `spec`, read with the options of `config`; one pseudo-sand "files".
LabStats analyse_tension_files(const std::vector<std::filesystem::path>& files, const TensileSpec& spec, const DatasetConfig& config);

/// Sieve analyses given as files (`gradem lab sieve.csv ...`): every sand of every file (only
/// the named one for "file.csv#sand"), named by its column headers or "# sand:" line (text
/// before " (") or else the file stem, with gradation indices and, when
/// `c144_limits` is not empty, the ASTM C144 check. Throws InputError for impossible tables.
LabStats analyse_sieve_files(const std::vector<std::filesystem::path>& files, const std::filesystem::path& c144_limits);

/// Reads and reduces one export; InputError when the curve cannot be reduced (e.g. the C469
/// modulus window is never reached), naming the file and the line of the sample concerned.
CubeResult reduce_cube_file(const std::filesystem::path& path, const std::string& display_name, const DatasetConfig& config);

}  // namespace gradem::lab
