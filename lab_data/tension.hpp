#pragma once
// Indirect tension tests of mortar, as load frames export them, reduced to a tensile strength per
// specimen and to the direct (uniaxial) tensile strength it stands for. The peak load comes from
// the same readers and channel roles as the cubes' (export_readers, load_frame_test); the
// specimen's dimensions from the export's metadata when it states them, else from the dataset
// (or the command line), else, for prisms, from ASTM C348.
//
//   splitting  ASTM C496/C496M §10 [check clause]: T = 2P/(π l d)
//              P maximum load [N], l cylinder length [m], d diameter [m] → T [Pa].
//   flexural   ASTM C348 §10 [check clause], centre-point loading of a simply supported prism:
//              Sf = 3 P L / (2 b d²), P maximum load [N], L support span, b width, d depth (in the
//              load direction) [m] → Sf [Pa]. The standard states it for its 40 × 40 × 160 mm prism
//              as Sf = 0.0028 P (MPa, P in N), which is 1.5 L / b³ with L = 120 mm
//              (1.5 · 120 / 40³ = 0.0028125 mm⁻²); EN 196-1 tests the same prism on a 100 mm span
//              (Sf = 0.00234 P). The general formula is used, so other prisms and spans work.
//   direct     fib Model Code 2010 §5.1.5.1 [check against the code text]:
//              f_ct = α_sp f_ct,sp with α_sp = 1.0 (Eq. 5.1-8), and
//              f_ct = α_fl f_ct,fl with α_fl = 0.06 h^0.7 / (1 + 0.06 h^0.7), h the depth of the
//              beam in mm (Eqs. 5.1-6, 5.1-7); for h = 40 mm, α_fl = 0.4425.

#include <filesystem>
#include <map>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "common/named_enum.hpp"
#include "lab_data/lab_warning.hpp"
#include "lab_data/load_frame_test.hpp"
#include "lab_data/raw_table.hpp"

namespace gradem::lab {

enum class TensileTestKind { splitting, flexural };

/// The dataset's `test` values and the command line's --test.
constexpr EnumNameTable<TensileTestKind, 2> enum_name_table(TensileTestKind) {
    return {{{TensileTestKind::splitting, "splitting"}, {TensileTestKind::flexural, "flexural"}}};
}
/// parse_enum<TensileTestKind> ignoring case and outer spaces.
std::optional<TensileTestKind> parse_tensile_test(std::string_view name);

/// ASTM C348 prism and span: the flexural defaults [m].
inline constexpr double kC348PrismWidth = 0.040;
inline constexpr double kC348PrismDepth = 0.040;
inline constexpr double kC348Span = 0.120;

/// fib Model Code 2010 Eq. (5.1-8): f_ct = α_sp f_ct,sp.
inline constexpr double kMc2010AlphaSplitting = 1.0;

/// Dimensions of a tension specimen [m]; 0 where not known.
struct TensileGeometry {
    double diameter_m = 0, length_m = 0;          ///< splitting: cylinder diameter d and length l
    double width_m = 0, depth_m = 0, span_m = 0;  ///< flexural: prism width b, depth d (load direction), support span L
    std::string source;                           ///< "file", "dataset", "command line", "ASTM C348", joined by '+'
    /// The dimensions not taken from the file (with file geometry allowed), for the warning.
    std::vector<NominalDimension> nominal_dimensions;
};

/// T = 2P/(π l d) [Pa] (ASTM C496).
double splitting_tensile_strength_pa(double peak_load_n, double length_m, double diameter_m);
/// Sf = 3PL/(2bd²) [Pa] (ASTM C348, centre-point loading).
double flexural_strength_pa(double peak_load_n, double span_m, double width_m, double depth_m);
/// α_fl = 0.06 h^0.7/(1 + 0.06 h^0.7), h = depth in mm (fib MC2010 Eq. 5.1-7).
double mc2010_alpha_flexural(double depth_m);
/// The factor from the test's strength to the direct tensile strength (α_sp or α_fl).
double direct_tension_factor(TensileTestKind kind, const TensileGeometry& geometry);
/// The conversion in words, e.g. "f_ct = 1.0 x f_ct,sp (fib Model Code 2010 5.1.5.1, alpha_sp = 1.0)".
std::string direct_tension_formula(TensileTestKind kind, const TensileGeometry& geometry);

struct TensileResult;
/// The conversion used for a group of specimens (a sand): the formula of each kind and prism
/// depth present, saying when splitting and flexural values are pooled.
std::string direct_tension_conversion(const std::vector<TensileResult>& tests, const std::vector<std::size_t>& members);

/// What a dataset's [[sand.tension]] (or the command line) says about a group of specimens.
struct TensileSpec {
    TensileTestKind test = TensileTestKind::splitting;
    TensileGeometry nominal;      ///< used where the export states nothing (0: not given)
    std::string nominal_source;   ///< "dataset" or "command line"
    bool use_file_geometry = true;
    // Where a missing dimension is to be set, for messages: the dataset TOML and the table's
    // line and name, or (config_file empty) the command line's options.
    std::filesystem::path config_file;
    int config_line = 0;
    std::string label;  ///< e.g. "[[sand.tension]] 'PBT1'"
};

struct TensileResult {
    std::string file;  ///< as given, or relative to the dataset folder
    std::string sand, batch, format;
    TensileTestKind test = TensileTestKind::splitting;
    TensileGeometry geometry;
    std::map<std::string, std::string> columns;  ///< role -> column used
    bool representative = false;
    double peak_load_n = 0;      ///< largest load sample [N]
    int peak_line = 0;           ///< its file line
    double strength_pa = 0;      ///< T (splitting) or Sf (flexural)
    double direct_factor = 0;    ///< α_sp or α_fl
    double direct_equivalent_pa = 0;  ///< direct_factor × strength_pa
    std::vector<std::string> flags;   ///< e.g. "peak_at_last_sample"
    std::vector<std::string> notes;   ///< what the reader did
    std::vector<LabWarning> warnings; ///< rows skipped, nominal dimensions (also in `notes`)
};

/// The specimen's dimensions: the export's metadata (diameter/length, or width/depth/span) where
/// stated and allowed, else the spec's nominal values, else (flexural) ASTM C348's. InputError
/// naming the dataset line and key (or the command-line option) when one stays unknown. With
/// file geometry allowed, the dimensions the file does not state are listed in
/// `nominal_dimensions`, each with where its value was set.
TensileGeometry tensile_geometry(const RawTable& table, const TensileSpec& spec, std::vector<std::string>& notes);

/// Peak load of an interpreted export → strength and direct equivalent.
TensileResult reduce_tensile_test(const LoadFrameTest& test, const TensileGeometry& geometry, TensileTestKind kind);

/// read_raw_export + interpret_export + tensile_geometry + reduce_tensile_test. Throws InputError.
TensileResult read_tensile_bytes(std::string_view bytes, const std::string& file, const TensileSpec& spec, const ReadOptions& read);
TensileResult read_tensile_file(const std::filesystem::path& path, const std::string& display_name, const TensileSpec& spec,
                                const ReadOptions& read);

}  // namespace gradem::lab
