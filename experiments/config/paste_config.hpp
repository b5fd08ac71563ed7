#pragma once
// The explicit-paste keys of a cube config (experiments/README.md "Explicit paste"):
//   [specimen] representation = "parallel_bonds" (default) | "explicit_paste"
//   [mix]      sand_to_cementitious_volume, water_cement_ratio, cement_specific_gravity,
//              sand_specific_gravity (default: the dataset sand's specific_gravity),
//              cement_bulk_density_kg_m3, sand_bulk_density_kg_m3, air_content, hydration_degree
//   [paste]    min_diameter_mm, max_diameter_mm (default = min: one coarse-grained size),
//              solid_fraction, overlap_tolerance, rsa_scale, rsa_attempts, growth_stages,
//              relax_iterations, memory_fraction, itz_strength_factor, itz_modulus_factor,
//              sand_sand ("frictional" | "bonded")
// [mix] and [paste] are refused with representation = "parallel_bonds".
#include <toml++/toml.h>

#include "experiments/config/cube_config.hpp"
#include "common/toml_section.hpp"

namespace gradem::exp {

/// Reads [mix] and [paste] into c.specimen.paste and c.material.families (after [specimen],
/// which holds c.representation). Throws common::InputError naming the file, line and key.
void read_paste_config(common::toml_io::Context& ctx, const toml::table& root, CubeConfig& c);

}  // namespace gradem::exp
