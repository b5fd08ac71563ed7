#pragma once
// Broad phase: which particle pairs are close enough to interact. The World asks for all pairs
// with a gap no larger than `max_gap` (the Verlet skin) and keeps the answer until particles
// have moved far enough to invalidate it. Implementations are swappable: the uniform cell grid
// suits narrow size distributions; the multi-level grid (Ogarko & Luding 2012,
// core/multilevel_grid.cpp) stays O(N) at size ratios of 50 and more; make_neighbor_search()
// (the World's default) picks one per call. All return the same pairs in the same order.
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "core/vec3.hpp"

namespace gradem {

struct ParticlePair {
    std::int32_t i = -1, j = -1;  ///< i < j
    friend bool operator<(const ParticlePair& a, const ParticlePair& b) {
        return a.i < b.i || (a.i == b.i && a.j < b.j);
    }
    friend bool operator==(const ParticlePair& a, const ParticlePair& b) {
        return a.i == b.i && a.j == b.j;
    }
};

class NeighborSearch {
public:
    virtual ~NeighborSearch() = default;
    /// Replaces `pairs` by every pair (i < j) with |x_i - x_j| - r_i - r_j <= max_gap, sorted by
    /// (i, j). The result must not depend on the number of threads.
    virtual void find_pairs(const std::vector<Vec3>& position, const std::vector<double>& radius,
                            double max_gap, std::vector<ParticlePair>& pairs) = 0;
    [[nodiscard]] virtual std::string name() const = 0;
};

/// Uniform cell grid with cell edge >= 2 R_max + max_gap; O(N) for bounded size ratios.
std::unique_ptr<NeighborSearch> make_cell_grid_search();

/// Multi-level grid (Ogarko & Luding 2012), levels chosen from the size distribution
/// (core/multilevel_grid.cpp); O(N) at any size ratio.
std::unique_ptr<NeighborSearch> make_multilevel_grid_search();

/// Radius ratio R_max / R_min above which the automatic search uses the multi-level grid.
inline constexpr double kMultilevelRadiusRatio = 3.0;

/// The default: on every call, the cell grid when R_max / R_min <= kMultilevelRadiusRatio,
/// else the multi-level grid. Both return the same pairs, so the choice never changes results.
std::unique_ptr<NeighborSearch> make_neighbor_search();

}  // namespace gradem
