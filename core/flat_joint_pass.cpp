// Phase 3 for the flat joint, vectorised across joints: FlatJointLaw::compute_all, the law's own
// pass over every bond, which the World calls instead of its generic loop (core/bond_pass.hpp;
// core/flat_joint_law.hpp has the law; docs/bond_laws.md "Flat joint"). In a given step almost
// no element of a joint breaks, so the law is a fixed sequence of arithmetic per element, the
// same for every joint up to selects, and runs across joints in structure-of-arrays lanes:
//   1. a scalar scan over each block of bonds gives every acting joint a lane (its bond, its
//      particles, their radii, its strengths): the fully bonded joints in one set of kJointLanes
//      lanes, the others (partly bonded, slit, gapped, broken) in a second, the mixed set; a set
//      runs whenever it is full, so its lanes are full but for the block's last. Just before, the
//      particles' state and the joints' (side state: header, elements' bonded flags and shear
//      forces; constants) are copied in, four lanes at a time by transposes where the processor
//      has AVX2 (core/lane_load.hpp);
//   2. the set's kernel runs every lane (core/flat_joint_pass_lanes.cpp: the fully bonded set's, or
//      the mixed set's);
//   3. the lanes whose elements all held are written back (by the same transposes), and every
//      other joint (an element that breaks this step, a separated joint to release: its lane
//      result is discarded, its state is still the old one) runs through FlatJointLaw::step as
//      the generic bond phase does. The energy terms of a block are summed in bond order and its
//      break events sorted into bond order, as the sets' joints run out of order;
//   4. with forces into particles (BondPass::force_owners), each thread runs a contiguous share
//      of the bonds (BondPass::shares; a block two shares cut is summed as one: BlockPart) and
//      a block (or its part) keeps its joints' outputs, then adds them in bond order to the
//      particles the thread owns (their gather's order), writing a slot only where a particle
//      is not owned or the joint was released; rebuild_slots() writes the others when read.
// The results are bitwise those of the generic phase, for any thread count
// (tests/core/test_determinism.cpp: the pinned hashes, and the lanes against the scalar kernel).
#include <algorithm>
#include <memory>
#include <utility>

#include "core/bond_pass.hpp"
#include "core/flat_joint_law.hpp"
#include "core/flat_joint_pass_lanes.hpp"
#include "core/parallel.hpp"

namespace gradem {
namespace {

using namespace flat_lanes;

constexpr std::int64_t kPrefetchAhead = 16;  ///< bonds: particle j's state (a random access)

/// Whether every family's element table is the same (the lanes share one geometry).
bool same_elements(const std::vector<FlatJointLaw::Context>& contexts) {
    const auto& a = contexts.front().elements;
    if (a.size() > kMaxLaneElements) return false;
    for (const auto& c : contexts) {
        if (c.elements.data() == a.data()) continue;  // the same layout's table
        if (c.elements.size() != a.size()) return false;
        for (std::size_t e = 0; e < a.size(); ++e) {
            const DiscElement &x = a[e], &y = c.elements[e];
            if (x.area != y.area || x.y != y.y || x.z != y.z || x.cyy != y.cyy || x.czz != y.czz || x.cyz != y.cyz)
                return false;
        }
    }
    return true;
}

/// A block's per-bond energy terms, summed in bond order at its end (the sets' joints run out of
/// order), and its lane/scalar counts. The terms are not initialised (a bond's are read only
/// once its flag is set): a block is 2048 bonds, and its step must not start by clearing them.
struct BlockState {
    struct Terms {
        double stored, released, damage, slip;  ///< [J], as BondStepResult's
    };
    static constexpr std::uint8_t kActed = 1, kReleased = 2;  ///< acted[]: the bond acted; and was released
    std::int64_t begin;
    std::unique_ptr<Terms[]> terms;     ///< per bond of the block (acting ones)
    std::vector<std::uint8_t> acted;    ///< 0, kActed or kReleased
    PairOutput* outputs = nullptr;      ///< per bond of the block: its output (forces into particles), else null
    std::vector<BondBreak> breaks;      ///< the scalar kernel's scratch list
    std::int64_t lanes = 0, scalars = 0;
    std::int64_t releases = 0;          ///< joints released (no longer acting)

