#pragma once
// Explicit-paste specimens (docs/genesis.md "Paste fill"): the sand packed as for parallel bonds
// (genesis.hpp), then its pore space filled with paste particles.
//   1. dilate: the jammed sand packing (solid fraction φ_p ≈ 0.6) is scaled about the box centre
//      (centres and box, radii kept) to the mix design's sand fraction φ_s ≈ 0.5, so the grains
//      float in paste as in the real mortar (a sand fraction ≤ 0.55 is below random close packing). A mix
//      whose φ_s exceeds φ_p is refused: its paste could not fill the sand's pore space;
//   2. size: paste particles are sampled by mass from a cement size distribution (Rosin-Rammler
//      F(d) = 1 - exp(-(d/d')^n), d' = 15 µm, n = 0.9: fitted to NIST SRM 114p's 8.9/14.9/24.9 %
//      passing 1/2/4 µm) truncated to [min_diameter, max_diameter], or all of one
//      coarse-grained size (min = max). Their total volume is the mix's paste fraction × box ×
//      `solid_fraction`: each paste particle stands for its own volume / solid_fraction of paste
//      (the rest of the paste is the interstitial space the paste bonds bridge);
//   3. RSA: largest first, each at `rsa_scale` × its radius, at random positions inside the box
//      that overlap neither sand nor placed paste (up to `rsa_attempts` tries; a particle that
//      finds no room keeps its last try and is counted);
//   4. growth with soft-overlap relaxation: the paste radii grow to full size in `growth_stages`
//      steps; after each, overlaps are removed by Jacobi projection (each overlapping pair is
//      pushed apart along its normal, split in inverse proportion to the particles' volumes,
//      so sand grains move little; the box walls fixed) with the pairs from the World's neighbour search (make_neighbor_search():
//      the multi-level grid at wide size ratios) until the largest overlap is below
//      `overlap_tolerance` × the smaller radius. A stage that does not get there within
//      `relax_iterations` stops the growth at the last stage that did (the report says so);
//   4b. the overlaps left are removed by shrinking particles (paste-sand: the paste one by the
//      whole overlap; paste-paste and sand-sand: both by half), so the bonded specimen starts
//      free of stress;
//   5. the grains sorted along the Morton curve (memory locality), families carried along.
// The "short equilibration" is the cube test's settling of the bonded specimen (cube_specimen).
// Simplifications (stated): one contact law for every family; the dilated sand has no contacts
// and no locked-in stress (it floats in paste); the fill is serial (deterministic by
// construction: no threads).
#include <cstdint>
#include <optional>
#include <stdexcept>
#include <string>

#include "experiments/specimen/genesis.hpp"
#include "experiments/paste/paste_mix.hpp"
#include "experiments/paste/paste_spec.hpp"

namespace gradem::exp {

/// What the fill did (printed by `gradem specimen`, written into macro.json).
struct PasteReport {
    std::size_t sand_count = 0, paste_count = 0;
    double sand_d_min = 0, sand_d_max = 0;      ///< [m]
    double paste_d_min = 0, paste_d_max = 0;    ///< [m]
    double size_ratio = 0;             ///< largest sand / smallest paste diameter [-]
    double dilation = 1;               ///< linear scale applied to the sand packing [-]
    double packed_sand_fraction = 0;   ///< sand solid fraction before dilation [-]
    double sand_fraction = 0;          ///< after dilation (= mix.sand up to round-off) [-]
    double paste_particle_fraction = 0;  ///< paste particle volume / box [-]
    double paste_fraction = 0;         ///< paste represented: particle fraction / solid_fraction [-]
    double mix_sand_fraction = 0, mix_paste_fraction = 0, mix_air_fraction = 0;  ///< the mix design [-]
    double void_fraction = 0;          ///< 1 - sand - paste represented [-]
    double growth_reached = 0;         ///< radius scale the growth reached (1: full size) [-]
    double max_overlap_sand = 0;       ///< largest paste-sand overlap / smaller radius [-]
    double max_overlap = 0;            ///< largest overlap of any pair / smaller radius [-] (after the shrink: 0)
    double max_shrink = 0;             ///< largest relative radius cut that removed the overlaps left [-]
    std::size_t rsa_failures = 0;      ///< particles RSA found no free place for
    std::int64_t relax_sweeps = 0;     ///< relaxation sweeps in total
    double estimated_bytes = 0;        ///< memory estimate of the bonded specimen [B]
    double seconds = 0;                ///< wall-clock time of the fill [s]
};

/// A specimen that would not fit the machine's memory (the message holds the estimate).
class PasteMemoryError : public std::invalid_argument {
public:
    using std::invalid_argument::invalid_argument;
};

/// The cement size distribution of step 2, as a gradation curve (0.3 µm .. 300 µm).
lab::GradationCurve cement_size_curve();

/// Expected paste particle count for a paste volume [m³] (mass sampling of step 2).
double expected_paste_count(const PasteSpec& spec, double paste_particle_volume);

/// Bytes a bonded specimen of n particles needs (the World's arrays, bonds, neighbour search;
/// a stated per-particle figure).
double estimated_specimen_bytes(double particles);

/// Physical memory of this machine [B].
double physical_memory_bytes();

/// Steps 1-5 on a converged sand packing. Throws std::invalid_argument (paste cannot fill the
/// pore space: messages name the fractions) and PasteMemoryError (with the estimate) before
/// allocating.
Packing fill_paste(const Packing& sand, const MixFractions& mix, const PasteSpec& spec, std::uint64_t seed,
                   PasteReport& report);

/// A few lines: counts, size ratio, volume fractions placed vs the mix design, overlaps.
std::string describe(const PasteReport& report);

}  // namespace gradem::exp
