// Phases 2 and 3 in one pass over the Verlet pairs, for the parallel bond. With the
// parallel bond the linear contact acts beside the bond (PFC linearpbond), so a bonded pair
// that overlaps needs the same pair kinematics twice: once in the contact phase, once in the
// bond phase. In a compression test about 55 % of the bonded pairs overlap, and almost every
// pair is bonded; this pass loads each pair's particle state and evaluates pair_kinematics()
// once, then applies the contact law and the bond law in the order of the two separate phases.
//
// Bitwise the same as compute_contacts() followed by compute_bonds_with<ParallelBondLaw>():
//   - per pair: the contact output is written first, the bond's force and moment added after,
//     with the same expressions on the same kinematics (pair_kinematics is a pure function);
//   - contact energies: summed per fixed pair block in pair order, as before;
//   - bond energies: the old loop summed them per fixed BOND block in bond order. Pairs and
//     bonds are both sorted by (i, j), so bonded pairs meet their bonds in bond order, but the
//     blocks differ; the stored energy of each bond is therefore kept in bond_stored_ and
//     summed per bond block afterwards, and the released energies (breaks only, in bond order)
//     per bond block from the break list. A bond that did not break adds +0 to the released
//     sum and a broken one +0 to the stored sum: both sums start at +0 and only add values
//     >= 0, so these additions never changed a bit;
//   - break events: per pair block in pair order, merged in block order = bond order.
// Laws whose bond replaces the contact keep the two separate phases (world_step.cpp, world_bonds.cpp).
//
// Vectorised across pairs, in place: the pairs' contact and bond state lives in
// structure-of-arrays batches of kPairLanes pairs (core/pair_batch.hpp). Per batch, as a list
// of steps: a scalar loop copies the lanes' particles into lanes (and tests which pairs
// overlap); one branch-free loop (compiled for AVX-512, AVX2 and the baseline ISA with function
// multiversioning) runs the kinematics, the contact law (only if some pair of the batch
// overlaps) and the bond law on every lane, writes the new contact and bond state back into the
// batch, and the pair's force and moment, selected by what acts (overlap, an intact bond), into
// a result row; a scalar loop copies the results into the pair output slots (or adds them to
// the pair's particles whose pairs all lie in this thread's share, in pair order, which is each
// particle's gather order: SimParams::forces_in_pass) and sums the energies in pair order; the
// breaks (rare) are handled pair by pair. Each lane does the same IEEE operations in the same
// order as the scalar code (-ffp-contract=off: no FMA; no reassociation), and a select keeps
// exactly the value the separate phases stored, so the results are bitwise the same.
#include <algorithm>
#include <cstddef>
#include <memory>
#include <utility>

#include "core/contact_law.hpp"
#include "core/flat_joint_law.hpp"
#include "core/lane_load.hpp"
#include "core/parallel.hpp"
#include "core/parallel_bond_law.hpp"
#include "core/world.hpp"

