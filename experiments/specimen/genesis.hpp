#pragma once
// Specimen genesis in the spirit of PFC's material genesis (Potyondy & Cundall 2004 §3;
// docs/genesis.md), with a geometric packer in place of the long dynamic compaction:
//   1. grains sampled by mass from the gradation curve under a size rule (grain_sampler);
//   2. dropped at random into the cubic vessel and packed by soft-sphere enthalpy minimisation
//      (dense_placement: positions and the three box edges, no dynamics), jammed at 1e-3 E*
//      and unloaded in decades to the isotropic "locked-in" stress: the walls end at that
//      stress and every grain in force balance, grains frictionless;
//   3. floaters (grains with fewer than `min_contacts` contacts) enlarged a little, repeatedly,
//      and the packing minimised again after each pass (at the jamming pressure, 1e-3 E*, where
//      a 1 % growth is a small disturbance; floaters_after is counted at the locked-in stress);
//   4. grains sorted along the Morton curve (morton_order: memory locality for the engine);
//   5. a short DEM check with the World (real masses, the six frictionless walls, local
//      damping): cycled until the World itself measures every wall stress within tolerance and
//      the mean unbalanced-force ratio below `equilibrium_ratio`.
// Converged means step 5 holds. Note on equilibrium: at sigma_0 / E* = 1e-5 the frictionless
// packing is within ~1e-5 of jamming, and every minimiser tried (FIRE with several step limits,
// Cundall local damping with unit-mass scaling) stalls at a mean unbalanced-force ratio of
// 3e-3 .. 1e-2 on the default cube, while the wall stresses converge to 0.1 %. The default
// tolerance is therefore 0.02 (the minimiser aims at half of it); the cube test cycles the
// BONDED specimen to its strict settle_ratio (1e-4) before loading.
// A run that does not converge within `max_steps` is returned flagged (converged = false, the
// description says so); load_or_generate refuses it (GenesisError).
// The result is an unbonded Packing: bonds and material parameters are applied separately, so
// one packing serves every parameter set (common random numbers for calibration).
#include <cstdint>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "core/vec3.hpp"
#include "experiments/specimen/grain_sampler.hpp"
#include "experiments/paste/paste_spec.hpp"

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

/// An unbonded packing and how it was made.
struct Packing {
    std::vector<Vec3> position;        ///< grain centres [m]
    std::vector<double> radius;        ///< [m]
    double density = 0.0;              ///< [kg/m^3]
    Vec3 box_lo, box_hi;               ///< vessel walls at the end of genesis [m]
    // --- report ---
    GrainSample grains;                ///< sampling report (diameters cleared to save space)
    std::int64_t steps = 0;            ///< DEM steps of genesis (the check, step 5)
    std::int64_t relax_iterations = 0; ///< minimisation iterations (steps 2 and 3)
    double porosity = 0.0;             ///< 1 - grain volume / box volume [-]
    double edge_over_d50 = 0.0;        ///< L / d50 [-]
    double mean_coordination = 0.0;    ///< contacts per grain (walls included) [-]
    double floaters_before = 0.0;      ///< fraction of grains with < min_contacts at the jamming pressure, before passes
    double floaters_after = 0.0;       ///< at the end, at the locked-in stress [-]
    Vec3 wall_stress;                  ///< final normal stress on the x, y, z walls [Pa]
    double unbalanced_ratio = 0.0;     ///< final mean unbalanced-force ratio [-]
    double radius_growth = 1.0;        ///< multiplier applied to every radius (1: the box moves instead) [-]
    bool converged = false;            ///< stress and equilibrium tolerances met (by the World)
    double seconds = 0.0;              ///< wall-clock time of genesis [s]
    // --- explicit paste (experiments/paste/paste_fill.hpp); empty / 0 for a sand-only packing ---
    std::vector<std::uint8_t> family;  ///< per grain: 0 sand, 1 paste; empty: all sand
    double paste_density = 0.0;        ///< density of paste particles [kg/m^3]
    [[nodiscard]] double edge() const { return box_hi.z - box_lo.z; }
};

/// Genesis that did not converge within its budget (thrown by load_or_generate).
class GenesisError : public std::runtime_error {
public:
    using std::runtime_error::runtime_error;
};

/// Runs genesis. Throws std::invalid_argument for a spec or curve that cannot work (cut-offs
/// that remove everything, an edge smaller than three largest grains, a locked-in stress that
/// is not small against E*, grains that jam before they fill the vessel at the target solid
/// fraction). A run that does not converge within max_steps comes back with converged = false.
Packing generate_packing(const lab::GradationCurve& curve, const SpecimenSpec& spec);

/// Why a packing is not converged (walls, ratio, budget), for error messages; empty if it is.
std::string convergence_failure(const Packing& packing, const SpecimenSpec& spec);

/// One-paragraph human summary of the rule and the result (N, L/d50, porosity, ...).
std::string describe(const Packing& packing, const SpecimenSpec& spec);

}  // namespace gradem::exp
