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
// Vectorised across pairs: each block of pairs is cut into batches of kLanes; a scalar scan
// copies the inputs of the pairs that need work into structure-of-arrays lanes (overlapping
// pairs in one set, open bonded pairs in another), one loop runs the kinematics, contact and
// bond arithmetic over the lanes (branch-free kernels, compiled for AVX-512, AVX2
// and for the baseline ISA with function multiversioning), and a scalar pass writes the results
// back in pair order. Each lane does the same IEEE operations in the same order as the scalar
// code (-ffp-contract=off: no FMA; no reassociation), so the results are bitwise the same.
#include <algorithm>
#include <bit>
#include <cstddef>
#include <memory>
#include <type_traits>

#include "core/contact_law.hpp"
#include "core/parallel.hpp"
#include "core/parallel_bond_law.hpp"
#include "core/world.hpp"

namespace gradem {
namespace {

constexpr int kLanes = 32;
constexpr std::int64_t kPrefetchAhead = 16;  ///< pairs: particle j's state (a random access)
constexpr std::int64_t kStreamAhead = 32;    ///< pairs: the pair's bond, constants and output slot
// The streams are prefetched only when the pass's arrays outgrow a last-level cache
// (SimParams::stream_prefetch_above_bytes: the development machine's L3, 32 MiB; sysconf
// reports the host's 384 MiB there). In cache the prefetches are extra instructions (-1..2 % at
// N = 2e4, 14 MB); from memory they save 14 % of the pass (N = 2e5, 125 MB).

/// Inputs and results of up to kLanes pairs, one array per scalar (structure of arrays).
struct Lanes {
    int count = 0;
    std::int64_t pair[kLanes];     ///< pair index
    std::int32_t bond[kLanes];     ///< bond index, -1: not bonded
    // inputs: the pair's particles, the stored contact shear force, the bond (bonded lanes)
    double xa[3][kLanes], xb[3][kLanes], va[3][kLanes], vb[3][kLanes], wa[3][kLanes], wb[3][kLanes];
    double ra[kLanes], rb[kLanes];
    double shear[3][kLanes];
    double fn[kLanes], fs[3][kLanes], mt[kLanes], mb[3][kLanes];
    double strength[kLanes], cohesion[kLanes], radius[kLanes], inv_radius[kLanes];
    double kn[kLanes], ks[kLanes], tan_phi[kLanes], beta[kLanes];
    // results: contact (shear force, output force and torque on j, energies) ...
    double c_shear[3][kLanes], c_force[3][kLanes], c_torque[3][kLanes], c_strain[kLanes], c_slip[kLanes];
    // ... and bond (advanced state, failure code, peak stresses, energy, force and torque on j)
    double failure[kLanes], tensile[kLanes], shear_stress[kLanes], energy[kLanes];
    double b_force[3][kLanes], b_torque[3][kLanes];
};

/// v = +0 without a store when it already is +0 (bit for bit): an open pair's stored shear force
/// stays zero step after step, and a pair record that is not written is not written back to
/// memory (40 B per pair and step at N = 2e5, where the pass is limited by memory traffic).
inline void clear_shear(Vec3& v) {
    if ((std::bit_cast<std::uint64_t>(v.x) | std::bit_cast<std::uint64_t>(v.y) | std::bit_cast<std::uint64_t>(v.z)) != 0)
        v = {};
}

inline Vec3 lane(const double (&a)[3][kLanes], int l) { return {a[0][l], a[1][l], a[2][l]}; }
inline void set_lane(double (&a)[3][kLanes], int l, const Vec3& v) {
    a[0][l] = v.x;
    a[1][l] = v.y;
    a[2][l] = v.z;
}

/// The arithmetic of compute_contacts() (WithContact) and of ParallelBondLaw::step() for every
/// lane; the caller keeps the results it needs.
template <bool WithContact>
__attribute__((always_inline, flatten)) inline void pair_lanes_body(Lanes& L, double dt, double e_contact, double ratio_contact,
                            double friction) {
    const int n = L.count;
#pragma GCC ivdep
    for (int l = 0; l < n; ++l) {
        PairState s{lane(L.xa, l), lane(L.xb, l), lane(L.va, l), lane(L.vb, l),
                          lane(L.wa, l), lane(L.wb, l), L.ra[l], L.rb[l]};
        // Aggregates not const: GCC keeps a const aggregate in memory (SRA refuses the store
        // of its return slot), and a struct in memory blocks the vectoriser.
        PairKinematics kin = pair_kinematics(s, dt);
        if constexpr (WithContact) {
            const double kn = contact_normal_stiffness(e_contact, s.ra, s.rb);
            LinearContactResult r = linear_contact(kn, kn / ratio_contact, friction, kin.gap,
                                                         rotate_into_plane(lane(L.shear, l), kin), kin.du_shear);
            const Vec3 force = r.normal_force * kin.normal + r.shear_force;
            set_lane(L.c_shear, l, r.shear_force);
            set_lane(L.c_force, l, force);
            set_lane(L.c_torque, l, cross(kin.arm_b, force));
            L.c_strain[l] = r.strain_energy;
            L.c_slip[l] = r.slip_energy;
        }
        ParallelBond b;
        b.tensile_strength = L.strength[l];
        b.cohesion = L.cohesion[l];
        b.normal_force = L.fn[l];
        b.shear_force = lane(L.fs, l);
        b.twist_moment = L.mt[l];
        b.bend_moment = lane(L.mb, l);
        BondSection sec = bond_section_of_radius(L.radius[l], L.inv_radius[l]);
        // energy always computed here (a select on a loop-invariant bool does not vectorise);
        // the write-back keeps it only if tracked, as ParallelBondLaw::step() does
        const ParallelBondLaw::Context ctx{L.tan_phi[l], L.beta[l], true};
        ParallelBondLaw::Advance a = ParallelBondLaw::advance(ctx, b, sec, {L.kn[l], L.ks[l]}, kin);
        L.fn[l] = b.normal_force;
        set_lane(L.fs, l, b.shear_force);
        L.mt[l] = b.twist_moment;
        set_lane(L.mb, l, b.bend_moment);
        L.failure[l] = static_cast<double>(static_cast<int>(a.failure));
        L.tensile[l] = a.stress.tensile;
        L.shear_stress[l] = a.stress.shear;
        L.energy[l] = a.energy;
        set_lane(L.b_force, l, a.force_j);
        set_lane(L.b_torque, l, cross(kin.arm_b, a.force_j) + a.moment_j);
    }
}

// Function multiversioning: AVX-512 (8 lanes), AVX2 (4) and baseline (2) clones, picked at load time (the
// default build must run on any x86-64: no -march=native).
#if defined(__x86_64__) && defined(__GNUC__) && !defined(__clang__) && !defined(GRADEM_NO_CLONES)
#define GRADEM_LANES_CLONES __attribute__((target_clones("avx512f", "avx2", "default")))
#else
#define GRADEM_LANES_CLONES
#endif

GRADEM_LANES_CLONES __attribute__((flatten)) void contact_lanes(Lanes& L, double dt, double e, double ratio, double mu) {
    pair_lanes_body<true>(L, dt, e, ratio, mu);
}
GRADEM_LANES_CLONES __attribute__((flatten)) void bond_lanes(Lanes& L, double dt) {
    pair_lanes_body<false>(L, dt, 0.0, 1.0, 0.0);
}

}  // namespace

namespace {

/// A bond's energy released by its break [J], kept per pair block in pair order (= bond order).
struct Released {
    std::int64_t bond;
    double energy;  ///< [J]
};

/// What one pair block hands back: its contact energies [J], break events and released energies.
struct BlockOut {
    double contact_strain = 0, contact_slip = 0;
    std::vector<BreakEvent> breaks;
    std::vector<Released> released;
};

/// Where each pair of a batch went: -1 nothing acts, 0 a lane of the overlapping set, 1 a lane
/// of the open bonded set; and its lane index.
struct BatchSlots {
    std::int8_t where[kLanes];
    std::int8_t which[kLanes];
};

constexpr double kIntact = static_cast<double>(static_cast<int>(BondState::intact));

}  // namespace

/// The pass of compute_contacts_and_parallel_bonds, as a list of steps per batch of kLanes
/// pairs: scan (which pairs need work, their inputs into lanes), the lane arithmetic, the
/// results back in pair order, and the breaks. `Prefetch` compiles the stream prefetches in
/// or out, so the in-cache loop is the one without them.
struct World::ParallelBondPass {
    World& w;
    double dt;
    bool track;  ///< keep bond energies (sim_.track_energy)
    std::vector<ParallelBondLaw::Context> contexts;  ///< one per bond family pair
    std::vector<BlockOut> blocks;

