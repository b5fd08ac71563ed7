// Verlet pair list with skin: rebuilt when any particle has moved more than half the skin
// since the last build (or a wall has moved enough to matter), so no pair can come into
// contact unseen between rebuilds. Pairs of acting bonds (bond_acts) are always kept, however far apart.
// Shear-force histories are carried over by merging the old and new sorted lists.
#include <algorithm>
#include <cmath>

#include "core/parallel.hpp"
#include "core/world.hpp"

namespace gradem {

bool World::needs_rebuild() const {
    if (rebuild_needed_) return true;
    double wall_shift = 0.0;
    for (const Vec3& s : wall_shift_since_rebuild_) wall_shift = std::max(wall_shift, norm(s));
    // Two grains that each grew by g and moved by d close their gap by at most 2 (d + g).
    const double d = std::sqrt(max_displacement_) + radius_growth_since_rebuild_;
    return 2.0 * d > skin_ || d + wall_shift > skin_;
}

void World::rebuild_neighbors() {
    write_back_pair_batches();  // the pair list changes: the batches' state back into the records first
    pair_batches_current_ = false;
    contact_pairs_stale_ = true;
    std::vector<ParticlePair> found;
    search_->find_pairs(particles_.position, particles_.radius, skin_, found);
    merge_pairs(found);
    build_incidence();
    build_wall_contacts();
    position_at_rebuild_ = particles_.position;
    wall_shift_since_rebuild_.assign(walls_.size(), Vec3{});
    max_displacement_ = 0.0;
    radius_growth_since_rebuild_ = 0.0;
    rebuild_needed_ = false;
    ++profile_.rebuilds;
    if (sim_.time_step == 0.0) dt_ = sim_.time_step_safety * critical_time_step();
}

// New pair list = (found pairs) ∪ (pairs of acting bonds: bond_acts), sorted; shear history and bond links
// carried over from the old list by a three-way merge on (i, j).
void World::merge_pairs(const std::vector<ParticlePair>& found) {
    std::vector<Pair> merged;
    merged.reserve(found.size() + bonds_.size() / 8);
    std::size_t f = 0, b = 0, o = 0;
    auto next_bond = [&]() {
        while (b < bonds_.size() && !bond_acts(bonds_[b])) {
            bonds_[b].slot = -1;
            ++b;
        }
    };
    next_bond();
    while (f < found.size() || b < bonds_.size()) {
        ParticlePair key;
        const bool take_found = f < found.size() &&
                                (b >= bonds_.size() || !(ParticlePair{bonds_[b].i, bonds_[b].j} < found[f]));
        key = take_found ? found[f] : ParticlePair{bonds_[b].i, bonds_[b].j};
        Pair p;
        p.i = key.i;
        p.j = key.j;
        if (b < bonds_.size() && bonds_[b].i == key.i && bonds_[b].j == key.j) {
            p.bond = static_cast<std::int32_t>(b);
            bonds_[b].slot = static_cast<std::int32_t>(merged.size());
            ++b;
            next_bond();
        }
        if (take_found) ++f;
        while (o < pairs_.size() && ParticlePair{pairs_[o].i, pairs_[o].j} < key) ++o;
        if (o < pairs_.size() && pairs_[o].i == key.i && pairs_[o].j == key.j)
            p.shear_force = pairs_[o].shear_force;
        merged.push_back(p);
    }
    pairs_.swap(merged);
    pair_out_.assign(pairs_.size(), PairOutput{});  // as the pairs are new, so are their slots: none stale
    pair_out_stale_ = false;
    force_owner_team_ = 0;  // the pass's shares hold other pairs now
    unowned_next_pass_.clear();  // the owners built anew know the released joints
}

// CSR: for each particle the pairs it belongs to, in pair order (fixed gather order).
void World::build_incidence() {
    const std::size_t n = particles_.size();
    incidence_start_.assign(n + 1, 0);
    for (const Pair& p : pairs_) {
        ++incidence_start_[static_cast<std::size_t>(p.i) + 1];
        ++incidence_start_[static_cast<std::size_t>(p.j) + 1];
    }
    for (std::size_t i = 0; i < n; ++i) incidence_start_[i + 1] += incidence_start_[i];
    incidence_.resize(static_cast<std::size_t>(incidence_start_[n]));
    std::vector<std::int32_t> fill(incidence_start_.begin(), incidence_start_.end() - 1);
    for (std::size_t k = 0; k < pairs_.size(); ++k) {
        const Pair& p = pairs_[k];
        const auto slot = static_cast<std::int32_t>(k);
        incidence_[static_cast<std::size_t>(fill[static_cast<std::size_t>(p.i)]++)] = {slot, ~p.j};
        incidence_[static_cast<std::size_t>(fill[static_cast<std::size_t>(p.j)]++)] = {slot, p.i};
    }
}

// Wall contacts: every (particle, wall) with gap <= skin, sorted by particle then wall.
void World::build_wall_contacts() {
    const std::size_t n = particles_.size();
    std::vector<WallContact> fresh;
    std::size_t o = 0;
    wall_start_.assign(n + 1, 0);
    for (std::size_t i = 0; i < n; ++i) {
        for (std::size_t w = 0; w < walls_.size(); ++w) {
            const Wall& wall = walls_[w];
            const double gap = dot(wall.normal, particles_.position[i] - wall.point) - particles_.radius[i];
            if (gap > skin_) continue;
            WallContact c;
            c.particle = static_cast<std::int32_t>(i);
            c.wall = static_cast<std::int32_t>(w);
            while (o < wall_contacts_.size() &&
                   (wall_contacts_[o].particle < c.particle ||
                    (wall_contacts_[o].particle == c.particle && wall_contacts_[o].wall < c.wall)))
                ++o;
            if (o < wall_contacts_.size() && wall_contacts_[o].particle == c.particle &&
                wall_contacts_[o].wall == c.wall)
                c.shear_force = wall_contacts_[o].shear_force;
            fresh.push_back(c);
        }
        wall_start_[i + 1] = static_cast<std::int32_t>(fresh.size());
    }
    wall_contacts_.swap(fresh);
    wall_out_.assign(wall_contacts_.size(), WallOutput{});
}

}  // namespace gradem
