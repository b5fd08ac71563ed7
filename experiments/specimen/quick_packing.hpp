#pragma once
// A fast dense polydisperse packing for benchmarks and smoke runs: jittered rock-salt sites
// (large grains on a face-centred-cubic lattice, small ones in its octahedral holes), radii
// drawn per kind and shrunk where needed so that no two spheres overlap, then bonded at the smallest gaps so every particle has about
// `bonded_coordination` bonded neighbours. It costs O(N) and builds 1.2 million spheres in
// seconds, which DEM genesis (servo-controlled compaction) cannot; it is NOT a specimen for
// calibration: that is genesis' job (experiments/specimen/genesis.hpp, docs/genesis.md).
#include <cstdint>

#include "core/particles.hpp"

namespace gradem::exp {

struct QuickPackingSpec {
    std::int64_t target_count = 20000;  ///< approximate number of spheres (8 m^3 sites)
    double max_radius = 0.3e-3;         ///< r_max [m]
    double radius_ratio = 3.0;          ///< r_max / r_min [-]
    double density = 2650.0;            ///< grain density [kg/m^3]
    double jitter = 0.05;               ///< site jitter as a fraction of r_max [-]
    double bonded_coordination = 5.0;   ///< mean bonds per particle x 2 [-]
    std::uint64_t seed = 1;
};

struct QuickPacking {
    ParticleSet particles;
    double edge = 0.0;         ///< cube edge of the site lattice [m]
    double bond_gap = 0.0;     ///< installation gap giving the requested coordination [m]
    double solid_fraction = 0.0;
};

QuickPacking make_quick_packing(const QuickPackingSpec& spec);

/// The number of spheres make_quick_packing() makes for `target_count`: the lattice has 8 m^3
/// sites, m = round(cbrt(target_count / 8)) >= 1 (216, 512, 1000, ..., 4096, ...).
std::int64_t quick_packing_count(std::int64_t target_count);

}  // namespace gradem::exp
