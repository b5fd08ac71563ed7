#pragma once
// Specimen genesis as PFC's material genesis does it (Potyondy & Cundall 2004 §3; physics.md §3):
//   1. grains sampled by mass from the gradation curve under a size rule (grain_sampler);
//   2. placed at random in the cubic vessel and pushed apart geometrically until they barely
//      overlap (dense_placement), then enclosed by six frictionless walls;
//   3. radii scaled uniformly until the walls feel a small isotropic "locked-in" stress,
//      grains frictionless;
//   4. floaters (grains with fewer than `min_contacts` contacts) enlarged a little, repeatedly;
//   5. cycled to equilibrium (mean unbalanced-force ratio below a tolerance).
// Note on equilibrium: a frictionless, unbonded packing held at sigma_0 / E* ~ 1e-5 keeps
// creeping (near the jamming point it has soft modes), and its mean unbalanced-force ratio
// falls only slowly below a few per cent; PFC-style 1e-5 is reached only once the specimen is
// bonded. Genesis therefore stops at a ratio of 0.05 by default, and the cube test cycles the
// bonded specimen to a strict ratio before loading.
// The result is an unbonded Packing: bonds and material parameters are applied separately, so
// one packing serves every parameter set (common random numbers for calibration).
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "core/vec3.hpp"
#include "experiments/grain_sampler.hpp"

namespace gradem::exp {

struct GenesisSpec {
    double edge = 3.5e-3;                  ///< target cube edge L [m]
    double target_solid_fraction = 0.60;   ///< grains sampled to fill L^3 at this fraction [-]
    double locked_in_stress = 0.1e6;       ///< isotropic stress reached by the walls [Pa]
    double stress_tolerance = 0.05;        ///< relative tolerance on each wall's stress [-]
    double reference_modulus = 10.0e9;     ///< E* of grains and walls while packing [Pa]
    double stiffness_ratio = 1.5;          ///< kappa* while packing [-]
    double density = 2640.0;               ///< grain density [kg/m^3] (SG 2.64, the study)
    double damping = 0.9;                  ///< local damping while packing [-]
    int min_contacts = 3;                  ///< floater threshold (PFC N_f = 3)
    int floater_passes = 2;                ///< enlargement passes for floaters
    double floater_growth = 0.01;          ///< relative radius growth of a floater per pass [-]
    double equilibrium_ratio = 0.05;       ///< mean unbalanced-force ratio to stop at [-] (see note)
    std::int64_t max_steps = 120000;       ///< give up (with a warning in the report) after this
    [[nodiscard]] std::optional<std::string> invalid_reason() const;
};

struct SpecimenSpec {
    SizeRule size_rule;
    GenesisSpec genesis;
    std::uint64_t seed = 1;
    [[nodiscard]] std::optional<std::string> invalid_reason() const;
};

/// An unbonded packing and how it was made.
struct Packing {
    std::vector<Vec3> position;        ///< grain centres [m]
    std::vector<double> radius;        ///< [m]
    double density = 0.0;              ///< [kg/m^3]
    Vec3 box_lo, box_hi;               ///< vessel walls at the end of genesis [m]
    // --- report ---
    GrainSample grains;                ///< sampling report (diameters cleared to save space)
    std::int64_t steps = 0;            ///< DEM steps of genesis
    double porosity = 0.0;             ///< 1 - grain volume / box volume [-]
    double edge_over_d50 = 0.0;        ///< L / d50 [-]
    double mean_coordination = 0.0;    ///< contacts per grain (walls included) [-]
    double floaters_before = 0.0;      ///< fraction of grains with < min_contacts, before passes
    double floaters_after = 0.0;       ///< and after [-]
    Vec3 wall_stress;                  ///< final normal stress on the x, y, z walls [Pa]
    double unbalanced_ratio = 0.0;     ///< final mean unbalanced-force ratio [-]
    double radius_growth = 1.0;        ///< multiplier applied to every radius to reach the stress [-]
    bool converged = false;            ///< stress and equilibrium tolerances met
    double seconds = 0.0;              ///< wall-clock time of genesis [s]
    [[nodiscard]] double edge() const { return box_hi.z - box_lo.z; }
};

/// Runs genesis. Throws std::invalid_argument for a spec or curve that cannot work (cut-offs
/// that remove everything, an edge smaller than three largest grains, ...).
Packing generate_packing(const lab::GradationCurve& curve, const SpecimenSpec& spec);

/// One-paragraph human summary of the rule and the result (N, L/d50, porosity, ...).
std::string describe(const Packing& packing, const SpecimenSpec& spec);

}  // namespace gradem::exp
