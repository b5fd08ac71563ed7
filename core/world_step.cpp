// One DEM cycle (see world.hpp for the phase list and the determinism argument).
#include <algorithm>
#include <bit>
#include <chrono>
#include <cmath>
#include <sstream>

#include "core/contact_law.hpp"
#include "core/parallel.hpp"
#include "core/world.hpp"

namespace gradem {
namespace {

}  // namespace

class Stopwatch {
public:
    double lap() {
        const auto now = std::chrono::steady_clock::now();
        const double s = std::chrono::duration<double>(now - last_).count();
        last_ = now;
        return s;
    }

private:
    std::chrono::steady_clock::time_point last_ = std::chrono::steady_clock::now();
};

namespace {

/// A contact shear force set to +0 if it is not: a +0 one is not stored to (the pair record is
/// then not written back).
inline void zero_shear(Vec3& shear) {
    if ((std::bit_cast<std::uint64_t>(shear.x) | std::bit_cast<std::uint64_t>(shear.y) | std::bit_cast<std::uint64_t>(shear.z)) != 0)
        shear = {};
}

struct EnergyPair {
    double stored = 0.0, dissipated = 0.0;
    EnergyPair& operator+=(const EnergyPair& o) {
        stored += o.stored;
        dissipated += o.dissipated;
        return *this;
    }
};

}  // namespace

// Motion first, then forces at the new configuration (PFC's cycle): after step() the positions,
// contact and bond forces and wall reactions all describe the same instant. The energy ledger
// describes the start of the step (where the leap-frog kinetic energy is defined).
RunStatus World::step() {
    if (status_ != RunStatus::running) return status_;
    Stopwatch clock;
    if (!forces_current_) {  // fresh set-up: evaluate at rest, no motion increments yet
        if (needs_rebuild()) rebuild_neighbors();
        (void)time_step();
        profile_.neighbors += clock.lap();
        evaluate_forces(0.0, clock);
        gather_forces();
        profile_.integrate += clock.lap();
        forces_current_ = true;
        reset_energy_reference_ = true;
    }
    // One dt per step: the increments of this step are computed with the dt
    // the particles and walls moved with, even if the rebuild below picks a new automatic dt
    // (that one takes effect from the next step's motion).
    const double step_dt = dt_;
    const IntegrationSums sums = integrate();
    double wall_work = 0.0;
    move_walls(wall_work);
    profile_.integrate += clock.lap();

    energy_.kinetic = sums.kinetic;
    energy_.strain_contact = last_eval_.contact_strain;
    energy_.strain_bond = last_eval_.bond_strain;
    energy_.friction += last_eval_.slip;
    energy_.bond_break += last_eval_.released;
    energy_.bond_damage += last_eval_.damage;
    energy_.damping += sums.damping;
    energy_.boundary_work += sums.boundary + wall_work;
    if (reset_energy_reference_) {
        energy_.reference = energy_.total();
        reset_energy_reference_ = false;
    }
    check_divergence(sums);
    ++step_;
    time_ += step_dt;

    if (needs_rebuild()) rebuild_neighbors();
    profile_.neighbors += clock.lap();
    evaluate_forces(step_dt, clock);
    gather_forces();
    profile_.integrate += clock.lap();
    return status_;
}

void World::evaluate_forces(double increment_dt, Stopwatch& clock) {
    ForceEvaluation e;
    double contact_slip = 0, wall_strain = 0, wall_slip = 0;
    BondEnergy bond;
    if (bond_params_.model == BondModel::parallel_bond) {  // one pass (world_pairs.cpp)
        bond = compute_contacts_and_parallel_bonds(increment_dt, e.contact_strain, contact_slip);
    } else {
        forces_from_pass_ = pair_out_stale_ = false;  // the phases below write every slot
        compute_contacts(increment_dt, e.contact_strain, contact_slip);
        profile_.contacts += clock.lap();
        bond = compute_bonds(increment_dt);
        forces_from_pass_ = pair_out_stale_ = joint_forces_in_pass();  // FlatJointLaw::compute_all
        profile_.pair_steps_into_particles += bond.into_particles;
        if (bond.releases > 0) contact_pairs_stale_ = true;  // their contacts act from the next step
    }
    profile_.bond_lane_steps += bond.lane_bonds;
    profile_.bond_scalar_steps += bond.scalar_bonds;
    e.bond_strain = bond.stored;
    e.released = bond.released;
    e.damage = bond.damage;
    profile_.bonds += clock.lap();
    compute_wall_contacts(increment_dt, wall_strain, wall_slip);
    profile_.walls += clock.lap();
    e.contact_strain += wall_strain;
    e.slip = contact_slip + wall_slip + bond.slip;
    last_eval_ = e;
}

// The pairs of block [begin, end) whose contact law runs, into contact_pairs_ from index begin
// on, in pair order; returns their count. A pair whose acting bond replaces the contact
// (BondParams::replaces_contact) is left out, its contact shear force set to +0: its bond is its
// only spring until it is released, and the bond phase sets its slot (bond_output() in
// core/bond_pass.hpp).
std::int32_t World::collect_contact_pairs(std::int64_t begin, std::int64_t end) {
    const bool bond_replaces = bond_params_.bond_replaces_contact();
    std::int32_t* out = contact_pairs_.data() + begin;
    std::int32_t n = 0;
    for (std::int64_t k = begin; k < end; ++k) {
        Pair& p = pairs_[static_cast<std::size_t>(k)];
        if (bond_replaces && p.bond >= 0 && bond_acts(bonds_[static_cast<std::size_t>(p.bond)])) {
            zero_shear(p.shear_force);
            continue;
        }
        out[n++] = static_cast<std::int32_t>(k);
    }
    return n;
}

// Phase 2: linear contact law for every Verlet pair but those whose acting bond replaces the
// contact (collect_contact_pairs), one output slot each. The bond phase, which runs after this
// one, sets the skipped pairs' slots (zero in the step a bond is released), and a release
// has the pairs collected again, so a bond broken this step lets its contact act from the next
// step on. Skipping those pairs saves their particle loads and slot stores (1.10-1.16x on the
// flat joint's step), and keeping the list saves reading every pair's record and bond
// (136 bytes per pair and step) to find them (bench/README.md).
void World::compute_contacts(double dt, double& strain, double& slip) {
    const auto m = static_cast<std::int64_t>(pairs_.size());
    const bool collect = contact_pairs_stale_;
    if (collect) {
        contact_pairs_.resize(static_cast<std::size_t>(m));
        contact_block_count_.resize(static_cast<std::size_t>(block_count(m)));
        contact_pairs_stale_ = false;
    }
    std::vector<EnergyPair> partial(static_cast<std::size_t>(block_count(m)));
    for_each_block(m, [&](std::int64_t begin, std::int64_t end, std::int64_t blk) {
        auto& count = contact_block_count_[static_cast<std::size_t>(blk)];
        if (collect) count = collect_contact_pairs(begin, end);
        EnergyPair e;
        const std::int32_t* listed = contact_pairs_.data() + begin;
        for (std::int32_t n = 0; n < count; ++n) {
            const std::int64_t k = listed[n];
            Pair& p = pairs_[static_cast<std::size_t>(k)];
            const auto i = static_cast<std::size_t>(p.i), j = static_cast<std::size_t>(p.j);
            const Vec3 xa = particles_.position[i], xb = particles_.position[j];
            const double ra = particles_.radius[i], rb = particles_.radius[j];
            PairOutput& out = pair_out_[static_cast<std::size_t>(k)];
            // an open pair needs no look at its particles' velocities and spins
            if (spheres_apart(xa, xb, ra, rb)) {
                zero_shear(p.shear_force);
                out = {};
                continue;
            }
            const PairState s{xa, xb, particles_.velocity[i], particles_.velocity[j], particles_.spin[i],
                              particles_.spin[j], ra, rb};
            const PairKinematics kin = pair_kinematics(s, dt);
            const double kn = contact_normal_stiffness(contact_.effective_modulus, s.ra, s.rb);
            const LinearContactResult r =
                linear_contact(kn, kn / contact_.stiffness_ratio, contact_.friction, kin.gap,
                               rotate_into_plane(p.shear_force, kin), kin.du_shear);
            p.shear_force = r.shear_force;
            out.force_j = r.normal_force * kin.normal + r.shear_force;
            out.torque_j = cross(kin.arm_b, out.force_j);
            set_i_side(out, xb - xa);
            e.stored += r.strain_energy;
            e.dissipated += r.slip_energy;
        }
        partial[static_cast<std::size_t>(blk)] = e;
    });
    const EnergyPair total = ordered_sum(partial);
    strain = total.stored;
    slip = total.dissipated;
}

// Phase 4: particle-wall contacts (linear, ball-facet stiffness), the wall playing particle A.
void World::compute_wall_contacts(double dt, double& strain, double& slip) {
    const auto m = static_cast<std::int64_t>(wall_contacts_.size());
    std::vector<EnergyPair> partial(static_cast<std::size_t>(block_count(m)));
    for_each_block(m, [&](std::int64_t begin, std::int64_t end, std::int64_t blk) {
        EnergyPair e;
        for (std::int64_t k = begin; k < end; ++k) {
            WallContact& c = wall_contacts_[static_cast<std::size_t>(k)];
            const Wall& w = walls_[static_cast<std::size_t>(c.wall)];
            const auto i = static_cast<std::size_t>(c.particle);
            const double r = particles_.radius[i];
            const double gap = dot(w.normal, particles_.position[i] - w.point) - r;
            WallOutput& out = wall_out_[static_cast<std::size_t>(k)];
            if (gap >= 0.0) {
                c.shear_force = {};
                out = {};
                continue;
            }
            const Vec3 arm = -(r + 0.5 * gap) * w.normal;  // particle centre -> contact point
            const Vec3 du = dt * (particles_.velocity[i] + cross(particles_.spin[i], arm) - w.velocity);
            const Vec3 du_shear = du - dot(du, w.normal) * w.normal;
            const Vec3 stored = c.shear_force - dot(c.shear_force, w.normal) * w.normal;
            const double kn = wall_normal_stiffness(w.contact.effective_modulus, r);
            const LinearContactResult res = linear_contact(
                kn, kn / w.contact.stiffness_ratio, w.contact.friction, gap, stored, du_shear);
            c.shear_force = res.shear_force;
            out.force = res.normal_force * w.normal + res.shear_force;
            out.torque = cross(arm, out.force);
            e.stored += res.strain_energy;
            e.dissipated += res.slip_energy;
        }
        partial[static_cast<std::size_t>(blk)] = e;
    });
    const EnergyPair total = ordered_sum(partial);
    strain = total.stored;
    slip = total.dissipated;
}

}  // namespace gradem