namespace gradem {
namespace {

constexpr int kLanes = kPairLanes;

/// The particle arrays the kernel reads (restrict: the kernel writes none of them).
struct ParticleArrays {
    const Vec3* __restrict position;
    const Vec3* __restrict velocity;
    const Vec3* __restrict spin;
    const double* __restrict radius;
};

/// The particles of a batch's lanes (structure of arrays), copied in before the kernel: the
/// vectoriser emulates gathers from the particle arrays by scalar loads and inserts inside the
/// vector loop, which costs more than this copy.
struct BatchParticles {
    double xa[3][kLanes], xb[3][kLanes], va[3][kLanes], vb[3][kLanes], wa[3][kLanes], wb[3][kLanes];
    double ra[kLanes], rb[kLanes];
};

/// What the kernel hands the scalar loops for one batch: the pair's force and moment on j
/// (contact and bond, as they act), which parts act, the energies, and the bond's failure code
/// and peak stresses (breaks only).
struct BatchResults {
    double force[3][kLanes], torque[3][kLanes];  ///< on j [N], [N m]
    double torque_i[3][kLanes];                  ///< on i (set_i_side) [N m]
    double open[kLanes];                         ///< 1: the pair does not overlap
    double contact_strain[kLanes], contact_slip[kLanes];  ///< [J], 0 when open
    double failure[kLanes];                      ///< BondState of an intact bond after the step; intact without one
    double tensile[kLanes], shear_stress[kLanes];  ///< σ̄, τ̄ [Pa]
    double bond_energy[kLanes];                  ///< [J]
};

constexpr double kIntact = static_cast<double>(static_cast<int>(BondState::intact));

// Component by component: an aggregate load or store of a Vec3 blocks the vectoriser.
inline Vec3 lane(const double (&a)[3][kLanes], int l) { return {a[0][l], a[1][l], a[2][l]}; }

inline void set_lane(double (&a)[3][kLanes], int l, const Vec3& v) {
    a[0][l] = v.x;
    a[1][l] = v.y;
    a[2][l] = v.z;
}

/// What to prefetch while a batch is loaded, a little per lane (prefetched in bursts, the lines
/// filled the miss queue and stalled the loop): the batch after the next one, the part of it the
/// kernel reads (its arrays lie 128-256 bytes apart, a pattern the hardware prefetcher does not
/// follow), and the next batch's particles j (random accesses: pairs are sorted by i, so i
/// streams and the hardware does not prefetch j).
struct BatchAhead {
    const char* batch;       ///< the batch after the next (or a nearer one at the end: harmless)
    int lines_per_lane = 0;  ///< 64-byte lines of it per lane
    const PairBatch* next;   ///< the next batch (or this one at the end: harmless)
    int next_count = 0;      ///< its pairs
};

/// Lane l's share of the prefetches.
__attribute__((always_inline)) inline void prefetch_ahead(const BatchAhead& ahead, int l, const ParticleArrays& A) {
    for (int line = 0; line < ahead.lines_per_lane; ++line)
        __builtin_prefetch(ahead.batch + (l * ahead.lines_per_lane + line) * 64, 1);
    if (l >= ahead.next_count) return;
    const std::int32_t j = ahead.next->j[l];
    __builtin_prefetch(&A.position[j]);
    __builtin_prefetch(&A.velocity[j]);
    __builtin_prefetch(&A.spin[j]);
    __builtin_prefetch(&A.radius[j]);
}

/// Whether lane l's pair is open (R.open, the separate contact phase's test); true if it overlaps.
__attribute__((always_inline)) inline bool overlap_test(BatchResults& R, const BatchParticles& P, int l) {
    const double ra = P.ra[l], rb = P.rb[l];
    const bool open = spheres_apart(lane(P.xa, l), lane(P.xb, l), ra, rb);
    R.open[l] = open ? 1.0 : 0.0;
    return !open;
}

/// Lanes [0, count) of P from the particle arrays, one double at a time (the rest stay as they
/// are, never used), and whether each pair is open; true if any overlaps.
inline bool load_particles_scalar(BatchParticles& P, BatchResults& R, const PairBatch& B, int count,
                                  const ParticleArrays& A, const BatchAhead& ahead) {
    bool any_overlap = false;
    for (int l = 0; l < count; ++l) {
        prefetch_ahead(ahead, l, A);
        const std::int32_t a = B.i[l], b = B.j[l];
        set_lane(P.xa, l, A.position[a]);
        set_lane(P.xb, l, A.position[b]);
        set_lane(P.va, l, A.velocity[a]);
        set_lane(P.vb, l, A.velocity[b]);
        set_lane(P.wa, l, A.spin[a]);
        set_lane(P.wb, l, A.spin[b]);
        P.ra[l] = A.radius[a];
        P.rb[l] = A.radius[b];
        any_overlap |= overlap_test(R, P, l);
    }
    return any_overlap;
}

#ifdef GRADEM_LANE_TRANSPOSE
/// The same lanes by transposes, four at a time (core/lane_load.hpp): the lanes up to the next
/// multiple of four past `count` are loaded too (the batch's lanes past the last pair hold
/// particle 0: pair_batch.hpp), and never used.
__attribute__((target("avx2"))) bool load_particles_transposed(BatchParticles& P, BatchResults& R, const PairBatch& B,
                                                               int count, const ParticleArrays& A, const BatchAhead& ahead) {
    bool any_overlap = false;
    for (int l0 = 0; l0 < count; l0 += 4) {
        const std::int32_t* a = &B.i[l0];
        const std::int32_t* b = &B.j[l0];
        transposed_lanes4(&P.xa[0][l0], &P.xa[1][l0], &P.xa[2][l0], A.position, a);
        transposed_lanes4(&P.xb[0][l0], &P.xb[1][l0], &P.xb[2][l0], A.position, b);
        transposed_lanes4(&P.va[0][l0], &P.va[1][l0], &P.va[2][l0], A.velocity, a);
        transposed_lanes4(&P.vb[0][l0], &P.vb[1][l0], &P.vb[2][l0], A.velocity, b);
        transposed_lanes4(&P.wa[0][l0], &P.wa[1][l0], &P.wa[2][l0], A.spin, a);
        transposed_lanes4(&P.wb[0][l0], &P.wb[1][l0], &P.wb[2][l0], A.spin, b);
        for (int l = l0; l < l0 + 4 && l < count; ++l) {
            prefetch_ahead(ahead, l, A);
            P.ra[l] = A.radius[B.i[l]];
            P.rb[l] = A.radius[B.j[l]];
            any_overlap |= overlap_test(R, P, l);
        }
    }
    return any_overlap;
}
#endif

/// Lanes [0, count) of P and the open test (R.open); true if any pair of the batch overlaps.
inline bool load_particles(BatchParticles& P, BatchResults& R, const PairBatch& B, int count, const ParticleArrays& A,
                           const BatchAhead& ahead, bool transpose) {
#ifdef GRADEM_LANE_TRANSPOSE
    if (transpose) return load_particles_transposed(P, R, B, count, A, ahead);
#else
    (void)transpose;
#endif
    return load_particles_scalar(P, R, B, count, A, ahead);
}

/// The scalars of one pass: the step, the contact law's parameters, and the bonds' stiffness,
/// section and friction parameters when every bond family has the same (`uniform`).
struct PassScalars {
    double dt;                    ///< [s]
    double contact_modulus;       ///< E* [Pa]
    double contact_ratio;         ///< k_n/k_s [-]
    double friction;              ///< μ [-]
    bool uniform;
    double radius_multiplier;     ///< λ̄ [-]
    double bond_modulus;          ///< Ē* [Pa]
    double bond_ratio;            ///< k̄_n/k̄_s [-]
    double tan_phi;               ///< tan φ̄ [-]
    double moment_factor;         ///< β̄ [-]
};

/// What acts on j from lane l's linear contact (compute_contacts()'s expressions): its force
/// and moment where the pair overlaps, zero where it is open; the contact's shear force
/// advanced in the batch (+0 when open) and its energies into R.
__attribute__((always_inline)) inline void lane_contact(PairBatch& B, BatchResults& R, int l, const PairState& s,
                                                        const PairKinematics& kin, const PassScalars& K, Vec3& force,
                                                        Vec3& torque) {
    const bool open = R.open[l] != 0.0;
    const double kn = contact_normal_stiffness(K.contact_modulus, s.ra, s.rb);
    LinearContactResult r = linear_contact(kn, kn / K.contact_ratio, K.friction, kin.gap,
                                           rotate_into_plane(lane(B.shear, l), kin), kin.du_shear);
    const Vec3 contact_force = r.normal_force * kin.normal + r.shear_force;
    const Vec3 contact_torque = cross(kin.arm_b, contact_force);
    set_lane(B.shear, l, select(open, Vec3{}, r.shear_force));
    R.contact_strain[l] = open ? 0.0 : r.strain_energy;
    R.contact_slip[l] = open ? 0.0 : r.slip_energy;
    force = select(open, Vec3{}, contact_force);
    torque = select(open, Vec3{}, contact_torque);
}

/// Lane l's bond through ParallelBondLaw::advance(), its state advanced in the batch (a dummy
/// in a lane without a bond: its state is then never read back); its failure code, stresses
/// and energy into R. Uniform: the bond's section and stiffness from the radii and K, as
/// World::refresh_bond_constants() computes them (the same expressions, so the same bits),
/// instead of from the lanes' copies (64 bytes per pair not read).
template <bool Uniform>
__attribute__((always_inline)) inline ParallelBondLaw::Advance lane_bond(PairBatch& B, BatchResults& R, int l, const PairState& s,
                                                                      const PairKinematics& kin, const PassScalars& K) {
    ParallelBond bond;
    bond.tensile_strength = B.tensile_strength[l];
    bond.cohesion = B.cohesion[l];
    bond.normal_force = B.normal_force[l];
    bond.shear_force = lane(B.shear_force, l);
    bond.twist_moment = B.twist_moment[l];
    bond.bend_moment = lane(B.bend_moment, l);
    BondSection sec;
    BondStiffness stiffness;
    // energy always computed here (a select on a loop-invariant bool does not vectorise);
    // the scalar loop keeps it only if tracked, as ParallelBondLaw::step() does
    ParallelBondLaw::Context ctx;
    if constexpr (Uniform) {
        sec = bond_section(K.radius_multiplier, s.ra, s.rb);
        stiffness = bond_stiffness(K.bond_modulus, K.bond_ratio, s.ra, s.rb);
        ctx = {K.tan_phi, K.moment_factor, true};
    } else {
        sec = bond_section_of_radius(B.radius[l], B.inv_radius[l]);
        stiffness = {B.kn[l], B.ks[l]};
        ctx = {B.tan_phi[l], B.moment_factor[l], true};
    }
    ParallelBondLaw::Advance adv = ParallelBondLaw::advance(ctx, bond, sec, stiffness, kin);
    B.normal_force[l] = bond.normal_force;
    set_lane(B.shear_force, l, bond.shear_force);
    B.twist_moment[l] = bond.twist_moment;
    set_lane(B.bend_moment, l, bond.bend_moment);
    R.failure[l] = B.bond[l] >= 0 ? static_cast<double>(static_cast<int>(adv.failure)) : kIntact;
    R.tensile[l] = adv.stress.tensile;
    R.shear_stress[l] = adv.stress.shear;
    R.bond_energy[l] = adv.energy;
    return adv;
}

/// The arithmetic of compute_contacts() (WithContact: some pair of the batch overlaps) and of
/// ParallelBondLaw::step() for every lane of a batch: the kinematics, the contact, the bond,
/// and what acts on j (the contact if it overlaps, then the bond if it holds, added after).
template <bool WithContact, bool Uniform>
__attribute__((always_inline, flatten)) inline void pair_batch_body(PairBatch& B, BatchResults& R, const BatchParticles& P,
                                                                  const PassScalars& K) {
#pragma GCC ivdep
    for (int l = 0; l < kLanes; ++l) {
        PairState s{lane(P.xa, l), lane(P.xb, l), lane(P.va, l), lane(P.vb, l),
                    lane(P.wa, l), lane(P.wb, l), P.ra[l],       P.rb[l]};
        // Aggregates not const: GCC keeps a const aggregate in memory (SRA refuses the store
        // of its return slot), and a struct in memory blocks the vectoriser.
        PairKinematics kin = pair_kinematics(s, K.dt);
        Vec3 force, torque;
        if constexpr (WithContact) lane_contact(B, R, l, s, kin, K, force, torque);
        else set_lane(B.shear, l, Vec3{});  // every pair of the batch is open
        ParallelBondLaw::Advance adv = lane_bond<Uniform>(B, R, l, s, kin, K);
        const bool holds = (B.bond[l] >= 0) & (adv.failure == BondState::intact);
        const Vec3 bond_torque = cross(kin.arm_b, adv.force_j) + adv.moment_j;
        const Vec3 force_j = select(holds, force + adv.force_j, force);
        const Vec3 torque_j = select(holds, torque + bond_torque, torque);
        set_lane(R.force, l, force_j);
        set_lane(R.torque, l, torque_j);
        set_lane(R.torque_i, l, moment_on_i(torque_j, force_j, s.xb - s.xa));
    }
}

// Function multiversioning: AVX-512 (8 lanes), AVX2 (4) and baseline (2) clones, picked at load time (the
// default build must run on any x86-64: no -march=native).
#if defined(__x86_64__) && defined(__GNUC__) && !defined(__clang__) && !defined(GRADEM_NO_CLONES)
#define GRADEM_LANES_CLONES __attribute__((target_clones("avx512f", "avx2", "default")))
#else
#define GRADEM_LANES_CLONES
#endif

GRADEM_LANES_CLONES __attribute__((flatten)) void contact_bond_lanes(PairBatch& B, BatchResults& R, const BatchParticles& P,
                                                                     const PassScalars& K) {
    pair_batch_body<true, false>(B, R, P, K);
}
GRADEM_LANES_CLONES __attribute__((flatten)) void bond_lanes(PairBatch& B, BatchResults& R, const BatchParticles& P,
                                                             const PassScalars& K) {
    pair_batch_body<false, false>(B, R, P, K);
}
GRADEM_LANES_CLONES __attribute__((flatten)) void contact_bond_lanes_uniform(PairBatch& B, BatchResults& R,
                                                                             const BatchParticles& P, const PassScalars& K) {
    pair_batch_body<true, true>(B, R, P, K);
}
GRADEM_LANES_CLONES __attribute__((flatten)) void bond_lanes_uniform(PairBatch& B, BatchResults& R, const BatchParticles& P,
                                                                     const PassScalars& K) {
    pair_batch_body<false, true>(B, R, P, K);
}

/// One batch through the kernel it needs: the contact's arithmetic only if a pair overlaps.
inline void run_batch(PairBatch& B, BatchResults& R, const BatchParticles& P, const PassScalars& K, bool any_overlap) {
    if (K.uniform) {
        if (any_overlap) contact_bond_lanes_uniform(B, R, P, K);
        else bond_lanes_uniform(B, R, P, K);
    } else {
        if (any_overlap) contact_bond_lanes(B, R, P, K);
        else bond_lanes(B, R, P, K);
    }
}

/// A bond's energy released by its break [J], kept per pair block in pair order (= bond order).
struct Released {
    std::int64_t bond;
    double energy;  ///< [J]
};

/// What one pair block hands back: its contact energies [J], break events and released energies.
struct BlockOut {
    double contact_strain = 0, contact_slip = 0;
    std::int64_t into_particles = 0;  ///< pairs added to both particles in the pass, no slot written
    std::vector<BreakEvent> breaks;
    std::vector<Released> released;
    /// A block's tail (BlockPart: another thread ran its head): its block, and its contact
    /// energy terms in pair order, added to the head's sums at the merge.
    std::int64_t tail_of = -1;
    std::vector<std::array<double, 2>> tail_terms;
};

/// A lane without an intact bond (pair_batch.hpp): a harmless dummy bond.
void clear_bond_lane(PairBatch& B, int l) {
    B.bond[l] = -1;
    B.normal_force[l] = B.twist_moment[l] = 0.0;
    for (int c = 0; c < 3; ++c) B.shear_force[c][l] = B.bend_moment[c][l] = 0.0;
    B.tensile_strength[l] = B.cohesion[l] = B.radius[l] = B.inv_radius[l] = B.kn[l] = B.ks[l] = 1.0;
    B.tan_phi[l] = B.moment_factor[l] = 0.0;
}

}  // namespace

/// The pass of compute_contacts_and_parallel_bonds, as a list of steps per batch of kPairLanes
/// pairs: the lane arithmetic in place, the results into the pair slots in pair order, and the
/// breaks. `Prefetch` compiles the stream prefetches in or out, so the in-cache loop is the one
/// without them.
struct World::ParallelBondPass {
    World& w;
    bool track;  ///< keep bond energies (sim_.track_energy)
    /// The particles whose pairs a thread's share of the pass holds (World::force_owner_: that
    /// thread's index) get each pair's force and moments added there, in pair order; a pair with
    /// a particle of no share writes its slot (SimParams::forces_in_pass). Null: every slot.
    const std::int16_t* owner = nullptr;
    bool transpose = lane_transpose_available();  ///< particles into lanes by transposes (core/lane_load.hpp)
    ParticleArrays particles;
    PassScalars scalars;
    int ahead_lines;  ///< 64-byte lines per lane that cover the part of a batch the kernel reads
    std::vector<BlockOut> blocks;  ///< per pair block (its head)
    std::vector<BlockOut> tails;   ///< per thread: the tail its share starts with, if any

