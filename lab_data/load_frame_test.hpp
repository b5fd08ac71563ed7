#pragma once
// One load-frame test in SI, compression positive: what a reader's RawTable means once the
// column roles (time, load, crosshead, extensometer strain, …) are known and units converted.

#include <filesystem>
#include <initializer_list>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "common/named_enum.hpp"
#include "lab_data/curve_reduction.hpp"
#include "lab_data/export_readers.hpp"
#include "lab_data/lab_warning.hpp"
#include "lab_data/raw_table.hpp"
#include "lab_data/units.hpp"

namespace gradem::lab {

enum class ChannelRole { time, load, crosshead, strain, lateral_strain, stress };
inline constexpr ChannelRole kAllRoles[] = {ChannelRole::time, ChannelRole::load, ChannelRole::crosshead,
                                            ChannelRole::strain, ChannelRole::lateral_strain, ChannelRole::stress};
/// The roles' names (also the [columns] keys and --column/--unit roles).
constexpr EnumNameTable<ChannelRole, 6> enum_name_table(ChannelRole) {
    return {{{ChannelRole::time, "time"},
             {ChannelRole::load, "load"},
             {ChannelRole::crosshead, "crosshead"},
             {ChannelRole::strain, "strain"},
             {ChannelRole::lateral_strain, "lateral_strain"},
             {ChannelRole::stress, "stress"}}};
}
/// parse_enum<ChannelRole> ignoring case and outer spaces.
std::optional<ChannelRole> parse_role(std::string_view name);

/// User overrides of the inferred column roles ([columns] in the dataset config).
struct ChannelOverrides {
    std::map<ChannelRole, std::string> column;  ///< column name as in the file (case and outer spaces ignored)
    std::map<ChannelRole, std::string> unit;    ///< unit to use instead of (or in the absence of) the file's
};

/// Specimen geometry. C109 cubes: 50 mm (2 in.) edge; loaded face width × depth.
struct SpecimenGeometry {
    double width_m = 0.050;       ///< loaded-face edge [m]
    double depth_m = 0.050;       ///< loaded-face edge [m]
    double height_m = 0.050;      ///< platen-to-platen height [m] (for crosshead strain)
    double area_m2 = 0.0;         ///< loaded area [m²]; > 0 overrides width × depth (e.g. from a diameter)
    double gauge_length_m = 0.0;  ///< extensometer gauge length [m]; needed only if it reports a length
    std::string source = "nominal";  ///< "nominal", "config", or "file"
    [[nodiscard]] double loaded_area_m2() const { return area_m2 > 0 ? area_m2 : width_m * depth_m; }
    [[nodiscard]] std::optional<std::string> invalid_reason() const;
};

struct ReadOptions {
    ExportFormat format = ExportFormat::automatic;
    ChannelOverrides channels;
    SpecimenGeometry nominal;       ///< used for whatever the file does not state
    bool use_file_geometry = true;  ///< take dimensions from the file's metadata when present
    /// Where each nominal dimension was set ("width" -> "lab/dataset.toml [specimen]"), for the
    /// warning when a file does not state it; a dimension not listed is gradem's default.
    std::map<std::string, std::string> nominal_origin;
};

/// The origin of a nominal cube dimension nobody set: the ASTM C109 cube's 50 mm.
inline constexpr const char* kDefaultCubeOrigin = "gradem's default (the ASTM C109 50 mm cube)";

struct LoadFrameTest {
    std::string file, format, encoding;
    std::vector<double> time_s;          ///< from the first sample [s]; empty if no time column
    std::vector<double> load_n;          ///< compression positive [N]
    std::vector<double> crosshead_m;     ///< platen approach from the first sample [m]; may be empty
    std::vector<double> strain;          ///< extensometer strain, zeroed at the first sample [-]; may be empty
    std::vector<double> lateral_strain;  ///< may be empty
    std::vector<int> line;               ///< file line of each sample
    SpecimenGeometry geometry;
    std::map<std::string, std::string> columns;  ///< role -> "name [unit]" actually used
    bool representative = false;  ///< the file itself says it is REPRESENTATIVE (synthetic), see datasets/study
    std::vector<std::string> notes;
    std::vector<LabWarning> warnings;  ///< rows skipped (also in `notes` and sent to the warning sink)
    /// The cube dimensions (width, depth, height) taken from `ReadOptions::nominal` because the
    /// file does not state them; empty when the file states them all or file geometry is off.
    std::vector<NominalDimension> nominal_dimensions;
    bool no_file_dimensions = false;  ///< the file states none of the cube's dimensions
};

/// The nominal_geometry record of a cube read from `test` (none when it used only file values).
LabWarning cube_geometry_warning(const LoadFrameTest& test);

/// Maps roles, converts units and signs. Throws InputError (file:line: column 'x': ...).
LoadFrameTest interpret_export(const RawTable& table, const ReadOptions& options = {});

/// read_raw_export + interpret_export.
LoadFrameTest read_load_frame_test(const std::filesystem::path& path, const ReadOptions& options = {});
LoadFrameTest read_load_frame_bytes(std::string_view bytes, const std::string& file, const ReadOptions& options = {});

/// A specimen dimension from the file's metadata: the first entry whose lower-case key contains
/// one of `keys` and none of `not_keys`, as `q` (length or area) in SI ("50.21 mm", or value +
/// unit cell; without a unit mm or mm², noted in `notes`). nullopt when there is no such entry or
/// its value is not a positive number; InputError (file:line) when its unit is of another quantity.
std::optional<double> metadata_dimension(const RawTable& table, std::initializer_list<const char*> keys,
                                         std::initializer_list<const char*> not_keys, Dimension q, std::vector<std::string>& notes);

/// Stress = load / loaded area (ASTM C109 §11); strain = extensometer (or, without one,
/// crosshead displacement / height); crosshead strain reported separately.
StressStrainCurve to_stress_strain(const LoadFrameTest& test);

}  // namespace gradem::lab
