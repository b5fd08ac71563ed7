#include "experiments/virtual_tests/gauges.hpp"

#include <algorithm>
#include <stdexcept>

namespace gradem::exp {

Gauges::Gauges(const ParticleSet& particles, const GaugeGeometry& geometry)
    : axial_(select(particles, geometry, 2)), across_x_(select(particles, geometry, 0)),
      across_y_(select(particles, geometry, 1)) {}

Gauges::Pair Gauges::select(const ParticleSet& p, const GaugeGeometry& g, int axis) {
    const Vec3 centre = 0.5 * (g.lo + g.hi);
    const Vec3 size = g.hi - g.lo;
    Pair pair;
    pair.axis = axis;
    const double half_gauge = 0.5 * g.gauge_length_fraction * size[axis];
    const double half_slab = 0.5 * g.slab_fraction * size[axis];
    for (std::size_t i = 0; i < p.size(); ++i) {
        const Vec3 x = p.position[i];
        bool in_core = true;
        for (int other = 0; other < 3; ++other)
            if (other != axis && std::abs(x[other] - centre[other]) > 0.5 * g.core_fraction * size[other])
                in_core = false;
        if (!in_core) continue;
        const double along = x[axis] - centre[axis];
        if (std::abs(along - half_gauge) <= half_slab) pair.high.ids.push_back(static_cast<std::int32_t>(i));
        if (std::abs(along + half_gauge) <= half_slab) pair.low.ids.push_back(static_cast<std::int32_t>(i));
    }
    if (pair.low.ids.empty() || pair.high.ids.empty())
        throw std::invalid_argument("gauges: a gauge slab holds no particle; increase test.slab_fraction or the specimen size");
    pair.low.reference_mean = mean_coordinate(p, pair.low, axis);
    pair.high.reference_mean = mean_coordinate(p, pair.high, axis);
    pair.length = pair.high.reference_mean - pair.low.reference_mean;
    return pair;
}

double Gauges::mean_coordinate(const ParticleSet& p, const Slab& s, int axis) {
    double sum = 0.0;
    for (std::int32_t i : s.ids) sum += p.position[static_cast<std::size_t>(i)][axis];
    return sum / static_cast<double>(s.ids.size());
}

// Change of the slab distance over its reference length (extension positive).
double Gauges::strain(const ParticleSet& p, const Pair& pair) {
    const double now = mean_coordinate(p, pair.high, pair.axis) - mean_coordinate(p, pair.low, pair.axis);
    return (now - pair.length) / pair.length;
}

double Gauges::axial_strain(const ParticleSet& p) const { return -strain(p, axial_); }

double Gauges::lateral_strain(const ParticleSet& p) const {
    return 0.5 * (strain(p, across_x_) + strain(p, across_y_));
}

std::size_t Gauges::smallest_slab() const {
    std::size_t m = axial_.low.ids.size();
    for (const Pair* pr : {&axial_, &across_x_, &across_y_})
        m = std::min({m, pr->low.ids.size(), pr->high.ids.size()});
    return m;
}

}  // namespace gradem::exp