    BlockState(std::int64_t b, std::int64_t e)
        : begin(b), terms(std::make_unique_for_overwrite<Terms[]>(static_cast<std::size_t>(e - b))),
          acted(static_cast<std::size_t>(e - b), 0) {}
    void lane(std::int64_t k, const BondStepResult& r) {
        record(k, r);
        ++lanes;
    }
    void scalar(std::int64_t k, const BondStepResult& r) {
        record(k, r);
        ++scalars;
    }
    void record(std::int64_t k, const BondStepResult& r) {
        terms[static_cast<std::size_t>(k - begin)] = {r.stored, r.released, r.damage, r.slip};
        const bool released = r.failure != BondState::intact;
        acted[static_cast<std::size_t>(k - begin)] = released ? kReleased : kActed;
        releases += released;
    }
    /// Every term as the scalar pass adds them, bond by bond.
    [[nodiscard]] BondPassEnergy sum() const {
        BondPassEnergy e;
        add_to(e);
        return e;
    }
    /// The terms added to `e` in bond order (a block's tail to its head's sums: BlockPart).
    void add_to(BondPassEnergy& e) const {
        for (std::size_t n = 0; n < acted.size(); ++n) {
            if (!acted[n]) continue;
            e.stored += terms[n].stored;
            e.released += terms[n].released;
            e.damage += terms[n].damage;
            e.slip += terms[n].slip;
        }
        e.lane_bonds += lanes;
        e.scalar_bonds += scalars;
        e.releases += releases;
    }
};

/// FlatJointLaw::compute_all as a list of steps per batch of kJointLanes bonds: scan (the acting
/// joints into the fully bonded lanes and the others'), the lane arithmetic, then in bond order
/// the lanes that took the common path and every other acting joint through the law's scalar
/// kernel.
struct FlatJointPass {
    const BondPass& pass;
    double dt;
    bool track;  ///< keep bond energies (sim.track_energy)
    JointStore store;  ///< the joints' state: side state, constants, records
    std::vector<FlatJointLaw::Context> contexts;  ///< one per bond family pair
    bool use_lanes = false;
    std::span<const DiscElement> elements;
    std::int64_t blocks = 0;                         ///< bond blocks
    std::vector<BondPassEnergy> partial;             ///< per bond block (its head: BlockPart)
    /// Per bond block, then per thread for the block tail its share starts with (tail_of).
    std::vector<std::vector<BreakEvent>> broken;     ///< in bond order
    /// Forces into particles (BondPass::force_owners): each particle's owning thread, else null;
    /// per bond block, the particles of the joints it released.
    std::int16_t* owner = nullptr;
    std::vector<std::vector<std::int32_t>> released_particles;
    /// Per thread: the block whose tail its share starts with (-1: none), that tail's terms and
    /// its joints added to both particles.
    std::vector<std::int64_t> tail_of;
    std::vector<std::unique_ptr<BlockState>> tail_state;
    std::vector<std::int64_t> tail_into_particles;

    FlatJointPass(const BondPass& p, double step)
        : pass(p), dt(step), track(p.sim.track_energy),
          store{p.side.data(), p.stride, p.constants.data(), p.bonds.data()} {
        for (const BondParams& bp : p.family_params) contexts.push_back(FlatJointLaw::context(bp, track));
        use_lanes = p.sim.vectorised_bond_passes && same_elements(contexts);
        elements = contexts.front().elements;
        blocks = block_count(static_cast<std::int64_t>(p.bonds.size()));
        const auto threads = static_cast<std::size_t>(thread_count());
        partial.resize(static_cast<std::size_t>(blocks));
        broken.resize(static_cast<std::size_t>(blocks) + threads);
        released_particles.resize(static_cast<std::size_t>(blocks) + threads);
        tail_of.assign(threads, -1);
        tail_state.resize(threads);
        tail_into_particles.assign(threads, 0);
    }

