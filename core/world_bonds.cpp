// The bond phase: installation and the per-step loop over bonds, generic over the bond law
// (core/bond_models.hpp picks the kernel once per phase). Each bond writes only its own record,
// its own side state and its pair's output slot; breaks are logged per block and merged in bond
// order, so the results are the same for any thread count.
#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "core/bond_models.hpp"
#include "core/parallel.hpp"
#include "core/random.hpp"
#include "core/world.hpp"

namespace gradem {

std::size_t World::install_bonds(const BondParams& params, double max_gap) {
    require_valid(params.invalid_reason());
    return install_bonds(BondFamilyTable::single(params), max_gap);
}

// Family pair (a, b) -> index min * n + max into the table (the bond's family_pair). A table of
// one family bonds every pair, whatever the particles' tags.
std::size_t World::install_bonds(const BondFamilyTable& table, double max_gap) {
    require_valid(table.invalid_reason());
    if (!std::isfinite(max_gap))
        throw std::invalid_argument("install_bonds: max_gap is not finite");
    const int nf = table.families;
    if (nf > 1) {
        if (particles_.family.size() != particles_.size())
            throw std::invalid_argument("install_bonds: particle families not set");
        for (std::size_t i = 0; i < particles_.size(); ++i)
            if (particles_.family[i] >= nf)
                throw std::invalid_argument("install_bonds: particle " + std::to_string(i) + " has family " +
                                            std::to_string(particles_.family[i]) + ", the table has " +
                                            std::to_string(nf));
    }
    const BondParams* first = nullptr;
    for (const auto& e : table.entries)
        if (e && !first) first = &*e;
    const std::size_t stride =
        visit_bond_law(first->model, [&](auto law) { return decltype(law)::side_size(*first); });
    std::vector<BondParams> family_params(table.entries.size(), *first);  // absent entries: never used
    for (std::size_t k = 0; k < table.entries.size(); ++k) {
        if (!table.entries[k]) continue;
        family_params[k] = *table.entries[k];
        const std::size_t own = visit_bond_law(first->model, [&](auto law) { return decltype(law)::side_size(family_params[k]); });
        if (own != stride) throw std::invalid_argument("install_bonds: bond families differ in the law's shape (side state)");
    }
    pair_outputs_current();     // before the batches go stale
    write_back_pair_batches();  // the contact shear forces, which the new bonds keep
    pair_batches_current_ = false;
    contact_pairs_stale_ = true;
    bond_params_ = *first;
    bond_family_params_ = family_params;
    std::vector<ParticlePair> found;
    search_->find_pairs(particles_.position, particles_.radius, std::max(max_gap, 0.0), found);
    bonds_.clear();
    std::vector<BondInstall> installs;
    for (const ParticlePair& p : found) {
        const auto i = static_cast<std::size_t>(p.i), j = static_cast<std::size_t>(p.j);
        const int fa = nf == 1 ? 0 : particles_.family[i], fb = nf == 1 ? 0 : particles_.family[j];
        const auto family_pair = static_cast<std::size_t>(std::min(fa, fb) * nf + std::max(fa, fb));
        if (!table.entries[family_pair]) continue;  // this family pair is not bonded
        const BondParams& params = family_params[family_pair];
        const Vec3 d = particles_.position[j] - particles_.position[i];
        const double dist = norm(d);
        const double gap = dist - particles_.radius[i] - particles_.radius[j];
        if (gap > max_gap) continue;
        ParallelBond b;
        b.i = p.i;
        b.j = p.j;
        b.model = params.model;
        b.family_pair = static_cast<std::uint8_t>(family_pair);
        const std::uint64_t key = (static_cast<std::uint64_t>(p.i) << 32) | static_cast<std::uint32_t>(p.j);
        b.tensile_strength = truncated_normal_positive(
            params.tensile_strength_mean, params.tensile_strength_std, params.seed, key);
        b.cohesion = truncated_normal_positive(params.cohesion_mean, params.cohesion_std,
                                               params.seed ^ 0x5bd1e995ull, key);
        bonds_.push_back(b);
        installs.push_back({dist > 0.0 ? (1.0 / dist) * d : Vec3{1.0, 0.0, 0.0}, gap, particles_.radius[i],
                            particles_.radius[j], key, std::max(max_gap, 0.0)});
    }
    bond_side_stride_ = stride;
    bond_side_.assign(bonds_.size() * stride, 0.0);
    bond_side_.shrink_to_fit();
    visit_bond_law(first->model, [&](auto law) {
        for (std::size_t k = 0; k < bonds_.size(); ++k)
            decltype(law)::install(bond_family_params_[bonds_[k].family_pair], installs[k], bonds_[k],
                                   bond_side_.data() + k * stride);
    });
    bond_stored_.assign(bonds_.size(), 0.0);
    bond_const_stale_ = true;
    rebuild_needed_ = true;
    forces_current_ = false;
    return bonds_.size();
}

// The same expressions the kernel evaluated every step before, so the values are bitwise equal.
void World::refresh_bond_constants() {
    bond_const_.resize(bonds_.size());
    bond_const_.shrink_to_fit();
    for (std::size_t k = 0; k < bonds_.size(); ++k) {
        const double ra = particles_.radius[static_cast<std::size_t>(bonds_[k].i)];
        const double rb = particles_.radius[static_cast<std::size_t>(bonds_[k].j)];
        const BondParams& bp = bond_family_params_[bonds_[k].family_pair];
        const BondSection sec = bond_section(bp.radius_multiplier, ra, rb);
        bond_const_[k] = {sec.radius, 1.0 / sec.radius, bond_stiffness(bp.effective_modulus, bp.stiffness_ratio, ra, rb)};
    }
    bond_const_stale_ = false;
}

BondPass World::bond_pass() {
    BondPass pass{particles_, bonds_, bond_side_, bond_side_stride_, bond_const_, bond_family_params_,
                  pair_out_, breaks_, sim_, step_, time_, bond_params_.bond_replaces_contact()};
    pass.force = particles_.force.data();
    pass.torque = particles_.torque.data();
    pass.bond_torque = &bond_torque_;
    pass.released_particles = &unowned_next_pass_;
    if (joint_forces_in_pass()) {
        pass.force_owners = [this](int team) {
            if (force_owner_team_ != team) build_force_owners(team);
            for (const std::int32_t p : unowned_next_pass_) force_owner_[static_cast<std::size_t>(p)] = -1;
            unowned_next_pass_.clear();
            return force_owner_.data();
        };
        pass_shares_ = {&pass_share_, &particle_share_, &share_seconds_, 1};
        pass.shares = &pass_shares_;
    }
    return pass;
}

bool World::joint_forces_in_pass() const {
    return sim_.forces_in_pass && bond_params_.model == BondModel::flat_joint && bond_params_.bond_replaces_contact();
}

// A law with its own pass over every bond (Law::compute_all, core/bond_pass.hpp) runs it; the
// others go through the generic loop below.
World::BondEnergy World::compute_bonds(double dt) {
    if (bond_const_stale_) refresh_bond_constants();
    return visit_bond_law(bond_params_.model, [&](auto law) -> BondEnergy {
        using Law = decltype(law);
        if constexpr (requires(const BondPass& pass) { Law::compute_all(pass, dt); }) {
            const BondEnergy e = Law::compute_all(bond_pass(), dt);
            if (joint_forces_in_pass()) balance_pass_shares(pass_shares_.team);
            return e;
        } else {
            return compute_bonds_with<Law>(dt);
        }
    });
}

// Phase 3: every acting bond (bond_acts) through the law's kernel, added into its pair's slot.
template <class Law>
World::BondEnergy World::compute_bonds_with(double dt) {
    const auto nb = static_cast<std::int64_t>(bonds_.size());
    std::vector<BondEnergy> partial(static_cast<std::size_t>(block_count(nb)));
    std::vector<std::vector<BreakEvent>> broken(static_cast<std::size_t>(block_count(nb)));
    std::vector<typename Law::Context> contexts;  // one per bond family pair
    for (const BondParams& p : bond_family_params_) contexts.push_back(Law::context(p, sim_.track_energy));
    const std::size_t stride = bond_side_stride_;
    const bool replaces = bond_params_.bond_replaces_contact();
    for_each_block(nb, [&](std::int64_t begin, std::int64_t end, std::int64_t blk) {
        BondEnergy e;
        std::vector<BondBreak> breaks;
        for (std::int64_t k = begin; k < end; ++k) {
            ParallelBond& b = bonds_[static_cast<std::size_t>(k)];
            if (!bond_acts(b)) continue;
            const auto i = static_cast<std::size_t>(b.i), j = static_cast<std::size_t>(b.j);
            const PairState s{particles_.position[i], particles_.position[j],
                              particles_.velocity[i], particles_.velocity[j], particles_.spin[i],
                              particles_.spin[j], particles_.radius[i], particles_.radius[j]};
            const PairKinematics kin = pair_kinematics(s, dt);
            const typename Law::Context& ctx = contexts[b.family_pair];
            const BondConstants& bc = bond_const_[static_cast<std::size_t>(k)];
            const BondSection sec = bond_section_of_radius(bc.radius, bc.inv_radius);
            const BondStiffness& stiff = bc.stiffness;
            double* side = bond_side_.data() + static_cast<std::size_t>(k) * stride;
            const BondStepResult r = Law::step(ctx, b, side, sec, stiff, kin, breaks);
            e.stored += r.stored;
            e.released += r.released;
            e.damage += r.damage;
            e.slip += r.slip;
            if (!breaks.empty()) {
                for (const BondBreak& x : breaks)
                    broken[static_cast<std::size_t>(blk)].push_back(
                        {step_, time_, static_cast<std::int32_t>(k), b.i, b.j, x.mode,
                         s.xa + kin.arm_a + x.offset, kin.normal, sec.radius, x.tensile_stress,
                         x.shear_stress, x.element});
                breaks.clear();
            }
            PairOutput& out = pair_out_[static_cast<std::size_t>(b.slot)];
            if (r.failure != BondState::intact) {
                released_bond_output(out, replaces);
                ++e.releases;
                continue;
            }
            bond_output(out, r.force_j, cross(kin.arm_b, r.force_j) + r.moment_j, replaces, s.xb - s.xa);
        }
        partial[static_cast<std::size_t>(blk)] = e;
    });
    for (auto& list : broken) breaks_.insert(breaks_.end(), list.begin(), list.end());
    return ordered_sum(partial);
}

}  // namespace gradem
