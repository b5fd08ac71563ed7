#pragma once
// Cache of explicit-paste specimens (docs/genesis.md "Paste cache"), next to the sand packings of packing_cache.hpp.
// The sand packing is cached as before (its key ignores the paste settings); the paste
// specimen made from it is cached under its own key: FNV-1a 64 over the sand key, every
// MixDesign and PasteSpec field and kPasteAlgorithmVersion. Two files, each written
// atomically: `paste-<key>.bin`, a packing file of packing_cache's format (every grain, sand
// and paste), and `paste-<key>.family` ("GRADEMPF" | u32 version | u64 key | u64 N | N u8
// family | f64 paste density | PasteReport (raw f64/u64 fields) | u64 FNV-1a 64 of every byte
// before it). A missing, truncated or mismatched .family file next to a .bin is an error
// naming it (delete both and run again).
#include <cstdint>
#include <filesystem>

#include "experiments/specimen/genesis.hpp"
#include "experiments/paste/paste_fill.hpp"
#include "lab_data/gradation.hpp"

namespace gradem::exp {

/// Bump when paste_fill changes its output.
inline constexpr std::uint32_t kPasteAlgorithmVersion = 2;  // 2: overlaps removed by shrinking paste

/// Key of the paste specimen made from the sand packing `sand_key` with `settings`.
std::uint64_t paste_packing_key(std::uint64_t sand_key, const PasteSettings& settings);

/// Where the paste specimen of (curve, spec) is cached: `cache_dir`/paste-<16 hex digits>.bin.
std::filesystem::path paste_cache_path(const lab::GradationCurve& curve, const SpecimenSpec& spec,
                                       const std::filesystem::path& cache_dir);

/// The cached explicit-paste specimen of (curve, spec) (spec.paste set), or a new one: the sand
/// packing from load_or_generate, then fill_paste with the specimen's seed. `report` (optional)
/// receives the fill's report.
Packing load_or_generate_paste(const lab::GradationCurve& curve, const SpecimenSpec& spec,
                               const std::filesystem::path& cache_dir, bool* was_cached = nullptr,
                               PasteReport* report = nullptr);

}  // namespace gradem::exp
