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

#include "experiments/specimen/packing.hpp"
#include "experiments/specimen/specimen_spec.hpp"
#include "lab_data/gradation.hpp"

namespace gradem::exp {

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
