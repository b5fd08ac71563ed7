#pragma once
// Multi-level (hierarchical) neighbour grid for wide size ratios (Ogarko & Luding 2012, CPC
// 183:931; level choice after Krijgsman, Ogarko & Luding 2014, Comp. Part. Mech. 1:357).
// The search itself is make_multilevel_grid_search() in core/neighbor_search.hpp; this header
// exposes the analytic level choice so it can be tested and printed on its own.
#include <vector>

namespace gradem {

/// Level bounds [m], finest first. Particle i belongs to the first level whose bound is
/// >= 2 r_i + max_gap; the search then sizes each level's cells by 2 r_max,level + max_gap of
/// the particles it actually holds (<= the bound). The last bound is 2 R_max + max_gap.
struct LevelPlan {
    std::vector<double> cell;    ///< upper bound of 2 r + max_gap per level [m], ascending
    double estimated_cost = 0;   ///< model cost per particle (cell visits + distance checks)
};

/// Chooses the number of levels (1..8) and their cell edges from the radius distribution
/// [m], the skin `max_gap` [m] and the volume `box_volume` [m^3] the particles fill, by
/// minimising the cost model described in core/multilevel_grid.cpp.
LevelPlan plan_levels(const std::vector<double>& radius, double max_gap, double box_volume);

}  // namespace gradem