    /// Bonds [begin, end) of a block part (BlockPart), run by thread `thread` (its index in the
    /// force owners). A head's sums and lists go to its block; a tail's are kept apart (at
    /// `blocks` + thread) and added to its block's after the pass (add_tails).
    void block(const BlockPart& part, std::int16_t thread = 0) {
        const std::int64_t begin = part.begin, end = part.end;
        const std::int64_t blk = part.head() ? part.block : blocks + thread;
        BlockState st(begin, end);
        thread_local std::vector<PairOutput> scratch;  // a block's outputs: 144 kB, kept warm per thread
        if (owner) {
            scratch.resize(static_cast<std::size_t>(kBlockSize));
            st.outputs = scratch.data();
        }
        if (!use_lanes) {
            for (std::int64_t k = begin; k < end; ++k)
                if (bond_acts(pass.bonds[static_cast<std::size_t>(k)])) st.scalar(k, scalar_joint(k, blk, st));
        } else {
            // no zero-fill of 2 x 22 kB per block: the lanes start as harmless dummies instead
            auto sets = std::make_unique_for_overwrite<LaneSet[]>(2);
            LaneSet& bonded = sets[0];
            LaneSet& mixed = sets[1];
            bonded.start(false);
            mixed.start(true);
            for (std::int64_t k = begin; k < end; ++k) scan(k, end, bonded, mixed, st, blk);
            flush(bonded, st, blk);
            flush(mixed, st, blk);
        }
        std::int64_t into_particles = 0;
        if (owner) into_particles = outputs_to_particles(st, end, blk, thread);
        sort_breaks(broken[static_cast<std::size_t>(blk)]);
        if (part.head()) {
            partial[static_cast<std::size_t>(blk)] = st.sum();
            partial[static_cast<std::size_t>(blk)].into_particles = into_particles;
            return;
        }
        const auto t = static_cast<std::size_t>(thread);
        tail_of[t] = part.block;
        tail_into_particles[t] = into_particles;
        tail_state[t] = std::make_unique<BlockState>(std::move(st));
    }

    /// Each block's sums in block order, its tails' terms (thread order = bond order) added to its
    /// head's, as if one thread had run the block; the break events into `breaks` in bond order.
    BondPassEnergy add_tails(std::vector<BreakEvent>& breaks) {
        BondPassEnergy total;
        for (std::int64_t b = 0; b < blocks; ++b) {
            BondPassEnergy e = partial[static_cast<std::size_t>(b)];
            const auto& head_events = broken[static_cast<std::size_t>(b)];
            breaks.insert(breaks.end(), head_events.begin(), head_events.end());
            for (std::size_t t = 0; t < tail_of.size(); ++t) {
                if (tail_of[t] != b) continue;
                tail_state[t]->add_to(e);
                e.into_particles += tail_into_particles[t];
                const auto& events = broken[static_cast<std::size_t>(blocks) + t];
                breaks.insert(breaks.end(), events.begin(), events.end());
            }
            total += e;
        }
        return total;
    }

    /// The particles of the joints released, in bond order.
    void hand_back_released(std::vector<std::int32_t>& out) const {
        for (std::int64_t b = 0; b < blocks; ++b) {
            const auto& head = released_particles[static_cast<std::size_t>(b)];
            out.insert(out.end(), head.begin(), head.end());
            for (std::size_t t = 0; t < tail_of.size(); ++t) {
                if (tail_of[t] != b) continue;
                const auto& tail = released_particles[static_cast<std::size_t>(blocks) + t];
                out.insert(out.end(), tail.begin(), tail.end());
            }
        }
    }

    /// One set of lanes and the bond of each: the fully bonded joints (intact, interface 0), or
    /// the others (partly bonded, slit, gapped, broken: with their elements' bonded flags).
    struct LaneSet {
        JointLanes lanes;
        std::int64_t bond[kJointLanes];
        std::int32_t ia[kJointLanes], ib[kJointLanes];  ///< the lane's particles, copied in at flush()
        bool mixed;
        void start(bool holds_mixed) {
            mixed = holds_mixed;
            lanes.count = 0;
            dummy_inputs(lanes);  // the kernels run over every lane
        }
    };