    ParallelBondPass(World& world, double step) : w(world), dt(step), track(world.sim_.track_energy) {
        for (const BondParams& p : w.bond_family_params_) contexts.push_back(ParallelBondLaw::context(p, track));
        blocks.resize(static_cast<std::size_t>(block_count(static_cast<std::int64_t>(w.pairs_.size()))));
    }

    /// Bytes the pass streams: pair records and slots, bonds, constants and energies, x v w r.
    [[nodiscard]] std::size_t streamed_bytes() const {
        return w.pairs_.size() * (sizeof(Pair) + sizeof(PairOutput)) +
               w.bonds_.size() * (sizeof(ParallelBond) + sizeof(BondConstants) + sizeof(double)) +
               w.particles_.size() * (3 * sizeof(Vec3) + sizeof(double));
    }

    template <bool Prefetch>
    void block(std::int64_t begin, std::int64_t end, std::int64_t blk) {
        BlockOut& bo = blocks[static_cast<std::size_t>(blk)];
        auto lanes = std::make_unique_for_overwrite<Lanes[]>(2);  // no zero-fill of 2 x 26 kB per block
        Lanes& C = lanes[0];  // overlapping pairs: contact, and bond if bonded
        Lanes& B = lanes[1];  // open bonded pairs: bond only
        BatchSlots slots;
        for (std::int64_t b0 = begin; b0 < end; b0 += kLanes) {
            const std::int64_t b1 = std::min(end, b0 + kLanes);
            scan<Prefetch>(b0, b1, end, lanes.get(), slots);
            if (C.count > 0) contact_lanes(C, dt, w.contact_.effective_modulus, w.contact_.stiffness_ratio, w.contact_.friction);
            if (B.count > 0) bond_lanes(B, dt);
            if (write_back(C, B, bo)) record_breaks(b0, b1, lanes.get(), slots, bo);
        }
    }