    ParallelBondPass(World& world, double step)
        : w(world), track(world.sim_.track_energy),
          particles{w.particles_.position.data(), w.particles_.velocity.data(), w.particles_.spin.data(),
                    w.particles_.radius.data()},
          scalars(pass_scalars(world, step)),
          ahead_lines(static_cast<int>(((scalars.uniform ? offsetof(PairBatch, radius) : sizeof(PairBatch)) + 64 * kLanes - 1) /
                                       (64 * kLanes))) {
        blocks.resize(static_cast<std::size_t>(block_count(static_cast<std::int64_t>(w.pairs_.size()))));
    }

    /// The pass's scalars; uniform when every bond family pair has the parameters of the first.
    static PassScalars pass_scalars(const World& w, double dt) {
        const BondParams& first = w.bond_family_params_.front();
        const bool uniform = std::all_of(w.bond_family_params_.begin(), w.bond_family_params_.end(), [&](const BondParams& p) {
            return p.radius_multiplier == first.radius_multiplier && p.effective_modulus == first.effective_modulus &&
                   p.stiffness_ratio == first.stiffness_ratio && p.friction_angle_deg == first.friction_angle_deg &&
                   p.moment_factor == first.moment_factor;
        });
        const ParallelBondLaw::Context ctx = ParallelBondLaw::context(first, true);
        return {dt, w.contact_.effective_modulus, w.contact_.stiffness_ratio, w.contact_.friction, uniform,
                first.radius_multiplier, first.effective_modulus, first.stiffness_ratio, ctx.tan_phi, ctx.moment_factor};
    }

