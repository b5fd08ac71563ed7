#pragma once
// What a specimen is made from (docs/genesis.md): the size rule of the grains, the genesis
// settings (cube edge, solid fraction, locked-in stress, ...), the packing seed and, for
// explicit paste, the paste settings. Validated by invalid_reason() (genesis.cpp); made into a
// Packing by generate_packing (genesis.hpp), cached by packing_cache.hpp.
#include <cstdint>
#include <optional>
#include <string>

#include "experiments/paste/paste_spec.hpp"
#include "experiments/specimen/grain_sampler.hpp"

namespace gradem::exp {

struct GenesisSpec {
    double edge = 3.5e-3;                  ///< target cube edge L [m]
    double target_solid_fraction = 0.60;   ///< grains sampled to fill L^3 at this fraction [-]
    double locked_in_stress = 0.1e6;       ///< isotropic stress reached by the walls [Pa]
    double stress_tolerance = 0.05;        ///< relative tolerance on each wall's stress [-]
    double reference_modulus = 10.0e9;     ///< E* of grains and walls while packing [Pa]
    double stiffness_ratio = 1.5;          ///< kappa* while packing [-]
    double density = 2640.0;               ///< grain density [kg/m^3] (SG 2.64, the study)
    double damping = 0.9;                  ///< local damping of the DEM check [-]
    int min_contacts = 3;                  ///< floater threshold (PFC N_f = 3)
    int floater_passes = 2;                ///< enlargement passes for floaters
    double floater_growth = 0.01;          ///< relative radius growth of a floater per pass [-]
    double equilibrium_ratio = 0.02;       ///< mean unbalanced-force ratio to reach [-] (see note)
    std::int64_t max_steps = 120000;       ///< budget: minimisation iterations + DEM steps
    [[nodiscard]] std::optional<std::string> invalid_reason() const;
};

struct SpecimenSpec {
    SizeRule size_rule;
    GenesisSpec genesis;
    std::uint64_t seed = 1;
    /// representation = "explicit_paste": the sand packing's pores filled with paste particles
    /// (paste_fill.hpp; load_or_generate does it and caches the result); none: parallel bonds.
    std::optional<PasteSettings> paste;
    [[nodiscard]] std::optional<std::string> invalid_reason() const;
};

}  // namespace gradem::exp
