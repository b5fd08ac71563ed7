#pragma once
// Dense random placement by collective rearrangement (mechanical contraction; Jodrey & Tory
// 1985 style): all grains are dropped at random positions inside the cubic vessel, overlapping,
// and pushed apart geometrically - every overlapping pair moves apart along its normal, the
// smaller grain more - until the largest overlap is a small fraction of the grain size. The
// vessel is then shrunk step by step (grain sizes fixed) until the grains jam. Geometry only,
// no dynamics: a few thousand cheap sweeps give a jammed random packing that DEM only has to
// bring to its stress state, instead of a long dynamic compaction from a loose gas.
#include <cstdint>
#include <vector>

#include "core/vec3.hpp"

namespace gradem::exp {

struct DensePlacement {
    std::vector<Vec3> position;   ///< [m], grains inside [0, edge]^3
    std::vector<double> radius;   ///< [m]
    double edge = 0.0;            ///< vessel edge at jamming [m]
    double max_overlap = 0.0;     ///< largest remaining overlap / smaller radius [-]
    int sweeps = 0;
};

/// Places spheres of the given diameters [m] in a cube of starting edge `edge` [m], relaxes
/// overlaps to below `tolerance` x the smaller radius of each pair (walls included) and shrinks
/// the cube until the grains jam. Deterministic in `seed`, independent of the thread count.
DensePlacement place_dense(const std::vector<double>& diameters, double edge, std::uint64_t seed,
                           double tolerance = 1.0e-3);

}  // namespace gradem::exp