    /// Bytes the pass streams: batches and slots, stored bond energies, x v w r.
    [[nodiscard]] std::size_t streamed_bytes() const {
        return w.pair_batches_.size() * sizeof(PairBatch) + w.pairs_.size() * sizeof(PairOutput) +
               w.bonds_.size() * sizeof(double) + w.particles_.size() * (3 * sizeof(Vec3) + sizeof(double));
    }

    /// The batches to prefetch while the batch from k0 is loaded (BatchAhead).
    [[nodiscard]] BatchAhead ahead_of(std::int64_t k0, std::int64_t end) const {
        const auto batch_of = [&](std::int64_t k) -> const PairBatch& {
            return w.pair_batches_[static_cast<std::size_t>(std::min(k, end - 1) / kLanes)];
        };
        return {reinterpret_cast<const char*>(&batch_of(k0 + 2 * kLanes)), ahead_lines, &batch_of(k0 + kLanes),
                static_cast<int>(std::clamp<std::int64_t>(end - k0 - kLanes, 0, kLanes))};
    }

    /// Pairs [begin, end), a block part (its head: blocks[], its tail: tails[thread]), run by
    /// thread `thread` (its index in force owners).
    template <bool Prefetch>
    void block(const BlockPart& part, std::int16_t thread = 0) {
        if (part.head()) return block_part<Prefetch, false>(part, blocks[static_cast<std::size_t>(part.block)], thread);
        BlockOut& tail = tails[static_cast<std::size_t>(thread)];
        tail.tail_of = part.block;
        block_part<Prefetch, true>(part, tail, thread);
    }