    /// 1. Which pairs of [b0, b1) need work; their inputs copied into lanes (the lane set is
    ///    picked by index, not by a branch: open/closed is a coin flip in a loaded test).
    template <bool Prefetch>
    __attribute__((always_inline)) inline void scan(std::int64_t b0, std::int64_t b1, std::int64_t end, Lanes* lanes,
                                                    BatchSlots& slots) {
        int count[2] = {0, 0};  // counters in registers
        for (std::int64_t k = b0; k < b1; ++k) {
            prefetch_ahead<Prefetch>(k, end);
            Pair& p = w.pairs_[static_cast<std::size_t>(k)];
            const auto i = static_cast<std::size_t>(p.i), j = static_cast<std::size_t>(p.j);
            const double ra = w.particles_.radius[i], rb = w.particles_.radius[j];
            const Vec3 d = w.particles_.position[j] - w.particles_.position[i];
            const bool bonded = p.bond >= 0 && w.bonds_[static_cast<std::size_t>(p.bond)].state == BondState::intact;
            const bool open = norm2(d) >= (ra + rb) * (ra + rb);
            const auto slot = static_cast<std::size_t>(k - b0);
            if (__builtin_expect(static_cast<int>(open) & static_cast<int>(!bonded), 0)) {  // nothing acts
                slots.where[slot] = -1;
                clear_shear(p.shear_force);
                w.pair_out_[static_cast<std::size_t>(k)] = {};
                continue;
            }
            Lanes& L = lanes[static_cast<std::size_t>(open)];
            const int l = open ? count[1] : count[0];
            count[1] += open;
            count[0] += !open;
            slots.where[slot] = static_cast<std::int8_t>(open);
            slots.which[slot] = static_cast<std::int8_t>(l);
            load_pair(L, l, k, p, bonded);
        }
        lanes[0].count = count[0];
        lanes[1].count = count[1];
    }

