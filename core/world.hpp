#pragma once
// The World owns the state of one DEM simulation and advances it. World::step() reads as the
// list of phases of one cycle (as PFC and Box2D's b2World_Step do it):
//   1. neighbours  - rebuild the Verlet pair list when particles moved more than half the skin;
//   2. contacts    - linear contact law for every pair, into that pair's own output slot
//                    (a pair whose acting bond replaces its contact is skipped);
//   3. bonds       - the bond law (BondParams::model; core/bond_models.hpp) for every acting
//                    bond, added into its pair's slot, or set there if the bond replaces the
//                    pair's contact (with the parallel bond, 2 and 3 are one vectorised pass
//                    over the pairs, bitwise the same: world_pairs.cpp);
//   4. walls       - linear contact with each platen, into per-wall-contact slots;
//   5. gather      - each particle sums its slots in a fixed order into force/torque (a slot
//                    carries the moment on each side: PairOutput, core/bond_pass.hpp); the
//                    parallel bond's pass adds the pairs of the particles whose pairs one thread
//                    runs to them itself, in that order, and the gather adds their walls
//                    (SimParams::forces_in_pass);
//   6. integrate   - leap-frog with Cundall local damping (next step, before 1-5: motion
//                    first, then forces at the new configuration, as PFC cycles).
// Determinism: every interaction is computed once, every particle sums its interactions in
// sorted order (from their slots, or as the pass computes them), reductions go through
// fixed-size blocks, so the state after N steps is bitwise identical for any number of OpenMP
// threads. No atomics on forces.
#include <cstdint>
#include <memory>
#include <span>
#include <string>
#include <vector>

#include "core/bond_families.hpp"
#include "core/bond_law.hpp"
#include "core/bond_pass.hpp"
#include "core/neighbor_search.hpp"
#include "core/pair_batch.hpp"
#include "core/params.hpp"
#include "core/particles.hpp"
#include "core/wall.hpp"
#include "core/world_types.hpp"

namespace gradem {

class World {
public:
    /// Validates every parameter and particle; throws std::invalid_argument naming the field.
    World(ParticleSet particles, const ContactParams& contact, const SimParams& sim,
          std::unique_ptr<NeighborSearch> search = make_neighbor_search());

    // --- set-up -------------------------------------------------------------------------
    std::int32_t add_wall(Wall wall);
    void remove_wall(std::int32_t index);
    /// Installs a bond of law params.model at every pair with gap <= max_gap [m] (PFC `bond
    /// gap`), at zero force in the current geometry, replacing any existing bonds. Returns the
    /// bond count.
    std::size_t install_bonds(const BondParams& params, double max_gap);
    /// The same with parameters per pair of particle families (ParticleSet::family; explicit paste):
    /// a pair whose table entry is empty gets no bond. Throws for an invalid table or a particle
    /// family outside it.
    std::size_t install_bonds(const BondFamilyTable& table, double max_gap);
    /// Changes bond stiffness parameters of the existing bonds (strengths stay as drawn).
    void set_bond_stiffness(double effective_modulus, double stiffness_ratio);
    void set_contact_params(const ContactParams& contact);
    /// Fixes the time step [s]; 0 returns to automatic (safety * critical, at every rebuild).
    void set_time_step(double dt);
    /// Sets the velocity [m/s] and spin [rad/s] a particle moves with over the next step (for
    /// prescribed motion of kFixedVelocity / kFixedSpin particles); keeps all histories.
    void set_particle_motion(std::int32_t i, const Vec3& velocity, const Vec3& spin);
    /// Multiplies every radius by `factor` at constant density (radius expansion, as PFC's
    /// genesis installs stress). Counts towards the Verlet skin instead of forcing a rebuild.
    void scale_radii(double factor);
    /// Particle state for editing (set-up only); forces a neighbour rebuild.
    ParticleSet& edit_particles();
    Wall& wall(std::int32_t index) { return walls_[static_cast<std::size_t>(index)]; }

