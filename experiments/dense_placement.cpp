#include "experiments/dense_placement.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "core/neighbor_search.hpp"
#include "core/random.hpp"

namespace gradem::exp {
namespace {

// One Jacobi sweep: displacement of every grain from its overlaps with neighbours and walls.
// Returns the largest relative overlap seen.
double relax_sweep(std::vector<Vec3>& x, const std::vector<double>& r, double edge,
                   const std::vector<ParticlePair>& pairs, std::vector<Vec3>& shift) {
    std::fill(shift.begin(), shift.end(), Vec3{});
    double worst = 0.0;
    for (const ParticlePair& p : pairs) {
        const auto i = static_cast<std::size_t>(p.i), j = static_cast<std::size_t>(p.j);
        const Vec3 d = x[j] - x[i];
        const double dist = norm(d), overlap = r[i] + r[j] - dist;
        if (overlap <= 0.0) continue;
        worst = std::max(worst, overlap / std::min(r[i], r[j]));
        const Vec3 n = dist > 0.0 ? (1.0 / dist) * d : Vec3{1, 0, 0};
        const double vi = r[i] * r[i] * r[i], vj = r[j] * r[j] * r[j];
        shift[i] -= (overlap * vj / (vi + vj)) * n;  // the smaller grain moves more
        shift[j] += (overlap * vi / (vi + vj)) * n;
    }
    for (std::size_t i = 0; i < x.size(); ++i) {
        for (int a = 0; a < 3; ++a) {
            const double lo = x[i][a] - r[i], hi = x[i][a] + r[i] - edge;
            const double push = lo < 0.0 ? -lo : (hi > 0.0 ? -hi : 0.0);
            if (push != 0.0) worst = std::max(worst, std::fabs(push) / r[i]);
            (a == 0 ? shift[i].x : (a == 1 ? shift[i].y : shift[i].z)) += push;
        }
        x[i] += 0.6 * shift[i];  // under-relaxed: neighbours push each other too
    }
    return worst;
}

}  // namespace

namespace {

// Relaxes overlaps below `tolerance`; false if `max_sweeps` do not suffice (jammed).
bool relax(std::vector<Vec3>& x, const std::vector<double>& r, double edge, double tolerance,
           int max_sweeps, NeighborSearch& search, std::vector<ParticlePair>& pairs,
           std::vector<Vec3>& shift, DensePlacement& stats) {
    const double r_max = *std::max_element(r.begin(), r.end());
    for (int sweep = 0; sweep < max_sweeps; ++sweep) {
        if (sweep % 10 == 0) search.find_pairs(x, r, 0.2 * r_max, pairs);
        stats.max_overlap = relax_sweep(x, r, edge, pairs, shift);
        ++stats.sweeps;
        if (stats.max_overlap < tolerance) return true;
    }
    return false;
}

}  // namespace

DensePlacement place_dense(const std::vector<double>& diameters, double edge, std::uint64_t seed,
                           double tolerance) {
    if (diameters.empty()) throw std::invalid_argument("place_dense: no grains");
    DensePlacement out;
    out.radius.resize(diameters.size());
    std::transform(diameters.begin(), diameters.end(), out.radius.begin(), [](double d) { return 0.5 * d; });
    SplitMix64 rng(seed);
    out.position.resize(diameters.size());
    for (std::size_t i = 0; i < out.position.size(); ++i) {
        const double r = out.radius[i];
        out.position[i] = {rng.uniform(r, edge - r), rng.uniform(r, edge - r), rng.uniform(r, edge - r)};
    }
    auto search = make_cell_grid_search();
    std::vector<ParticlePair> pairs;
    std::vector<Vec3> shift(out.position.size());
    // 1. Relax at the requested size; if the grains do not fit, give them 1 % more room.
    while (!relax(out.position, out.radius, edge, tolerance, 3000, *search, pairs, shift, out)) {
        for (Vec3& p : out.position) p *= 1.01;
        edge *= 1.01;
    }
    // 2. Shrink the vessel (grain sizes fixed) until the grains jam: a shrink the relaxation
    //    cannot absorb is undone and retried at half the size, down to 0.01 %.
    std::vector<Vec3> saved = out.position;
    for (double shrink = 0.005; shrink > 1e-4;) {
        for (Vec3& p : out.position) p *= 1.0 - shrink;
        if (relax(out.position, out.radius, edge * (1.0 - shrink), tolerance, 1500, *search, pairs, shift, out)) {
            edge *= 1.0 - shrink;
            saved = out.position;
        } else {
            out.position = saved;
            shrink *= 0.5;
        }
    }
    out.position = saved;
    out.edge = edge;
    return out;
}

}  // namespace gradem::exp
