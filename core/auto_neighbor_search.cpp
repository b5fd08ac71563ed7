// Automatic broad phase: the uniform cell grid for narrow size distributions (its dense
// cells are the fastest there) and the multi-level grid for wide ones, decided on each call
// from the current radii. Both searches return the same sorted pair set.
#include <algorithm>

#include "core/neighbor_search.hpp"

namespace gradem {
namespace {

class AutoNeighborSearch final : public NeighborSearch {
public:
    void find_pairs(const std::vector<Vec3>& x, const std::vector<double>& r, double max_gap,
                    std::vector<ParticlePair>& pairs) override {
        choose(r).find_pairs(x, r, max_gap, pairs);
    }
    [[nodiscard]] std::string name() const override { return "auto"; }

private:
    std::unique_ptr<NeighborSearch> cell_grid_ = make_cell_grid_search();
    std::unique_ptr<NeighborSearch> multilevel_ = make_multilevel_grid_search();

    NeighborSearch& choose(const std::vector<double>& r) const {
        if (r.empty()) return *cell_grid_;
        const auto [lo, hi] = std::minmax_element(r.begin(), r.end());
        return *hi > kMultilevelRadiusRatio * *lo ? *multilevel_ : *cell_grid_;
    }
};

}  // namespace

std::unique_ptr<NeighborSearch> make_neighbor_search() {
    return std::make_unique<AutoNeighborSearch>();
}

}  // namespace gradem