    // --- stepping -----------------------------------------------------------------------
    RunStatus step();
    RunStatus run(std::int64_t steps);

    // --- queries ------------------------------------------------------------------------
    [[nodiscard]] const ParticleSet& particles() const { return particles_; }
    [[nodiscard]] const std::vector<ParallelBond>& bonds() const {
        records_current();
        return bonds_;
    }
    /// Law-specific side state of bond k (empty for the parallel bond); decode it with the
    /// law's header (its state decoder).
    [[nodiscard]] std::span<const double> bond_side_state(std::size_t k) const {
        return {bond_side_.data() + k * bond_side_stride_, bond_side_stride_};
    }
    [[nodiscard]] const std::vector<Wall>& walls() const { return walls_; }
    [[nodiscard]] const EnergyLedger& energy() const { return energy_; }
    [[nodiscard]] const std::vector<BreakEvent>& break_events() const { return breaks_; }
    [[nodiscard]] const StepProfile& profile() const { return profile_; }
    [[nodiscard]] RunStatus status() const { return status_; }
    [[nodiscard]] const std::string& status_reason() const { return status_reason_; }
    [[nodiscard]] std::int64_t step_count() const { return step_; }
    [[nodiscard]] double time() const { return time_; }
    [[nodiscard]] double time_step();
    /// min over particles of sqrt(m/k_tran), sqrt(I/k_rot) with stiffnesses summed over every
    /// neighbour pair, bond and wall contact (PFC "Timestep Determination"), without safety.
    [[nodiscard]] double critical_time_step();
    [[nodiscard]] const ContactParams& contact_params() const { return contact_; }
    [[nodiscard]] const BondParams& bond_params() const { return bond_params_; }
    /// Parameters of each bond family pair (index ParallelBond::family_pair; one entry for the
    /// single-parameter installation).
    [[nodiscard]] const std::vector<BondParams>& bond_family_params() const { return bond_family_params_; }
    [[nodiscard]] const SimParams& sim_params() const { return sim_; }
    [[nodiscard]] std::size_t intact_bond_count() const;
    [[nodiscard]] std::size_t pair_count() const { return pairs_.size(); }
    [[nodiscard]] std::size_t active_contact_count() const;
    /// Contacts (overlapping pairs, wall contacts and intact bonds) per particle.
    [[nodiscard]] std::vector<std::int32_t> contact_counts() const;
    /// PFC's mean unbalanced-force ratio: mean |resultant force| over free particles divided by
    /// the mean magnitude of the contact and bond forces (0 when nothing touches).
    [[nodiscard]] double unbalanced_force_ratio() const;
    /// Each pair's force and moments on its particles at the latest force evaluation, in the
    /// World's pair order (the same for any thread count): force and moment on j, moment on i.
    [[nodiscard]] const std::vector<PairOutput>& pair_outputs() const {
        pair_outputs_current();
        return pair_out_;
    }
    /// Bytes held by the particle, pair, bond and wall-contact arrays (capacity, not size).
    [[nodiscard]] std::size_t memory_bytes() const;
    /// Hash of positions, velocities, spins and bond forces (FNV-1a over the raw bits).
    [[nodiscard]] std::uint64_t state_hash() const;

private:
    /// A Verlet pair: persistent shear history of the linear contact, and its bond if any.
    struct Pair {
        std::int32_t i = -1, j = -1;
        std::int32_t bond = -1;  ///< index into bonds_, -1 if none
        Vec3 shear_force;        ///< linear part, force on j [N]
    };
    struct WallOutput {
        Vec3 force, torque;  ///< on the particle
    };
    struct Incidence {
        std::int32_t slot;     ///< pair index
        std::int32_t partner;  ///< the other particle; sign bit set when this particle is i
    };

    ParticleSet particles_;
    ContactParams contact_;
    BondParams bond_params_;
    std::vector<BondParams> bond_family_params_{BondParams{}};  ///< per ParallelBond::family_pair
    SimParams sim_;
    std::unique_ptr<NeighborSearch> search_;

