#pragma once
// On-disk cache of unbonded packings: genesis is slow, and one packing serves every parameter
// set (bonds and material are applied by the cube test), so a packing is generated once per
// (gradation, size rule, seed, genesis settings) and reused.
//
// Key: FNV-1a 64 over the raw bits of every input that influences genesis, plus the format
// and genesis versions:
//   - the gradation curve's size_m and passing (not the designations: they are labels);
//   - SizeRule::min_diameter, max_diameter, scale;
//   - SpecimenSpec::seed;
//   - every GenesisSpec field (edge, target_solid_fraction, locked_in_stress, stress_tolerance,
//     reference_modulus, stiffness_ratio, density, damping, min_contacts, floater_passes,
//     floater_growth, equilibrium_ratio, max_steps);
//   - kPackingFormatVersion and kGenesisAlgorithmVersion (bump the latter when genesis changes).
//
// File (native little-endian, packing-<16 hex digits of the key>.bin):
//   "GRADEMPK" | u32 format version | u64 key | u64 count N |
//   N x (f64 x, y, z) | N x f64 radius | f64 density | box_lo (3 f64) | box_hi (3 f64) |
//   GrainSample: u64 n + n f64 diameters, f64 removed_fine, f64 removed_coarse,
//                u64 n + n f64 sieve_sizes, u64 n + n f64 target_passing,
//                u64 n + n f64 achieved_passing, f64 max_deviation, f64 d50, f64 solid_volume |
//   i64 steps | i64 relax_iterations | f64 porosity, edge_over_d50, mean_coordination, floaters_before,
//   floaters_after | wall_stress (3 f64) | f64 unbalanced_ratio, radius_growth |
//   u8 converged | f64 seconds |
//   u64 FNV-1a 64 of every byte before it.
// Files are written to a temporary file and renamed into place (whole or not at all).
#include <cstdint>
#include <filesystem>
#include <stdexcept>
#include <string>

#include "experiments/specimen/genesis.hpp"
#include "lab_data/gradation.hpp"

namespace gradem::exp {

// Format 2: i64 relax_iterations after steps. Genesis 2: enthalpy minimisation + Morton order.
inline constexpr std::uint32_t kPackingFormatVersion = 2;
inline constexpr std::uint32_t kGenesisAlgorithmVersion = 3;  // 3: grains Morton-sorted inside the packer

/// A cache file that cannot be used; the message names the file and what is wrong.
class PackingCacheError : public std::runtime_error {
public:
    enum class Kind { io, bad_magic, version, key_mismatch, truncated, checksum };
    PackingCacheError(Kind kind, const std::string& what) : std::runtime_error(what), kind_(kind) {}
    [[nodiscard]] Kind kind() const noexcept { return kind_; }

private:
    Kind kind_;
};

/// Stable 64-bit key of everything that influences genesis (see the list above).
std::uint64_t packing_key(const lab::GradationCurve& curve, const SpecimenSpec& spec);

/// `dir`/packing-<16 lower-case hex digits>.bin
std::filesystem::path packing_cache_path(const std::filesystem::path& dir, std::uint64_t key);

/// The file's bytes (exposed for tests) and the atomic write.
std::string serialize_packing(const Packing& packing, std::uint64_t key);
void save_packing(const std::filesystem::path& path, const Packing& packing, std::uint64_t key);

/// Reads a cache file; throws PackingCacheError (bad magic, other format version, truncated,
/// checksum mismatch, key mismatch, unreadable), naming the file.
Packing load_packing(const std::filesystem::path& path, std::uint64_t expected_key);

/// The cached packing of (curve, spec) in `cache_dir`, or a new one (generated and saved).
/// A cache file that exists but cannot be used is an error (it is never silently replaced);
/// a new packing that did not converge is a GenesisError and is not saved.
Packing load_or_generate(const lab::GradationCurve& curve, const SpecimenSpec& spec,
                         const std::filesystem::path& cache_dir, bool* was_cached = nullptr);

}  // namespace gradem::exp