    template <bool Prefetch, bool Tail>
    void block_part(const BlockPart& part, BlockOut& bo, std::int16_t thread) {
        const std::int64_t begin = part.begin, end = part.end;
        auto results = std::make_unique<BatchResults>();
        auto lanes = std::make_unique<BatchParticles>();  // lanes past the end of the pairs stay finite
        for (std::int64_t k0 = begin; k0 < end; k0 += kLanes) {
            PairBatch& B = w.pair_batches_[static_cast<std::size_t>(k0 / kLanes)];
            const int count = static_cast<int>(std::min<std::int64_t>(end - k0, kLanes));
            if constexpr (Prefetch) prefetch_slots(k0 + kLanes, end);
            const bool any_overlap = load_particles(*lanes, *results, B, count, particles, ahead_of(k0, end), transpose);
            run_batch(B, *results, *lanes, scalars, any_overlap);
            if (write_results<Tail>(k0, count, B, *results, bo, thread)) record_breaks(count, B, *results, bo);
        }
    }

    /// The output slots of the batch from k0 (with the stream prefetches: only out of cache,
    /// SimParams::stream_prefetch_above_bytes).
    __attribute__((always_inline)) inline void prefetch_slots(std::int64_t k0, std::int64_t end) const {
        if (k0 >= end) return;
        const int count = static_cast<int>(std::min<std::int64_t>(end - k0, kLanes));
        const auto* slots = reinterpret_cast<const char*>(&w.pair_out_[static_cast<std::size_t>(k0)]);
        for (std::size_t line = 0; line < static_cast<std::size_t>(count) * sizeof(PairOutput); line += 64)
            __builtin_prefetch(slots + line, 1);
    }

    /// The batch's results in pair order: each pair's output slot (or its force and moments
    /// added to its particles), the contact energies summed in pair order (Tail: kept in order
    /// for the head's sums), each holding bond's stored energy. True if a bond of the batch broke.
    template <bool Tail>
    __attribute__((always_inline)) inline bool write_results(std::int64_t k0, int count, const PairBatch& B,
                                                             const BatchResults& R, BlockOut& bo, std::int16_t thread) {
        bool any_break = false;
        double strain_sum = bo.contact_strain, slip_sum = bo.contact_slip;
        for (int l = 0; l < count; ++l) {
            if (owner && add_to_particles(B, R, l, thread)) {
                ++bo.into_particles;
            } else {
                PairOutput& out = w.pair_out_[static_cast<std::size_t>(k0 + l)];
                out.force_j = lane(R.force, l);
                out.torque_j = lane(R.torque, l);
                out.torque_i = lane(R.torque_i, l);
            }
            if (R.open[l] == 0.0) {
                if constexpr (Tail) {
                    bo.tail_terms.push_back({R.contact_strain[l], R.contact_slip[l]});
                } else {
                    strain_sum += R.contact_strain[l];
                    slip_sum += R.contact_slip[l];
                }
            }
            const std::int32_t bk = B.bond[l];
            if (bk < 0) continue;
            if (R.failure[l] != kIntact) {
                any_break = true;
                continue;
            }
            w.bond_stored_[static_cast<std::size_t>(bk)] = track ? R.bond_energy[l] : 0.0;
        }
        bo.contact_strain = strain_sum;
        bo.contact_slip = slip_sum;
        return any_break;
    }

    /// Lane l's force and moments added to those of its particles this thread owns
    /// (add_to_owned_particles). A share runs in pair order, which is every particle's gather
    /// order, so each sum takes its terms in the gather's order. True if both particles took
    /// them (the slot is then not needed).
    __attribute__((always_inline)) inline bool add_to_particles(const PairBatch& B, const BatchResults& R, int l,
                                                                std::int16_t thread) {
        const auto i = static_cast<std::size_t>(B.i[l]), j = static_cast<std::size_t>(B.j[l]);
        const bool own_i = owner[i] == thread, own_j = owner[j] == thread;
        add_to_owned_particles(w.particles_.force.data(), w.particles_.torque.data(), i, j, own_i, own_j, lane(R.force, l),
                               lane(R.torque, l), lane(R.torque_i, l));
        return own_i & own_j;
    }