    std::vector<Pair> pairs_;
    std::vector<PairOutput> pair_out_;
    /// The latest evaluation added the pairs' forces to the particles in the pass
    /// (SimParams::forces_in_pass) and left pair_out_ behind it: rebuilt when read.
    bool forces_from_pass_ = false;
    bool pair_out_stale_ = false;
    /// Per particle, the thread whose share of the pass holds every one of its pairs (it adds
    /// their forces to the particle in the pass), -1 where its pairs span two shares or it has
    /// none (the gather sums its slots); built for a team of force_owner_team_ threads (0: to
    /// build) over the shares of share_pass(): the parallel bond's pass shares the pairs, the
    /// flat joint's the bonds (its particles' pairs must all be acting joints).
    std::vector<std::int16_t> force_owner_;
    int force_owner_team_ = 0;
    void build_force_owners(int team);
    /// A pass with forces into particles: each thread's share of its pairs (parallel bond) or
    /// bonds (flat joint) and of the particles (team + 1 bounds; World::share_pass), empty
    /// otherwise (equal shares).
    std::vector<std::int64_t> pass_share_, particle_share_;
    /// Relative speeds of the team's threads (empty: equal) that share_pass() cuts the shares
    /// by, measured from the time each thread spends in its share of the pass (SimParams::
    /// thread_share_weights empty), over windows of steps.
    std::vector<double> share_speed_, share_seconds_;
    std::int64_t share_window_steps_ = 0;
    PassShares pass_shares_;  ///< the above for a law's own pass (bond_pass())
    void share_pass(int team, bool over_bonds);
    void balance_pass_shares(int team);
    void share_window_reset() {
        share_seconds_.assign(share_seconds_.size(), 0.0);
        share_window_steps_ = 0;
    }
    /// The flat joint's pass adds its joints' forces to the particles (SimParams::forces_in_pass;
    /// the joints must own their pairs' slots: BondParams::bond_replaces_contact).
    [[nodiscard]] bool joint_forces_in_pass() const;
    std::vector<Vec3> bond_torque_;  ///< per bond: its moment on j from that pass [N m] (its slot rebuilt from it)
    std::vector<std::int32_t> unowned_next_pass_;  ///< BondPass::released_particles
    std::vector<std::int32_t> incidence_start_;
    std::vector<Incidence> incidence_;
    std::vector<ParallelBond> bonds_;
    std::vector<double> bond_side_;      ///< per-bond law state, bond_side_stride_ doubles each
    std::vector<BondConstants> bond_const_;  ///< per bond (core/bond_pass.hpp)
    /// Strain energy of each bond after the latest step [J] (0 once broken), summed per bond
    /// block by the fused pair pass so the sum keeps the bond-order rounding (world_pairs.cpp).
    std::vector<double> bond_stored_;
    /// The parallel bond's pass state in structure-of-arrays batches (core/pair_batch.hpp):
    /// current while the pair list, the bonds and their constants are unchanged; while it is,
    /// the contact shear forces and intact bonds' forces in pairs_ and bonds_ may lag behind it.
    /// The contacts phase's pairs (compute_contacts): per block of kBlockSize pairs, the ones whose
    /// contact law runs (no acting bond replaces it), in pair order, stored from the block's first
    /// index on, contact_block_count_[block] of them. Collected again when the pairs or the set
    /// of acting bonds change (a neighbour rebuild, an installation, a release).
    std::vector<std::int32_t> contact_pairs_;
    std::vector<std::int32_t> contact_block_count_;
    bool contact_pairs_stale_ = true;
    std::vector<PairBatch> pair_batches_;
    bool pair_batches_current_ = false;
    bool records_behind_batches_ = false;
    bool bond_const_stale_ = true;
    std::size_t bond_side_stride_ = 0;   ///< 0 for laws without side state (parallel bond)
    std::vector<Wall> walls_;
    std::vector<WallContact> wall_contacts_;
    std::vector<WallOutput> wall_out_;
    std::vector<std::int32_t> wall_start_;
    std::vector<Vec3> position_at_rebuild_;
    std::vector<Vec3> wall_shift_since_rebuild_;
    std::vector<Vec3> wall_previous_reaction_;
    std::vector<Vec3> wall_last_step_;