    /// 1. Acting joint k into its set's next lane, the set run and emptied whenever it is full
    ///    (so its lanes are full but for the block's last).
    __attribute__((always_inline)) inline void scan(std::int64_t k, std::int64_t end, LaneSet& bonded, LaneSet& mixed,
                                                    BlockState& st, std::int64_t blk) {
        prefetch_ahead(k, end);
        const ParallelBond& b = pass.bonds[static_cast<std::size_t>(k)];
        if (!bond_acts(b)) return;
        const bool fully_bonded = b.state == BondState::intact && b.interface == 0;
        LaneSet& set = fully_bonded ? bonded : mixed;
        const int l = set.lanes.count++;
        set.bond[l] = k;
        set.ia[l] = b.i;
        set.ib[l] = b.j;
        load_joint(set.lanes, l, b, !fully_bonded);
        if (set.lanes.count == kJointLanes) flush(set, st, blk);
    }

    /// 2-3. A set through its kernel: each joint whose lane took the common path stored, the
    ///    others through the scalar kernel; the set emptied.
    void flush(LaneSet& set, BlockState& st, std::int64_t blk) {
        JointLanes& L = set.lanes;
        if (L.count == 0) return;
        load_particles(L, pass.particles, set.ia, set.ib, L.count);
        load_joints(L, store, set.bond, L.count, elements.size());
        if (set.mixed) mixed_joint_lanes(L, dt, elements);
        else joint_lanes(L, dt, elements);
        store_joints(L, store, set.bond, L.count, elements.size());
        for (int l = 0; l < L.count; ++l) {
            if (L.fails[l] == 0.0) st.lane(set.bond[l], lane_output(L, l, output(st, set.bond[l])));
            else st.scalar(set.bond[l], scalar_joint(set.bond[l], blk, st));
        }
        L.count = 0;
    }

    /// Where joint k's output goes: its pair's slot, or (forces into particles) the block's
    /// outputs, which outputs_to_particles() then reads in bond order.
    PairOutput& output(BlockState& st, std::int64_t k) const {
        if (st.outputs) return st.outputs[k - st.begin];
        return pass.pair_out[static_cast<std::size_t>(pass.bonds[static_cast<std::size_t>(k)].slot)];
    }

    /// Forces into particles: the block's outputs in bond order, each added to its particles
    /// this thread owns (add_to_owned_particles). An owned particle's pairs are all acting
    /// joints in this thread's share and bond order is pair order, so it takes them in its
    /// gather's order. The slot is written unless both particles took the output and the joint
    /// still acts (the slots are rebuilt from the bond and its moment on j: World::pair_outputs).
    /// Returns the joints added to both particles without a slot.
    std::int64_t outputs_to_particles(const BlockState& st, std::int64_t end, std::int64_t blk, std::int16_t thread) {
        std::int64_t into_particles = 0;
        Vec3* const force = pass.force;
        Vec3* const torque = pass.torque;
        for (std::int64_t k = st.begin; k < end; ++k) {
            const std::uint8_t acted = st.acted[static_cast<std::size_t>(k - st.begin)];
            if (acted == 0) continue;
            const PairOutput& o = st.outputs[k - st.begin];
            const ParallelBond& b = pass.bonds[static_cast<std::size_t>(k)];
            const auto i = static_cast<std::size_t>(b.i), j = static_cast<std::size_t>(b.j);
            (*pass.bond_torque)[static_cast<std::size_t>(k)] = o.torque_j;
            const bool own_i = owner[i] == thread, own_j = owner[j] == thread;
            add_to_owned_particles(force, torque, i, j, own_i, own_j, o.force_j, o.torque_j, o.torque_i);
            const bool released = acted == BlockState::kReleased;
            if (own_i && own_j && !released) ++into_particles;
            else pass.pair_out[static_cast<std::size_t>(b.slot)] = o;
            if (released) {
                auto& handed_back = released_particles[static_cast<std::size_t>(blk)];
                handed_back.insert(handed_back.end(), {b.i, b.j});
            }
        }
        return into_particles;
    }