    /// Breaks (rare), in pair order = bond order: the event with the crack's geometry (the
    /// kinematics again: a pure function, the same bits), the release, the released energy; the
    /// lane becomes a dummy.
    void record_breaks(int count, PairBatch& B, const BatchResults& R, BlockOut& bo) {
        for (int l = 0; l < count; ++l) {
            if (B.bond[l] < 0 || R.failure[l] == kIntact) continue;
            const auto bk = static_cast<std::size_t>(B.bond[l]);
            ParallelBond& b = w.bonds_[bk];
            const auto failure = static_cast<BondState>(static_cast<int>(R.failure[l]));
            const auto i = static_cast<std::size_t>(b.i), j = static_cast<std::size_t>(b.j);
            const PairState s{w.particles_.position[i], w.particles_.position[j], w.particles_.velocity[i], w.particles_.velocity[j],
                              w.particles_.spin[i],     w.particles_.spin[j],     w.particles_.radius[i],   w.particles_.radius[j]};
            const PairKinematics kin = pair_kinematics(s, scalars.dt);
            bo.breaks.push_back({w.step_, w.time_, B.bond[l], b.i, b.j, failure, s.xa + kin.arm_a + Vec3{}, kin.normal, B.radius[l],
                                 R.tensile[l], R.shear_stress[l], -1});
            release_bond(b, failure);
            w.bond_stored_[bk] = 0.0;
            bo.released.push_back({B.bond[l], track ? R.bond_energy[l] : 0.0});
            clear_bond_lane(B, l);
        }
    }