    std::vector<BreakEvent> breaks_;
    EnergyLedger energy_;
    StepProfile profile_;
    RunStatus status_ = RunStatus::running;
    std::string status_reason_;
    std::int64_t step_ = 0;
    double time_ = 0.0;
    double dt_ = 0.0;
    double skin_ = 0.0;
    double max_displacement_ = 0.0;
    double radius_growth_since_rebuild_ = 0.0;  ///< sum of r_max * (factor - 1) [m]
    bool rebuild_needed_ = true;

    /// Energy terms of the latest force evaluation.
    struct ForceEvaluation {
        double contact_strain = 0, bond_strain = 0, slip = 0, released = 0, damage = 0;
    };
    ForceEvaluation last_eval_;
    bool forces_current_ = false;
    bool reset_energy_reference_ = true;  ///< set-up changed the energy: new reference next step

    // Phases of step(), in order (world_step.cpp). `dt` is the time over which the current
    // velocities moved the particles here (0 for a fresh evaluation after set-up).
    [[nodiscard]] bool needs_rebuild() const;
    void evaluate_forces(double increment_dt, class Stopwatch& clock);
    void compute_contacts(double dt, double& strain, double& slip);
    std::int32_t collect_contact_pairs(std::int64_t begin, std::int64_t end);
    using BondEnergy = BondPassEnergy;
    BondEnergy compute_bonds(double dt);
    void refresh_bond_constants();
    /// Phases 2 and 3 in one pass for the parallel bond (world_pairs.cpp); returns the bond
    /// energies, the contact strain and slip energies through `strain` and `slip`.
    BondEnergy compute_contacts_and_parallel_bonds(double dt, double& strain, double& slip);
    void build_pair_batches();
    /// Brings pairs_' shear forces and bonds_' forces and moments up to the batches (world_pairs.cpp).
    void write_back_pair_batches();
    /// The same for const queries: the records are a cache of the batches' state then, so
    /// bringing them up to date changes nothing a caller can observe.
    void records_current() const {
        if (records_behind_batches_) const_cast<World*>(this)->write_back_pair_batches();
    }
    struct ParallelBondPass;  ///< its steps, one pair block at a time (world_pairs.cpp)
    friend struct ParallelBondPass;
    /// The World's state for a law's own pass over every bond (Law::compute_all, bond_pass.hpp).
    BondPass bond_pass();
    template <class Law>
    BondEnergy compute_bonds_with(double dt);
    void compute_wall_contacts(double dt, double& strain, double& slip);
    struct IntegrationSums {
        double kinetic = 0, damping = 0, boundary = 0, max_disp2 = 0;
        std::int64_t runaway = -1;  ///< a particle that moved too far or went non-finite
    };
    void gather_forces();
    /// pair_out_ as the latest evaluation would have written it, from the pass's batches (the
    /// flat joint's: its bonds, FlatJointLaw::rebuild_slots) and the positions (world_pairs.cpp);
    /// called before anything reads the slots or changes what they are computed from.
    void rebuild_pair_outputs();
    void pair_outputs_current() const {
        if (pair_out_stale_) const_cast<World*>(this)->rebuild_pair_outputs();
    }
    IntegrationSums integrate();
    void move_walls(double& boundary_work);
    void check_divergence(const IntegrationSums& sums);

    // Neighbour bookkeeping (world_neighbors.cpp).
    void rebuild_neighbors();
    void merge_pairs(const std::vector<ParticlePair>& found);
    void build_incidence();
    void build_wall_contacts();
};

}  // namespace gradem