    /// Prefetches for pair k: particle j of a pair a few pairs ahead (a random access: pairs are
    /// sorted by i, so i streams, and the hardware does not prefetch j); with Prefetch, the
    /// streams of the pair a batch ahead (bond, bond constants, stored energy, output slot, and
    /// the pair record further on): ~10 concurrent streams at N = 2e5 outrun the hardware
    /// prefetcher (only out of cache: SimParams::stream_prefetch_above_bytes).
    template <bool Prefetch>
    __attribute__((always_inline)) inline void prefetch_ahead(std::int64_t k, std::int64_t end) const {
        if (k + kPrefetchAhead < end) {
            const auto jn = static_cast<std::size_t>(w.pairs_[static_cast<std::size_t>(k + kPrefetchAhead)].j);
            __builtin_prefetch(&w.particles_.position[jn]);
            __builtin_prefetch(&w.particles_.velocity[jn]);
            __builtin_prefetch(&w.particles_.spin[jn]);
            __builtin_prefetch(&w.particles_.radius[jn]);
        }
        if constexpr (Prefetch) if (k + kStreamAhead < end) {
            const auto ka = static_cast<std::size_t>(k + kStreamAhead);
            __builtin_prefetch(&w.pair_out_[ka], 1);
            __builtin_prefetch(&w.pairs_[std::min(ka + kStreamAhead, w.pairs_.size() - 1)]);
            if (const std::int32_t bond = w.pairs_[ka].bond; bond >= 0) {
                const auto* record = reinterpret_cast<const char*>(&w.bonds_[static_cast<std::size_t>(bond)]);
                __builtin_prefetch(record + offsetof(ParallelBond, state), 1);  // a bond spans two lines
                __builtin_prefetch(record + sizeof(ParallelBond) - 1, 1);
                __builtin_prefetch(&w.bond_const_[static_cast<std::size_t>(bond)]);
                __builtin_prefetch(&w.bond_stored_[static_cast<std::size_t>(bond)], 1);
            }
        }
    }

    /// Lane l of L: pair k's particles, its stored contact shear force, and its bond (a harmless
    /// dummy bond, whose results are not used, when it is not bonded).
    __attribute__((always_inline)) inline void load_pair(Lanes& L, int l, std::int64_t k, const Pair& p, bool bonded) const {
        const auto i = static_cast<std::size_t>(p.i), j = static_cast<std::size_t>(p.j);
        L.pair[l] = k;
        L.bond[l] = bonded ? p.bond : -1;
        set_lane(L.xa, l, w.particles_.position[i]);
        set_lane(L.xb, l, w.particles_.position[j]);
        set_lane(L.va, l, w.particles_.velocity[i]);
        set_lane(L.vb, l, w.particles_.velocity[j]);
        set_lane(L.wa, l, w.particles_.spin[i]);
        set_lane(L.wb, l, w.particles_.spin[j]);
        L.ra[l] = w.particles_.radius[i];
        L.rb[l] = w.particles_.radius[j];
        set_lane(L.shear, l, p.shear_force);
        if (!bonded) {
            L.fn[l] = L.mt[l] = 0.0;
            set_lane(L.fs, l, {});
            set_lane(L.mb, l, {});
            L.strength[l] = L.cohesion[l] = 1.0;
            L.radius[l] = L.inv_radius[l] = L.kn[l] = L.ks[l] = 1.0;
            L.tan_phi[l] = L.beta[l] = 0.0;
            return;
        }
        const ParallelBond& bd = w.bonds_[static_cast<std::size_t>(p.bond)];
        const BondConstants& bc = w.bond_const_[static_cast<std::size_t>(p.bond)];
        const ParallelBondLaw::Context& ctx = contexts[bd.family_pair];
        L.fn[l] = bd.normal_force;
        set_lane(L.fs, l, bd.shear_force);
        L.mt[l] = bd.twist_moment;
        set_lane(L.mb, l, bd.bend_moment);
        L.strength[l] = bd.tensile_strength;
        L.cohesion[l] = bd.cohesion;
        L.radius[l] = bc.radius;
        L.inv_radius[l] = bc.inv_radius;
        L.kn[l] = bc.stiffness.normal;
        L.ks[l] = bc.stiffness.shear;
        L.tan_phi[l] = ctx.tan_phi;
        L.beta[l] = ctx.moment_factor;
    }

    /// 3. Results back. Contact lanes in pair order (so the energies are summed in pair order):
    ///    contact output first, then the bond's part, as the separate phases did. True if a
    ///    bond of the batch broke.
    __attribute__((always_inline)) inline bool write_back(const Lanes& C, const Lanes& B, BlockOut& bo) {
        bool any_break = false;
        double strain_sum = bo.contact_strain, slip_sum = bo.contact_slip;
        for (int l = 0; l < C.count; ++l) {
            const auto k = static_cast<std::size_t>(C.pair[l]);
            PairOutput& out = w.pair_out_[k];
            w.pairs_[k].shear_force = lane(C.c_shear, l);
            out.force_j = lane(C.c_force, l);
            out.torque_j = lane(C.c_torque, l);
            strain_sum += C.c_strain[l];
            slip_sum += C.c_slip[l];
            any_break |= !store_bond(C, l, out);
        }
        for (int l = 0; l < B.count; ++l) {  // open: the contact carries nothing
            const auto k = static_cast<std::size_t>(B.pair[l]);
            PairOutput& out = w.pair_out_[k];
            clear_shear(w.pairs_[k].shear_force);
            out = {};
            any_break |= !store_bond(B, l, out);
        }
        bo.contact_strain = strain_sum;
        bo.contact_slip = slip_sum;
        return any_break;
    }

