#pragma once
// ParaView output without libvtk: hand-written VTK XML PolyData (.vtp) files and a .pvd
// collection tying them into a time series (VTK XML file formats, "PolyData" and "Collection").
//
//   particles.vtp : Points = particle centres, one Vert per particle; PointData id, radius [m]
//                   (for "Scale by Array" glyphs), velocity [m/s], force [N], spin [rad/s],
//                   broken_bonds, and displacement [m] when reference positions are given.
//   bonds.vtp     : Points = particle centres, one Line (i, j) per bond, intact or broken;
//                   CellData state (PFC code 1 tension / 2 shear / 3 intact), normal_force [N]
//                   (tension positive), shear_force [N] (magnitude), bond_radius [m],
//                   break_step (-1 if intact).
//   cracks.vtp    : one Vert per crack at its contact point; PointData mode, normal, radius,
//                   step, time, tensile_stress, shear_stress, bond.
//
// Encoding: base64 (default) writes every DataArray as format="binary" inline data: one
// base64 block of [UInt64 byte count][raw little/native-endian values], encoded together
// (header_type="UInt64", version="1.0", no compression). ascii writes the values as text,
// doubles with 17 significant digits (exact round trip).
// Every file is written through common::write_file_atomically: whole or not at all; the
// parent folder is created.
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include "core/vec3.hpp"
#include "core/world.hpp"
#include "core/world_types.hpp"

namespace gradem::report {

enum class VtkEncoding : std::uint8_t { ascii, base64 };

/// Particles of `world` as Verts. `reference_positions` (one per particle, [m]) adds the
/// PointData `displacement` = position - reference; throws std::invalid_argument on a size
/// mismatch.
void write_particles_vtp(const std::filesystem::path& path, const World& world,
                         const std::vector<Vec3>* reference_positions = nullptr,
                         VtkEncoding encoding = VtkEncoding::base64);

/// Every bond of `world` (intact and broken) as a Line between its two particle centres; the
/// Line's point ids are the particle indices. break_step comes from world.break_events().
void write_bonds_vtp(const std::filesystem::path& path, const World& world,
                     VtkEncoding encoding = VtkEncoding::base64);

/// One Vert per crack (bond break) at its contact point.
void write_cracks_vtp(const std::filesystem::path& path, const std::vector<BreakEvent>& cracks,
                      VtkEncoding encoding = VtkEncoding::base64);

/// A .pvd collection: add() one DataSet per written file, write() rewrites the whole .pvd
/// atomically (call it after each output step so an interrupted run keeps a valid series).
class PvdSeries {
public:
    explicit PvdSeries(std::filesystem::path pvd_path);

    /// `file` as it was written (absolute, or relative to the current working directory); it
    /// is stored relative to the .pvd's folder. `time` [s] becomes the DataSet's timestep;
    /// `part` tells apart files of the same time (e.g. 0 particles, 1 bonds, 2 cracks).
    void add(double time, const std::filesystem::path& file, int part = 0);
    void write() const;

    [[nodiscard]] const std::filesystem::path& path() const { return pvd_path_; }
    [[nodiscard]] std::size_t size() const { return entries_.size(); }

private:
    struct Entry {
        double time = 0.0;   ///< [s]
        int part = 0;
        std::string file;    ///< relative to the .pvd's folder, '/' separators
    };
    std::filesystem::path pvd_path_;
    std::vector<Entry> entries_;
};

/// Standard base64 (RFC 4648, '+' '/', '=' padding) of `size` bytes.
std::string base64_encode(const void* data, std::size_t size);

}  // namespace gradem::report
