#pragma once
// The state the fused contact + parallel-bond pass (core/world_pairs.cpp) reads and writes,
// kept in structure-of-arrays batches of kPairLanes consecutive Verlet pairs, so the pass's
// vector kernel loads and stores it in place: no copy into lanes before the arithmetic and no
// copy back after it (the copies cost three times the arithmetic in the array-of-structures
// layout; bench/README.md). Batch b holds pairs [b kPairLanes, (b + 1) kPairLanes) of the
// World's pair list, lane l pair b kPairLanes + l.
//
// While the batches are current they, not World's pair and bond records, hold the contact shear
// forces and the intact bonds' forces and moments; World writes them back into the records
// before anything reads or rebuilds those (World::write_back_pair_batches) and rebuilds the
// batches after the pair list, the bonds or their constants changed. Everything else of a bond
// (its ends, state, strengths as drawn) stays in its record; the lanes keep copies of what the
// kernel needs. A lane without an intact bond holds a dummy bond (unit strengths, radius and
// stiffness, zero friction and moment factor) whose arithmetic is harmless and whose results the
// pass ignores; lanes past the end of the pair list are such lanes between particle 0 and itself.
#include <cstddef>
#include <cstdint>

namespace gradem {

inline constexpr int kPairLanes = 32;

struct PairBatch {
    std::int32_t i[kPairLanes], j[kPairLanes];  ///< the pair's particles, i < j
    std::int32_t bond[kPairLanes];              ///< its intact bond, -1: none (or broken)
    double shear[3][kPairLanes];                ///< the linear contact's shear force on j [N]
    // The bond: forces and moments on j (ParallelBond's), its strengths, section and stiffness
    // (BondConstants) and its family's tan φ̄ and β̄.
    double normal_force[kPairLanes];            ///< F̄_n, tension positive [N]
    double shear_force[3][kPairLanes];          ///< F̄_s [N]
    double twist_moment[kPairLanes];            ///< M̄_t [N m]
    double bend_moment[3][kPairLanes];          ///< M̄_b [N m]
    double tensile_strength[kPairLanes];        ///< σ̄_c [Pa]
    double cohesion[kPairLanes];                ///< c̄ [Pa]
    double radius[kPairLanes], inv_radius[kPairLanes];  ///< R̄ [m], 1/R̄ [1/m]
    double kn[kPairLanes], ks[kPairLanes];      ///< k̄_n, k̄_s [Pa/m]
    double tan_phi[kPairLanes];                 ///< tan φ̄ [-]
    double moment_factor[kPairLanes];           ///< β̄ [-]
};

/// Batches needed for n pairs.
inline std::size_t pair_batch_count(std::size_t n) { return (n + kPairLanes - 1) / kPairLanes; }

}  // namespace gradem
