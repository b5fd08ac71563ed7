#pragma once
// Virtual extensometers (docs/virtual_tests.md "Gauges"): slabs of particles in the central part of the cube whose
// mean displacement stands in for the knife edges of a clip-on gauge. Axial gauge strain is
//     eps_g = -(w_top - w_bottom) / g      (compression positive),
// with w the mean axial displacement of the particles of each slab, centred at +-g/2 about
// mid-height; lateral strain is the same measurement across x and across y, averaged
// (positive = expansion). Slabs take only particles inside the central `core` of the other two
// directions, away from the free faces and the platen-restrained ends.
#include <cstdint>
#include <vector>

#include "core/particles.hpp"

namespace gradem::exp {

struct GaugeGeometry {
    Vec3 lo, hi;                        ///< specimen bounding box [m]
    double gauge_length_fraction = 0.5; ///< g / edge [-]
    double slab_fraction = 0.1;         ///< slab thickness / edge [-]
    double core_fraction = 0.6;         ///< central width used across the slab / edge [-]
};

class Gauges {
public:
    /// Picks the slab particles from the current positions (the reference state).
    Gauges(const ParticleSet& particles, const GaugeGeometry& geometry);
    /// Axial gauge strain (compression positive) and lateral strain (expansion positive).
    [[nodiscard]] double axial_strain(const ParticleSet& particles) const;
    [[nodiscard]] double lateral_strain(const ParticleSet& particles) const;
    [[nodiscard]] std::size_t smallest_slab() const;

private:
    struct Slab {
        std::vector<std::int32_t> ids;
        double reference_mean = 0.0;  ///< mean coordinate along the gauge axis at selection [m]
    };
    struct Pair {
        Slab low, high;
        int axis = 2;
        double length = 0.0;  ///< distance between the slab centres at selection [m]
    };
    Pair axial_, across_x_, across_y_;

    static Pair select(const ParticleSet& p, const GaugeGeometry& g, int axis);
    static double mean_coordinate(const ParticleSet& p, const Slab& s, int axis);
    static double strain(const ParticleSet& p, const Pair& pair);
};

}  // namespace gradem::exp