    /// A block's break events in bond order (a set's joints may run after later bonds; the
    /// events of one joint stay in element order).
    static void sort_breaks(std::vector<BreakEvent>& events) {
        std::stable_sort(events.begin(), events.end(), [](const BreakEvent& a, const BreakEvent& b) { return a.bond < b.bond; });
    }

    /// Prefetches for bond k: particle j of a bond a few bonds ahead (a random access), and that
    /// joint's own streams: its bond record further on, its pair slot (when the pass writes
    /// every slot), its constants, the lines of its side state (header and element shears, for
    /// writing).
    __attribute__((always_inline)) inline void prefetch_ahead(std::int64_t k, std::int64_t end) const {
        if (k + kPrefetchAhead >= end) return;
        const auto ka = static_cast<std::size_t>(k + kPrefetchAhead);
        const auto jn = static_cast<std::size_t>(pass.bonds[ka].j);
        __builtin_prefetch(&pass.particles.position[jn]);
        __builtin_prefetch(&pass.particles.velocity[jn]);
        __builtin_prefetch(&pass.particles.spin[jn]);
        __builtin_prefetch(&pass.bonds[std::min(ka + kPrefetchAhead, pass.bonds.size() - 1)], 1);
        if (const std::int32_t slot = pass.bonds[ka].slot; !owner && slot >= 0)  // where its force goes
            __builtin_prefetch(&pass.pair_out[static_cast<std::size_t>(slot)], 1);
        __builtin_prefetch(&pass.constants[ka]);
        const double* side = store.side + ka * store.stride;
        for (std::size_t at = 0; at < store.stride; at += 8) __builtin_prefetch(side + at, 1);
        __builtin_prefetch(side + store.stride - 1, 1);
    }

    /// Lane l: the radii of joint b's particles, its strengths and its family's constants (μ_r and
    /// ρ for a joint not fully bonded); its state is copied in at flush() (load_joints).
    __attribute__((always_inline)) inline void load_joint(JointLanes& L, int l, const ParallelBond& b, bool mixed) const {
        const ParticleSet& particles = pass.particles;
        const FlatJointLaw::Context& family = contexts[b.family_pair];
        L.ra[l] = particles.radius[static_cast<std::size_t>(b.i)];
        L.rb[l] = particles.radius[static_cast<std::size_t>(b.j)];
        L.strength[l] = b.tensile_strength;
        L.cohesion[l] = b.cohesion;
        L.tan_phi[l] = family.tan_phi;
        if (!mixed) return;
        L.friction[l] = family.friction;
        L.unbonded_kn[l] = family.unbonded_kn;
    }

    /// A joint whose lane took the law's common path (no element failed or was cut, nothing
    /// released; its state already stored: store_joints): its output and energy terms.
    __attribute__((always_inline)) inline BondStepResult lane_output(const JointLanes& L, int l, PairOutput& out) const {
        BondStepResult r;
        r.stored = track ? L.stored[l] : 0.0;
        r.slip = track ? L.slip[l] : 0.0;
        bond_output(out, lane(L.force, l), lane(L.torque, l), pass.replaces_contact, lane(L.xb, l) - lane(L.xa, l));
        return r;
    }

