// Uniform cell grid (linked cells by counting sort). Cells have an edge of at least
// 2 R_max + max_gap, so every partner of a particle lies in its own or one of the 26
// neighbouring cells. The grid is capped at ~8 cells per particle so a stray particle far away
// cannot blow up memory; it only makes cells larger, never misses a pair.
#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

#include "core/neighbor_search.hpp"
#include "core/parallel.hpp"

namespace gradem {
namespace {

struct GridGeometry {
    Vec3 origin;
    double cell = 1.0;
    std::array<std::int64_t, 3> dims{1, 1, 1};

    std::int64_t coord(double v, double o, std::int64_t n) const {
        const auto c = static_cast<std::int64_t>(std::floor((v - o) / cell));
        return std::clamp<std::int64_t>(c, 0, n - 1);
    }
    std::array<std::int64_t, 3> cell_of(const Vec3& x) const {
        return {coord(x.x, origin.x, dims[0]), coord(x.y, origin.y, dims[1]),
                coord(x.z, origin.z, dims[2])};
    }
    std::int64_t index(const std::array<std::int64_t, 3>& c) const {
        return (c[2] * dims[1] + c[1]) * dims[0] + c[0];
    }
};

GridGeometry make_geometry(const std::vector<Vec3>& x, double cutoff) {
    Vec3 lo{std::numeric_limits<double>::max(), std::numeric_limits<double>::max(),
            std::numeric_limits<double>::max()};
    Vec3 hi = -1.0 * lo;
    for (const Vec3& p : x) {
        lo = {std::min(lo.x, p.x), std::min(lo.y, p.y), std::min(lo.z, p.z)};
        hi = {std::max(hi.x, p.x), std::max(hi.y, p.y), std::max(hi.z, p.z)};
    }
    GridGeometry g;
    g.origin = lo;
    const Vec3 extent = hi - lo;
    const double max_cells = 8.0 * static_cast<double>(x.size()) + 64.0;
    g.cell = cutoff;
    for (;;) {
        double total = 1.0;
        for (int k = 0; k < 3; ++k) total *= std::floor(extent[k] / g.cell) + 1.0;
        if (total <= max_cells) break;
        g.cell *= 1.25;
    }
    for (int k = 0; k < 3; ++k)
        g.dims[static_cast<std::size_t>(k)] = static_cast<std::int64_t>(extent[k] / g.cell) + 1;
    return g;
}

class CellGridSearch final : public NeighborSearch {
public:
    void find_pairs(const std::vector<Vec3>& x, const std::vector<double>& r, double max_gap,
                    std::vector<ParticlePair>& pairs) override {
        pairs.clear();
        const auto n = static_cast<std::int64_t>(x.size());
        if (n < 2) return;
        const double r_max = *std::max_element(r.begin(), r.end());
        const GridGeometry g = make_geometry(x, 2.0 * r_max + max_gap);
        bin_particles(x, g);
        collect_pairs(x, r, max_gap, g, pairs);
    }
    [[nodiscard]] std::string name() const override { return "cell-grid"; }

private:
    std::vector<std::int64_t> cell_of_;   // per particle
    std::vector<std::int64_t> cell_start_;  // CSR over cells
    std::vector<std::int32_t> sorted_;      // particle ids, grouped by cell, ascending in a cell

    void bin_particles(const std::vector<Vec3>& x, const GridGeometry& g) {
        const std::size_t n = x.size();
        const std::int64_t cells = g.dims[0] * g.dims[1] * g.dims[2];
        cell_of_.resize(n);
        cell_start_.assign(static_cast<std::size_t>(cells) + 1, 0);
        for (std::size_t i = 0; i < n; ++i) {
            cell_of_[i] = g.index(g.cell_of(x[i]));
            ++cell_start_[static_cast<std::size_t>(cell_of_[i]) + 1];
        }
        for (std::int64_t c = 0; c < cells; ++c)
            cell_start_[static_cast<std::size_t>(c + 1)] += cell_start_[static_cast<std::size_t>(c)];
        sorted_.resize(n);
        std::vector<std::int64_t> fill(cell_start_.begin(), cell_start_.end() - 1);
        for (std::size_t i = 0; i < n; ++i)
            sorted_[static_cast<std::size_t>(fill[static_cast<std::size_t>(cell_of_[i])]++)] =
                static_cast<std::int32_t>(i);
    }

    // Partners j > i of particle i, appended to `out` in ascending j.
    void partners_of(std::int32_t i, const std::vector<Vec3>& x, const std::vector<double>& r,
                     double max_gap, const GridGeometry& g, std::vector<ParticlePair>& out) const {
        const std::size_t first = out.size();
        const auto c = g.cell_of(x[static_cast<std::size_t>(i)]);
        for (std::int64_t dz = -1; dz <= 1; ++dz)
            for (std::int64_t dy = -1; dy <= 1; ++dy)
                for (std::int64_t dx = -1; dx <= 1; ++dx) {
                    const std::array<std::int64_t, 3> nc{c[0] + dx, c[1] + dy, c[2] + dz};
                    if (nc[0] < 0 || nc[1] < 0 || nc[2] < 0 || nc[0] >= g.dims[0] ||
                        nc[1] >= g.dims[1] || nc[2] >= g.dims[2])
                        continue;
                    const auto cell = static_cast<std::size_t>(g.index(nc));
                    for (std::int64_t k = cell_start_[cell]; k < cell_start_[cell + 1]; ++k) {
                        const std::int32_t j = sorted_[static_cast<std::size_t>(k)];
                        if (j <= i) continue;
                        const double reach = r[static_cast<std::size_t>(i)] +
                                             r[static_cast<std::size_t>(j)] + max_gap;
                        if (norm2(x[static_cast<std::size_t>(j)] - x[static_cast<std::size_t>(i)]) <=
                            reach * reach)
                            out.push_back({i, j});
                    }
                }
        std::sort(out.begin() + static_cast<std::ptrdiff_t>(first), out.end());
    }

    // Each thread takes a contiguous range of i; concatenating thread results in thread order
    // gives the list sorted by (i, j) whatever the thread count.
    void collect_pairs(const std::vector<Vec3>& x, const std::vector<double>& r, double max_gap,
                       const GridGeometry& g, std::vector<ParticlePair>& pairs) const {
        const auto n = static_cast<std::int64_t>(x.size());
        std::vector<std::vector<ParticlePair>> per_thread(static_cast<std::size_t>(thread_count()));
#pragma omp parallel
        {
            const int t = thread_index();
            const int nt = team_size();
            const std::int64_t begin = n * t / nt, end = n * (t + 1) / nt;
            auto& out = per_thread[static_cast<std::size_t>(t)];
            out.reserve(static_cast<std::size_t>((end - begin) * 4));
            for (std::int64_t i = begin; i < end; ++i)
                partners_of(static_cast<std::int32_t>(i), x, r, max_gap, g, out);
        }
        std::size_t total = 0;
        for (const auto& v : per_thread) total += v.size();
        pairs.reserve(total);
        for (const auto& v : per_thread) pairs.insert(pairs.end(), v.begin(), v.end());
    }
};

}  // namespace

std::unique_ptr<NeighborSearch> make_cell_grid_search() {
    return std::make_unique<CellGridSearch>();
}

}  // namespace gradem
