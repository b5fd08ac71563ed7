#include "experiments/specimen/quick_packing.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "core/neighbor_search.hpp"
#include "core/random.hpp"

namespace gradem::exp {
namespace {

// Rock-salt sites of an m x m x m cell block: face-centred-cubic sites for large grains (nearest
// neighbours 2 r_max apart) and the octahedral holes between them (room for 0.414 r_max) for
// small ones, jittered. Every site carries its largest admissible radius.
struct Site {
    Vec3 x;
    bool large = true;
};

std::vector<Site> rock_salt_sites(std::int64_t m, double r_max, double jitter, SplitMix64& rng) {
    const double a = 2.0 * std::sqrt(2.0) * r_max;  // cubic cell edge
    const Vec3 fcc[4] = {{0, 0, 0}, {0.5, 0.5, 0}, {0.5, 0, 0.5}, {0, 0.5, 0.5}};
    const Vec3 octahedral[4] = {{0.5, 0, 0}, {0, 0.5, 0}, {0, 0, 0.5}, {0.5, 0.5, 0.5}};
    std::vector<Site> sites;
    sites.reserve(static_cast<std::size_t>(8 * m * m * m));
    for (std::int64_t k = 0; k < m; ++k)
        for (std::int64_t j = 0; j < m; ++j)
            for (std::int64_t i = 0; i < m; ++i)
                for (int s = 0; s < 8; ++s) {
                    const Vec3 cell{static_cast<double>(i), static_cast<double>(j), static_cast<double>(k)};
                    const Vec3 jit{rng.uniform(-1, 1), rng.uniform(-1, 1), rng.uniform(-1, 1)};
                    const Vec3 b = s < 4 ? fcc[s] : octahedral[s - 4];
                    sites.push_back({a * (cell + b) + (jitter * r_max) * jit + Vec3{r_max, r_max, r_max}, s < 4});
                }
    return sites;
}

// Adjacency (CSR) of the site pairs closer than 2 r_max (1 + slack).
struct Adjacency {
    std::vector<std::int64_t> start;
    std::vector<std::int32_t> other;
};

Adjacency site_adjacency(const std::vector<Vec3>& x, double r_max) {
    std::vector<ParticlePair> pairs;
    const std::vector<double> r(x.size(), r_max);
    make_cell_grid_search()->find_pairs(x, r, 0.5 * r_max, pairs);
    Adjacency adj;
    adj.start.assign(x.size() + 1, 0);
    for (const ParticlePair& p : pairs) {
        ++adj.start[static_cast<std::size_t>(p.i) + 1];
        ++adj.start[static_cast<std::size_t>(p.j) + 1];
    }
    for (std::size_t i = 0; i < x.size(); ++i) adj.start[i + 1] += adj.start[i];
    adj.other.resize(static_cast<std::size_t>(adj.start.back()));
    std::vector<std::int64_t> fill(adj.start.begin(), adj.start.end() - 1);
    for (const ParticlePair& p : pairs) {
        adj.other[static_cast<std::size_t>(fill[static_cast<std::size_t>(p.i)]++)] = p.j;
        adj.other[static_cast<std::size_t>(fill[static_cast<std::size_t>(p.j)]++)] = p.i;
    }
    return adj;
}

// Radii in random order: large sites draw from [0.8, 1] r_max, small ones from
// [r_min, 0.414 r_max]; each is then shrunk to touch (not cross) its assigned neighbours and to
// leave r_min for the unassigned ones.
std::vector<double> assign_radii(const std::vector<Site>& sites, const std::vector<Vec3>& x,
                                 const Adjacency& adj, const QuickPackingSpec& spec, SplitMix64& rng) {
    const double r_min = spec.max_radius / spec.radius_ratio;
    std::vector<std::int32_t> order(x.size());
    for (std::size_t i = 0; i < order.size(); ++i) order[i] = static_cast<std::int32_t>(i);
    for (std::size_t i = order.size(); i > 1; --i)
        std::swap(order[i - 1], order[static_cast<std::size_t>(rng.next() % i)]);
    std::vector<double> r(x.size(), 0.0);
    for (std::int32_t i : order) {
        const auto ui = static_cast<std::size_t>(i);
        double room = spec.max_radius;
        for (std::int64_t e = adj.start[ui]; e < adj.start[ui + 1]; ++e) {
            const auto j = static_cast<std::size_t>(adj.other[static_cast<std::size_t>(e)]);
            const double d = norm(x[j] - x[ui]);
            room = std::min(room, r[j] > 0.0 ? d - r[j] : d - r_min);
        }
        const double draw = sites[ui].large ? rng.uniform(0.8 * spec.max_radius, spec.max_radius)
                                            : rng.uniform(r_min, std::max(r_min, 0.414 * spec.max_radius));
        r[ui] = std::max(r_min, std::min(room, draw));
    }
    return r;
}

// Installation gap such that the pairs with gap <= it give the requested coordination.
double gap_for_coordination(const std::vector<Vec3>& x, const std::vector<double>& r,
                            double coordination, double r_max) {
    std::vector<ParticlePair> pairs;
    make_cell_grid_search()->find_pairs(x, r, r_max, pairs);
    std::vector<double> gaps;
    gaps.reserve(pairs.size());
    for (const ParticlePair& p : pairs) {
        const auto i = static_cast<std::size_t>(p.i), j = static_cast<std::size_t>(p.j);
        gaps.push_back(norm(x[j] - x[i]) - r[i] - r[j]);
    }
    const auto want = static_cast<std::size_t>(0.5 * coordination * static_cast<double>(x.size()));
    if (want == 0 || gaps.empty()) return 0.0;
    const std::size_t k = std::min(want, gaps.size()) - 1;
    std::nth_element(gaps.begin(), gaps.begin() + static_cast<std::ptrdiff_t>(k), gaps.end());
    return std::max(0.0, gaps[k]);
}

// Rock-salt cells per edge for about `target_count` spheres (8 sites a cell).
std::int64_t lattice_cells(std::int64_t target_count) {
    return std::max<std::int64_t>(1, std::llround(std::cbrt(static_cast<double>(target_count) / 8.0)));
}

}  // namespace

std::int64_t quick_packing_count(std::int64_t target_count) {
    const std::int64_t m = lattice_cells(target_count);
    return 8 * m * m * m;
}

QuickPacking make_quick_packing(const QuickPackingSpec& spec) {
    if (spec.target_count < 4) throw std::invalid_argument("QuickPackingSpec::target_count < 4");
    if (!(spec.max_radius > 0.0)) throw std::invalid_argument("QuickPackingSpec::max_radius <= 0");
    if (!(spec.radius_ratio >= 1.0)) throw std::invalid_argument("QuickPackingSpec::radius_ratio < 1");
    SplitMix64 rng(spec.seed);
    const std::int64_t m = lattice_cells(spec.target_count);
    const std::vector<Site> sites = rock_salt_sites(m, spec.max_radius, spec.jitter, rng);
    std::vector<Vec3> x(sites.size());
    for (std::size_t i = 0; i < sites.size(); ++i) x[i] = sites[i].x;
    const std::vector<double> radii = assign_radii(sites, x, site_adjacency(x, spec.max_radius), spec, rng);
    QuickPacking out;
    double solid = 0.0;
    for (std::size_t i = 0; i < sites.size(); ++i) {
        out.particles.add(x[i], radii[i], spec.density);
        solid += 4.0 / 3.0 * kPi * radii[i] * radii[i] * radii[i];
    }
    out.edge = static_cast<double>(m) * 2.0 * std::sqrt(2.0) * spec.max_radius;
    out.solid_fraction = solid / (out.edge * out.edge * out.edge);
    out.bond_gap = gap_for_coordination(x, radii, spec.bonded_coordination, spec.max_radius);
    return out;
}

}  // namespace gradem::exp