    /// The blocks' sums in block order (a block's head, then its tails in pair order): contact
    /// energies into `strain` and `slip`, breaks into the World's list; bond energies per fixed
    /// bond block (see the top of this file).
    BondEnergy merge(double& strain, double& slip) {
        const auto nb = static_cast<std::int64_t>(w.bonds_.size());
        double contact_strain = 0, contact_slip = 0;
        std::vector<BondEnergy> bond_partial(static_cast<std::size_t>(block_count(nb)));
        const auto add_events = [&](const BlockOut& bo) {
            w.breaks_.insert(w.breaks_.end(), bo.breaks.begin(), bo.breaks.end());
            for (const Released& x : bo.released) {
                BondEnergy& e = bond_partial[static_cast<std::size_t>(x.bond / kBlockSize)];
                e.released += x.energy;
                ++e.releases;
            }
            w.profile_.pair_steps_into_particles += bo.into_particles;
        };
        for (std::size_t b = 0; b < blocks.size(); ++b) {
            BlockOut& head = blocks[b];
            add_events(head);
            for (const BlockOut& tail : tails) {  // shares are in thread order = pair order
                if (tail.tail_of != static_cast<std::int64_t>(b)) continue;
                for (const auto& [stored, slipped] : tail.tail_terms) {
                    head.contact_strain += stored;
                    head.contact_slip += slipped;
                }
                add_events(tail);
            }
            contact_strain += head.contact_strain;
            contact_slip += head.contact_slip;
        }
        strain = contact_strain;
        slip = contact_slip;
        if (track)
            for_each_block(nb, [&](std::int64_t begin, std::int64_t end, std::int64_t blk) {
                double stored = 0;
                for (std::int64_t k = begin; k < end; ++k) stored += w.bond_stored_[static_cast<std::size_t>(k)];
                bond_partial[static_cast<std::size_t>(blk)].stored = stored;
            });
        return ordered_sum(bond_partial);
    }
};

World::BondEnergy World::compute_contacts_and_parallel_bonds(double dt, double& strain, double& slip) {
    if (bond_const_stale_) {
        write_back_pair_batches();
        refresh_bond_constants();
        pair_batches_current_ = false;
    }
    if (!pair_batches_current_) build_pair_batches();
    bond_stored_.resize(bonds_.size(), 0.0);
    ParallelBondPass pass(*this, dt);
    const auto m = static_cast<std::int64_t>(pairs_.size());
    forces_from_pass_ = sim_.forces_in_pass;
    if (forces_from_pass_) {  // each thread its share of the pairs (share_pass), in order
        pass.tails.resize(static_cast<std::size_t>(thread_count()));
        share_seconds_.resize(static_cast<std::size_t>(thread_count()), 0.0);
        int team_run = 1;
#pragma omp parallel
        {
            const int team = team_size();
            const auto t = static_cast<std::int16_t>(thread_index());
            const auto n = static_cast<std::int64_t>(particles_.size());
            const auto [p0, p1] = item_share(particle_share_, n, team, t);
            std::fill(particles_.force.begin() + p0, particles_.force.begin() + p1, Vec3{});
            std::fill(particles_.torque.begin() + p0, particles_.torque.begin() + p1, Vec3{});
#pragma omp barrier
#pragma omp single
            {
                if (force_owner_team_ != team) build_force_owners(team);
                pass.owner = force_owner_.data();
                team_run = team;
            }  // (a barrier)
            run_timed_share(pass_share_, m, team, t, share_seconds_, [&](const BlockPart& part) { pass.block<false>(part, t); });
        }
        balance_pass_shares(team_run);
    } else {
        const bool prefetch_streams = pass.streamed_bytes() > sim_.stream_prefetch_above_bytes;
        for_each_block(m, [&](std::int64_t begin, std::int64_t end, std::int64_t blk) {
            const BlockPart whole{begin, end, blk};
            if (prefetch_streams) pass.block<true>(whole);
            else pass.block<false>(whole);
        });
    }
    pair_out_stale_ = forces_from_pass_;
    records_behind_batches_ = true;
    return pass.merge(strain, slip);
}

// Each particle's force owner for a team of `team` threads: the thread whose share of the pass
// holds both its first and its last pair (so all of them: the shares are contiguous), else -1.
// A particle's incidence list is in pair order, so those are its list's ends. The flat joint's
// pass runs over the bonds (in pair order too): there a particle's pairs must all be acting
// joints (the contacts phase writes the others' slots), and the shares cut the bonds.
void World::build_force_owners(int team) {
    const bool over_bonds = bond_params_.model != BondModel::parallel_bond;
    const auto unit = [&](std::int32_t slot) -> std::int64_t {  // the pass's index of pair `slot`
        return over_bonds ? pairs_[static_cast<std::size_t>(slot)].bond : slot;
    };
    const auto passed = [&](const Incidence& e) {  // the pass (not the contacts phase) sets the pair
        const std::int32_t bond = pairs_[static_cast<std::size_t>(e.slot)].bond;
        return bond >= 0 && bond_acts(bonds_[static_cast<std::size_t>(bond)]);
    };
    share_pass(team, over_bonds);
    const auto thread_of = [&](std::int64_t unit) -> std::int16_t {  // the share that runs unit
        const auto above = std::upper_bound(pass_share_.begin() + 1, pass_share_.end() - 1, unit);
        return static_cast<std::int16_t>(above - (pass_share_.begin() + 1));
    };
    force_owner_.assign(particles_.size(), -1);
    for (std::size_t p = 0; p < particles_.size(); ++p) {
        const std::int32_t begin = incidence_start_[p], end = incidence_start_[p + 1];
        if (begin == end) continue;
        if (over_bonds && !std::all_of(incidence_.begin() + begin, incidence_.begin() + end, passed)) continue;
        const std::int16_t first = thread_of(unit(incidence_[static_cast<std::size_t>(begin)].slot));
        const std::int16_t last = thread_of(unit(incidence_[static_cast<std::size_t>(end - 1)].slot));
        if (first == last) force_owner_[p] = first;
    }
    force_owner_team_ = team;
}

// The pass with forces into particles shared by a team of `team` threads (the parallel bond's
// over the pairs, the flat joint's over the bonds): runs of whole batches of 32 in proportion to
// the threads' weights (SimParams::thread_share_weights, else their measured speeds, else
// equal; the shares need not fall on block bounds: BlockPart), and the particle phases (zeroing
// the sums, integration, gather) cut where the pass's shares are, at each share's first pair's
// particle i (pairs and bonds are in (i, j) order), so each thread integrates the particles it
// added forces to, and the threads' loads are even to a batch rather than to a 2048-item block.
void World::share_pass(int team, bool over_bonds) {
    const auto m = static_cast<std::int64_t>(over_bonds ? bonds_.size() : pairs_.size());
    const auto first_particle = [&](std::int64_t k) {
        return over_bonds ? bonds_[static_cast<std::size_t>(k)].i : pairs_[static_cast<std::size_t>(k)].i;
    };
    const auto n = static_cast<std::int64_t>(particles_.size());
    const auto teamsize = static_cast<std::size_t>(team);
    std::vector<double> weight(teamsize, 1.0);
    if (sim_.thread_share_weights.size() == teamsize) weight = sim_.thread_share_weights;
    else if (share_speed_.size() == teamsize) weight = share_speed_;
    double total = 0.0;
    for (const double x : weight) total += x;
    pass_share_.assign(teamsize + 1, m);
    particle_share_.assign(teamsize + 1, n);
    pass_share_[0] = particle_share_[0] = 0;
    double before = 0.0;
    for (std::size_t t = 1; t < teamsize; ++t) {
        before += weight[t - 1];
        const auto k = std::min(m, static_cast<std::int64_t>(static_cast<double>(m) * (before / total)) / kLanes * kLanes);
        pass_share_[t] = std::max(k, pass_share_[t - 1]);
        particle_share_[t] = pass_share_[t] < m ? first_particle(pass_share_[t]) : n;
    }
}

// Every kShareWindow steps of the pass on more than one thread (and no fixed weights), each
// thread's speed (its pairs or bonds per second in its share) becomes its weight when shares cut
// by these speeds would shorten the slowest thread's time by more than kShareGain; the force
// owners are then built again at the next pass. Timing moves only the cut, never the results.
void World::balance_pass_shares(int team) {
    constexpr std::int64_t kShareWindow = 64;
    constexpr double kShareGain = 0.03;
    const auto teamsize = static_cast<std::size_t>(team);
    if (team < 2 || !sim_.thread_share_weights.empty() || pass_share_.size() != teamsize + 1) return;
    if (++share_window_steps_ < kShareWindow) return;
    std::vector<double> speed(teamsize);
    double slowest = 0.0, total_pairs = 0.0, total_speed = 0.0;
    for (std::size_t t = 0; t < teamsize; ++t) {
        const auto pairs = static_cast<double>(pass_share_[t + 1] - pass_share_[t]);
        const double seconds = share_seconds_[t];
        if (!(pairs > 0.0 && seconds > 0.0)) return share_window_reset();
        speed[t] = pairs / seconds;
        slowest = std::max(slowest, seconds);
        total_pairs += pairs;
        total_speed += speed[t];
    }
    const double balanced = total_pairs / total_speed;  // every thread's time with shares by speed
    if (balanced < (1.0 - kShareGain) * slowest) {
        share_speed_ = speed;
        force_owner_team_ = 0;
    }
    share_window_reset();
}

// The slots the pass did not write (forces_from_pass_), as its kernel computes them
// (pair_batch_body), from what it left: each pair's contact shear force and its intact bond's
// forces and moments in the batches (a bond broken in that step is no longer in its lane), and
// the positions the forces were evaluated at. The same functions in the same order, so the same
// bits (tests/core/test_pair_pass.cpp). The kinematics' velocity terms are not used.
void World::rebuild_pair_outputs() {
    pair_out_stale_ = false;
    if (bond_params_.model == BondModel::flat_joint) {
        FlatJointLaw::rebuild_slots(bond_pass());
        return;
    }
    const auto m = static_cast<std::int64_t>(pairs_.size());
    const ParticleSet& P = particles_;
    for_each_block(m, [&](std::int64_t begin, std::int64_t end, std::int64_t) {
        for (std::int64_t k = begin; k < end; ++k) {
            const PairBatch& B = pair_batches_[static_cast<std::size_t>(k / kLanes)];
            const int l = static_cast<int>(k % kLanes);
            const auto i = static_cast<std::size_t>(B.i[l]), j = static_cast<std::size_t>(B.j[l]);
            const PairState s{P.position[i], P.position[j], P.velocity[i], P.velocity[j],
                              P.spin[i],     P.spin[j],     P.radius[i],   P.radius[j]};
            const PairKinematics kin = pair_kinematics(s, 0.0);
            Vec3 force, torque;  // the contact's (overlap_test, lane_contact): none when open
            if (!spheres_apart(s.xa, s.xb, s.ra, s.rb)) {
                const double kn = contact_normal_stiffness(contact_.effective_modulus, s.ra, s.rb);
                const Vec3 contact_force = linear_contact_normal_force(kn, kin.gap) * kin.normal + lane(B.shear, l);
                force = contact_force;
                torque = cross(kin.arm_b, contact_force);
            }
            if (B.bond[l] >= 0) {  // the bond holds (ParallelBondLaw::advance's outputs)
                ParallelBond bond;
                bond.normal_force = B.normal_force[l];
                bond.shear_force = lane(B.shear_force, l);
                bond.twist_moment = B.twist_moment[l];
                bond.bend_moment = lane(B.bend_moment, l);
                const Vec3 bond_force = bond_force_on_j(bond, kin.normal);
                const Vec3 bond_torque = cross(kin.arm_b, bond_force) + bond_moment_on_j(bond, kin.normal);
                force = force + bond_force;
                torque = torque + bond_torque;
            }
            PairOutput& out = pair_out_[static_cast<std::size_t>(k)];
            out.force_j = force;
            out.torque_j = torque;
            out.torque_i = moment_on_i(torque, force, s.xb - s.xa);
        }
    });
}

// The batches from the pair and bond records (pair_batch.hpp), one block of pairs per task.
void World::build_pair_batches() {
    const auto m = static_cast<std::int64_t>(pairs_.size());
    pair_batches_.resize(pair_batch_count(pairs_.size()));
    std::vector<ParallelBondLaw::Context> contexts;  // one per bond family pair
    for (const BondParams& p : bond_family_params_) contexts.push_back(ParallelBondLaw::context(p, true));
    for_each_block(m, [&](std::int64_t begin, std::int64_t end, std::int64_t) {
        for (std::int64_t k0 = begin; k0 < end; k0 += kLanes) {
            PairBatch& B = pair_batches_[static_cast<std::size_t>(k0 / kLanes)];
            for (int l = 0; l < kLanes; ++l) {
                const std::int64_t k = k0 + l;
                clear_bond_lane(B, l);
                if (k >= m) {  // past the end: particle 0 with itself, never written back
                    B.i[l] = B.j[l] = 0;
                    set_lane(B.shear, l, {});
                    continue;
                }
                const Pair& p = pairs_[static_cast<std::size_t>(k)];
                B.i[l] = p.i;
                B.j[l] = p.j;
                set_lane(B.shear, l, p.shear_force);
                if (p.bond < 0 || bonds_[static_cast<std::size_t>(p.bond)].state != BondState::intact) continue;
                const ParallelBond& bd = bonds_[static_cast<std::size_t>(p.bond)];
                const BondConstants& bc = bond_const_[static_cast<std::size_t>(p.bond)];
                const ParallelBondLaw::Context& ctx = contexts[bd.family_pair];
                B.bond[l] = p.bond;
                B.normal_force[l] = bd.normal_force;
                set_lane(B.shear_force, l, bd.shear_force);
                B.twist_moment[l] = bd.twist_moment;
                set_lane(B.bend_moment, l, bd.bend_moment);
                B.tensile_strength[l] = bd.tensile_strength;
                B.cohesion[l] = bd.cohesion;
                B.radius[l] = bc.radius;
                B.inv_radius[l] = bc.inv_radius;
                B.kn[l] = bc.stiffness.normal;
                B.ks[l] = bc.stiffness.shear;
                B.tan_phi[l] = ctx.tan_phi;
                B.moment_factor[l] = ctx.moment_factor;
            }
        }
    });
    pair_batches_current_ = true;
    records_behind_batches_ = false;
}

// The contact shear forces and the intact bonds' forces and moments from the batches back into
// the pair and bond records (a no-op when the records are current).
void World::write_back_pair_batches() {
    if (!records_behind_batches_) return;
    const auto m = static_cast<std::int64_t>(pairs_.size());
    for_each_block(m, [&](std::int64_t begin, std::int64_t end, std::int64_t) {
        for (std::int64_t k = begin; k < end; ++k) {
            const PairBatch& B = pair_batches_[static_cast<std::size_t>(k / kLanes)];
            const int l = static_cast<int>(k % kLanes);
            pairs_[static_cast<std::size_t>(k)].shear_force = lane(B.shear, l);
            if (B.bond[l] < 0) continue;
            ParallelBond& bd = bonds_[static_cast<std::size_t>(B.bond[l])];
            bd.normal_force = B.normal_force[l];
            bd.shear_force = lane(B.shear_force, l);
            bd.twist_moment = B.twist_moment[l];
            bd.bend_moment = lane(B.bend_moment, l);
        }
    });
    records_behind_batches_ = false;
}

}  // namespace gradem
