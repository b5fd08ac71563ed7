// World set-up and queries. The step itself is in world_step.cpp, neighbour bookkeeping in
// world_neighbors.cpp.
#include "core/world.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <stdexcept>

#include "core/bond_models.hpp"
#include "core/contact_law.hpp"
#include "core/parallel.hpp"

namespace gradem {

World::World(ParticleSet particles, const ContactParams& contact, const SimParams& sim,
             std::unique_ptr<NeighborSearch> search)
    : particles_(std::move(particles)), contact_(contact), sim_(sim), search_(std::move(search)) {
    require_valid(contact_.invalid_reason());
    require_valid(sim_.invalid_reason());
    require_valid(particles_.invalid_reason());
    if (particles_.size() > static_cast<std::size_t>(std::numeric_limits<std::int32_t>::max() / 2))
        throw std::invalid_argument("World: too many particles for 32-bit indices");
    if (!search_) throw std::invalid_argument("World: neighbour search is null");
    const double r_min =
        particles_.size() ? *std::min_element(particles_.radius.begin(), particles_.radius.end())
                          : 1.0;
    skin_ = sim_.skin_fraction * r_min;
    dt_ = sim_.time_step;
}

std::int32_t World::add_wall(Wall wall) {
    pair_outputs_current();
    require_valid(wall.contact.invalid_reason());
    const double l = norm(wall.normal);
    if (!(l > 0.0)) throw std::invalid_argument("Wall::normal = 0 violates |n| > 0");
    wall.normal = (1.0 / l) * wall.normal;
    walls_.push_back(std::move(wall));
    rebuild_needed_ = true;
    forces_current_ = false;
    return static_cast<std::int32_t>(walls_.size() - 1);
}

void World::remove_wall(std::int32_t index) {
    pair_outputs_current();
    if (index < 0 || static_cast<std::size_t>(index) >= walls_.size())
        throw std::invalid_argument("World::remove_wall: no wall " + std::to_string(index));
    walls_.erase(walls_.begin() + index);
    wall_contacts_.clear();  // indices shift: start the wall histories afresh
    rebuild_needed_ = true;
    forces_current_ = false;
}

void World::set_bond_stiffness(double effective_modulus, double stiffness_ratio) {
    pair_outputs_current();
    BondParams p = bond_params_;
    p.effective_modulus = effective_modulus;
    p.stiffness_ratio = stiffness_ratio;
    require_valid(p.invalid_reason());
    bond_params_ = p;
    for (BondParams& f : bond_family_params_) {
        f.effective_modulus = effective_modulus;
        f.stiffness_ratio = stiffness_ratio;
    }
    bond_const_stale_ = true;
    forces_current_ = false;
    if (sim_.time_step == 0.0) dt_ = 0.0;
}

void World::set_contact_params(const ContactParams& contact) {
    pair_outputs_current();
    require_valid(contact.invalid_reason());
    contact_ = contact;
    forces_current_ = false;
    if (sim_.time_step == 0.0) dt_ = 0.0;
}

void World::set_time_step(double dt) {
    if (!(dt >= 0.0 && std::isfinite(dt)))
        throw std::invalid_argument("World::set_time_step: dt = " + std::to_string(dt) +
                                    " violates >= 0");
    sim_.time_step = dt;
    dt_ = dt;
}

void World::set_particle_motion(std::int32_t i, const Vec3& velocity, const Vec3& spin) {
    particles_.velocity.at(static_cast<std::size_t>(i)) = velocity;
    particles_.spin.at(static_cast<std::size_t>(i)) = spin;
}

void World::scale_radii(double factor) {
    if (!(factor > 0.0 && std::isfinite(factor)))
        throw std::invalid_argument("World::scale_radii: factor = " + std::to_string(factor) + " violates > 0");
    pair_outputs_current();
    double r_max = 0.0;
    for (std::size_t i = 0; i < particles_.size(); ++i) {
        particles_.set_radius(i, particles_.radius[i] * factor);
        r_max = std::max(r_max, particles_.radius[i]);
    }
    radius_growth_since_rebuild_ += std::fabs(factor - 1.0) * r_max;
    bond_const_stale_ = true;
    forces_current_ = false;
    if (sim_.time_step == 0.0) dt_ = 0.0;
}

ParticleSet& World::edit_particles() {
    pair_outputs_current();
    rebuild_needed_ = true;
    bond_const_stale_ = true;
    forces_current_ = false;
    return particles_;
}

RunStatus World::run(std::int64_t steps) {
    for (std::int64_t s = 0; s < steps && status_ == RunStatus::running; ++s) step();
    return status_;
}

double World::time_step() {
    if (dt_ == 0.0) dt_ = sim_.time_step_safety * critical_time_step();
    return dt_;
}

double World::critical_time_step() {
    if (rebuild_needed_) rebuild_neighbors();
    const auto n = static_cast<std::int64_t>(particles_.size());
    // The bond law's undamaged stiffness (one law per World: resolved once, outside the loop).
    const auto bond_time_step_stiffness = visit_bond_law(bond_params_.model, [](auto law) {
        return &decltype(law)::time_step_stiffness;
    });
    // A bond that replaces its pair's contact acts alone while it acts, and the contact alone
    // once it is released.
    const bool bond_replaces = bond_params_.bond_replaces_contact();
    std::vector<double> block_min(static_cast<std::size_t>(block_count(n)),
                                  std::numeric_limits<double>::infinity());
    for_each_block(n, [&](std::int64_t begin, std::int64_t end, std::int64_t b) {
        double m = std::numeric_limits<double>::infinity();
        for (std::int64_t p = begin; p < end; ++p) {
            const auto i = static_cast<std::size_t>(p);
            const double ri = particles_.radius[i];
            TimeStepStiffness k;  // the particle's, summed over its pairs and walls
            for (std::int32_t e = incidence_start_[i]; e < incidence_start_[i + 1]; ++e) {
                const Pair& pr = pairs_[static_cast<std::size_t>(incidence_[static_cast<std::size_t>(e)].slot)];
                const double ra = particles_.radius[static_cast<std::size_t>(pr.i)];
                const double rb = particles_.radius[static_cast<std::size_t>(pr.j)];
                const double kn = contact_normal_stiffness(contact_.effective_modulus, ra, rb);
                const double ks = kn / contact_.stiffness_ratio;
                const TimeStepStiffness contact{std::max(kn, ks), ks * ri * ri};
                TimeStepStiffness bond_k;
                const TimeStepStiffness* acting_bond = nullptr;
                if (pr.bond >= 0 && bond_acts(bonds_[static_cast<std::size_t>(pr.bond)])) {
                    const BondParams& bp = bond_family_params_[bonds_[static_cast<std::size_t>(pr.bond)].family_pair];
                    const BondSection s = bond_section(bp.radius_multiplier, ra, rb);
                    bond_k = bond_time_step_stiffness(s, bond_stiffness(bp.effective_modulus, bp.stiffness_ratio, ra, rb), ri);
                    acting_bond = &bond_k;
                }
                add_pair_time_step_stiffness(k, contact, acting_bond, bond_replaces);
            }
            for (std::int32_t w = wall_start_[i]; w < wall_start_[i + 1]; ++w) {
                const Wall& wall = walls_[static_cast<std::size_t>(wall_contacts_[static_cast<std::size_t>(w)].wall)];
                const double kn = wall_normal_stiffness(wall.contact.effective_modulus, ri);
                const double ks = kn / wall.contact.stiffness_ratio;
                k.translational += std::max(kn, ks);
                k.rotational += ks * ri * ri;
            }
            if (k.translational > 0.0) m = std::min(m, std::sqrt(particles_.mass[i] / k.translational));
            if (k.rotational > 0.0) m = std::min(m, std::sqrt(particles_.inertia[i] / k.rotational));
        }
        block_min[static_cast<std::size_t>(b)] = m;
    });
    double dt = std::numeric_limits<double>::infinity();
    for (double m : block_min) dt = std::min(dt, m);
    if (!std::isfinite(dt)) {
        // No interaction at all: free flight. Use the time to cross a tenth of the smallest
        // radius at unit speed as a harmless default.
        dt = 0.1 * (n ? *std::min_element(particles_.radius.begin(), particles_.radius.end()) : 1.0);
    }
    return dt;
}

std::size_t World::intact_bond_count() const {
    return static_cast<std::size_t>(std::count_if(bonds_.begin(), bonds_.end(), [](const ParallelBond& b) {
        return b.state == BondState::intact;
    }));
}

std::size_t World::active_contact_count() const {
    std::size_t count = 0;
    for (const Pair& p : pairs_) {
        const auto i = static_cast<std::size_t>(p.i), j = static_cast<std::size_t>(p.j);
        const double gap = norm(particles_.position[j] - particles_.position[i]) -
                           particles_.radius[i] - particles_.radius[j];
        if (gap < 0.0) ++count;
    }
    return count;
}

std::vector<std::int32_t> World::contact_counts() const {
    std::vector<std::int32_t> count(particles_.size(), 0);
    for (const Pair& p : pairs_) {
        const auto i = static_cast<std::size_t>(p.i), j = static_cast<std::size_t>(p.j);
        const bool bonded = p.bond >= 0 && bond_acts(bonds_[static_cast<std::size_t>(p.bond)]);
        const double reach = particles_.radius[i] + particles_.radius[j];
        if (bonded || norm2(particles_.position[j] - particles_.position[i]) < reach * reach) {
            ++count[i];
            ++count[j];
        }
    }
    for (std::size_t k = 0; k < wall_contacts_.size(); ++k)
        if (norm2(wall_out_[k].force) > 0.0) ++count[static_cast<std::size_t>(wall_contacts_[k].particle)];
    return count;
}

double World::unbalanced_force_ratio() const {
    pair_outputs_current();
    double contact_sum = 0.0, unbalanced_sum = 0.0;
    std::size_t contacts = 0, free_particles = 0;
    for (const PairOutput& o : pair_out_) {
        const double f = norm(o.force_j);
        if (f > 0.0) contact_sum += f, ++contacts;
    }
    for (const WallOutput& o : wall_out_) {
        const double f = norm(o.force);
        if (f > 0.0) contact_sum += f, ++contacts;
    }
    for (std::size_t i = 0; i < particles_.size(); ++i)
        if (!(particles_.flags[i] & kFixedVelocity)) unbalanced_sum += norm(particles_.force[i]), ++free_particles;
    if (contacts == 0 || free_particles == 0 || contact_sum == 0.0) return 0.0;
    return (unbalanced_sum / static_cast<double>(free_particles)) / (contact_sum / static_cast<double>(contacts));
}

std::size_t World::memory_bytes() const {
    auto bytes = [](const auto& v) { return v.capacity() * sizeof(v[0]); };
    const ParticleSet& p = particles_;
    return bytes(p.position) + bytes(p.velocity) + bytes(p.spin) + bytes(p.force) +
           bytes(p.torque) + bytes(p.radius) + bytes(p.mass) + bytes(p.inertia) + bytes(p.flags) +
           bytes(pairs_) + bytes(pair_out_) + bytes(incidence_start_) + bytes(incidence_) + bytes(force_owner_) +
           bytes(bonds_) + bytes(pair_batches_) + bytes(bond_side_) + bytes(bond_const_) + bytes(bond_stored_) + bytes(wall_contacts_) + bytes(wall_out_) + bytes(wall_start_) +
           bytes(position_at_rebuild_) + bytes(contact_pairs_) + bytes(contact_block_count_);
}

namespace {
void fnv_mix(std::uint64_t& h, const void* data, std::size_t size) {
    const auto* c = static_cast<const unsigned char*>(data);
    for (std::size_t k = 0; k < size; ++k) {
        h ^= c[k];
        h *= 1099511628211ull;
    }
}
}  // namespace

std::uint64_t World::state_hash() const {
    records_current();
    std::uint64_t h = 1469598103934665603ull;
    for (std::size_t i = 0; i < particles_.size(); ++i) {
        fnv_mix(h, &particles_.position[i], sizeof(Vec3));
        fnv_mix(h, &particles_.velocity[i], sizeof(Vec3));
        fnv_mix(h, &particles_.spin[i], sizeof(Vec3));
    }
    for (const ParallelBond& b : bonds_) {
        fnv_mix(h, &b.normal_force, sizeof(double));
        fnv_mix(h, &b.shear_force, sizeof(Vec3));
        fnv_mix(h, &b.state, sizeof(b.state));
    }
    if (!bond_side_.empty()) fnv_mix(h, bond_side_.data(), bond_side_.size() * sizeof(double));
    return h;
}

}  // namespace gradem