    /// A joint through the law's scalar kernel, as the generic bond phase does; its breaks
    /// into block `blk`'s events.
    BondStepResult scalar_joint(std::int64_t k, std::int64_t blk, BlockState& st) {
        std::vector<BondBreak>& breaks = st.breaks;
        const ParticleSet& particles = pass.particles;
        ParallelBond& b = pass.bonds[static_cast<std::size_t>(k)];
        const auto i = static_cast<std::size_t>(b.i), j = static_cast<std::size_t>(b.j);
        const PairState s{particles.position[i], particles.position[j], particles.velocity[i], particles.velocity[j],
                          particles.spin[i],     particles.spin[j],     particles.radius[i],   particles.radius[j]};
        const PairKinematics kin = pair_kinematics(s, dt);
        const BondConstants& bc = pass.constants[static_cast<std::size_t>(k)];
        const BondSection sec = bond_section_of_radius(bc.radius, bc.inv_radius);
        double* side = store.side + static_cast<std::size_t>(k) * store.stride;
        const BondStepResult r = FlatJointLaw::step(contexts[b.family_pair], b, side, sec, bc.stiffness, kin, breaks);
        for (const BondBreak& x : breaks)
            broken[static_cast<std::size_t>(blk)].push_back({pass.step, pass.time, static_cast<std::int32_t>(k), b.i, b.j, x.mode,
                                                             s.xa + kin.arm_a + x.offset, kin.normal, sec.radius, x.tensile_stress,
                                                             x.shear_stress, x.element});
        breaks.clear();
        PairOutput& out = output(st, k);
        if (r.failure != BondState::intact) released_bond_output(out, pass.replaces_contact);
        else bond_output(out, r.force_j, cross(kin.arm_b, r.force_j) + r.moment_j, pass.replaces_contact, s.xb - s.xa);
        return r;
    }
};

/// Forces into particles: the particles' sums zeroed, then each thread its share of the bonds
/// (BondPass::shares: its time in it measured), in order; the particles of the joints it released
/// handed back.
void run_into_particles(FlatJointPass& joints, const BondPass& pass) {
    const auto nb = static_cast<std::int64_t>(pass.bonds.size());
    const auto n = static_cast<std::int64_t>(pass.particles.size());
    PassShares& shares = *pass.shares;
    shares.seconds->resize(static_cast<std::size_t>(thread_count()), 0.0);
#pragma omp parallel
    {
        const int team = team_size();
        const auto t = static_cast<std::int16_t>(thread_index());
        const auto [p0, p1] = item_share(*shares.particles, n, team, t);
        std::fill(pass.force + p0, pass.force + p1, Vec3{});
        std::fill(pass.torque + p0, pass.torque + p1, Vec3{});
#pragma omp barrier
#pragma omp single
        {
            joints.owner = pass.force_owners(team);  // (cuts the shares again when stale)
            shares.team = team;
        }
        run_timed_share(*shares.units, nb, team, t, *shares.seconds, [&](const BlockPart& part) { joints.block(part, t); });
    }
    joints.hand_back_released(*pass.released_particles);
}

}  // namespace

BondPassEnergy FlatJointLaw::compute_all(const BondPass& pass, double dt) {
    FlatJointPass joints(pass, dt);
    if (pass.force_owners) {
        pass.bond_torque->resize(pass.bonds.size());
        run_into_particles(joints, pass);
    } else {
        for_each_block(static_cast<std::int64_t>(pass.bonds.size()),
                       [&](std::int64_t begin, std::int64_t end, std::int64_t blk) { joints.block({begin, end, blk}); });
    }
    return joints.add_tails(pass.breaks);
}

// The slots a pass into particles left unwritten, as it would have written them: each acting
// joint's force on j from its bond record (joint_resultant: F = F_s - F_n n, the same
// operations) at the positions it was evaluated at, its moment on j as the pass kept it, the
// moment on i from both (bond_output). Joints released in the pass wrote their slots.
void FlatJointLaw::rebuild_slots(const BondPass& pass) {
    const ParticleSet& P = pass.particles;
    for_each_block(static_cast<std::int64_t>(pass.bonds.size()), [&](std::int64_t begin, std::int64_t end, std::int64_t) {
        for (std::int64_t k = begin; k < end; ++k) {
            const ParallelBond& b = pass.bonds[static_cast<std::size_t>(k)];
            if (!bond_acts(b) || b.slot < 0) continue;
            const auto i = static_cast<std::size_t>(b.i), j = static_cast<std::size_t>(b.j);
            const PairState s{P.position[i], P.position[j], P.velocity[i], P.velocity[j], P.spin[i], P.spin[j], P.radius[i], P.radius[j]};
            const Vec3 n = pair_kinematics(s, 0.0).normal;
            const Vec3 force = b.shear_force - b.normal_force * n;
            bond_output(pass.pair_out[static_cast<std::size_t>(b.slot)], force, (*pass.bond_torque)[static_cast<std::size_t>(k)],
                        pass.replaces_contact, s.xb - s.xa);
        }
    });
}

}  // namespace gradem