    /// An intact bond's new state, energy and contribution to the pair output; false if it
    /// broke (record_breaks handles it, in pair order).
    __attribute__((always_inline)) inline bool store_bond(const Lanes& L, int l, PairOutput& out) {
        const std::int32_t bk = L.bond[l];
        if (bk < 0) return true;
        if (L.failure[l] != kIntact) return false;
        ParallelBond& b = w.bonds_[static_cast<std::size_t>(bk)];
        b.normal_force = L.fn[l];
        b.shear_force = lane(L.fs, l);
        b.twist_moment = L.mt[l];
        b.bend_moment = lane(L.mb, l);
        w.bond_stored_[static_cast<std::size_t>(bk)] = track ? L.energy[l] : 0.0;
        out.force_j += lane(L.b_force, l);
        out.torque_j += lane(L.b_torque, l);
        return true;
    }

    /// 4. Breaks (rare), in pair order = bond order: the event with the crack's geometry (the
    ///    kinematics again: a pure function, the same bits), the release, the released energy.
    void record_breaks(std::int64_t b0, std::int64_t b1, const Lanes* lanes, const BatchSlots& slots, BlockOut& bo) {
        for (std::int64_t k = b0; k < b1; ++k) {
            const auto slot = static_cast<std::size_t>(k - b0);
            if (slots.where[slot] < 0) continue;
            const Lanes& L = lanes[static_cast<std::size_t>(slots.where[slot])];
            const int l = slots.which[slot];
            if (L.bond[l] < 0 || L.failure[l] == kIntact) continue;
            const auto bk = static_cast<std::size_t>(L.bond[l]);
            ParallelBond& b = w.bonds_[bk];
            const auto failure = static_cast<BondState>(static_cast<int>(L.failure[l]));
            const auto i = static_cast<std::size_t>(b.i), j = static_cast<std::size_t>(b.j);
            const PairState s{w.particles_.position[i], w.particles_.position[j], w.particles_.velocity[i], w.particles_.velocity[j],
                              w.particles_.spin[i],     w.particles_.spin[j],     w.particles_.radius[i],   w.particles_.radius[j]};
            const PairKinematics kin = pair_kinematics(s, dt);
            bo.breaks.push_back({w.step_, w.time_, L.bond[l], b.i, b.j, failure, s.xa + kin.arm_a + Vec3{}, kin.normal, L.radius[l],
                                 L.tensile[l], L.shear_stress[l], -1});
            release_bond(b, failure);
            w.bond_stored_[bk] = 0.0;
            bo.released.push_back({L.bond[l], track ? L.energy[l] : 0.0});
        }
    }

    /// The blocks' sums in block order: contact energies into `strain` and `slip`, breaks into
    /// the World's list; bond energies per fixed bond block (see the top of this file).
    BondEnergy merge(double& strain, double& slip) {
        const auto nb = static_cast<std::int64_t>(w.bonds_.size());
        double contact_strain = 0, contact_slip = 0;
        std::vector<BondEnergy> bond_partial(static_cast<std::size_t>(block_count(nb)));
        for (const BlockOut& bo : blocks) {
            contact_strain += bo.contact_strain;
            contact_slip += bo.contact_slip;
            w.breaks_.insert(w.breaks_.end(), bo.breaks.begin(), bo.breaks.end());
            for (const Released& x : bo.released) bond_partial[static_cast<std::size_t>(x.bond / kBlockSize)].released += x.energy;
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
    if (bond_const_stale_) refresh_bond_constants();
    bond_stored_.resize(bonds_.size(), 0.0);
    ParallelBondPass pass(*this, dt);
    const bool prefetch_streams = pass.streamed_bytes() > sim_.stream_prefetch_above_bytes;
    for_each_block(static_cast<std::int64_t>(pairs_.size()), [&](std::int64_t begin, std::int64_t end, std::int64_t blk) {
        if (prefetch_streams) pass.block<true>(begin, end, blk);
        else pass.block<false>(begin, end, blk);
    });
    return pass.merge(strain, slip);
}

}  // namespace gradem
