// Phase 3 for the flat joint, vectorised across joints: FlatJointLaw::compute_all, the law's own
// pass over every bond, which the World calls instead of its generic loop (core/bond_pass.hpp;
// core/flat_joint_law.hpp has the law;
// docs/bond_laws.md "Flat joint"). Most joints of a loaded specimen are fully bonded and do
// not break in a given step; for those the law is a fixed sequence of arithmetic per element
// with no branch. Each block of bonds is cut into batches of kJointLanes:
//   1. a scalar scan copies the inputs of the fully bonded joints into structure-of-arrays
//      lanes (particle state, the joint's header and element shear forces, its constants);
//   2. three loops over the lanes run the pair kinematics and the frame, then each element
//      (element loop outside, lanes inside: one vector operation serves kJointLanes joints),
//      then the resultant — compiled for AVX-512, AVX2 and the baseline ISA (function
//      multiversioning, picked at load time);
//   3. a scalar pass in bond order writes back the lanes whose elements all held, and runs
//      every other acting joint (partly or wholly unbonded, or with an element that fails this
//      step: its lane result is discarded, its state is still the old one) through
//      FlatJointLaw::step, exactly as the generic bond phase does.
// The lanes call the law's own helpers (advance_frame, joint_step, element_trial,
// linear_normal, joint_resultant) in the law's order, and every lane does the same IEEE
// operations as the scalar code (-ffp-contract=off: no FMA; no reassociation); energies are
// summed per bond in bond order as before. So the results are bitwise those of the generic
// phase, for any thread count (the pinned hashes in tests/core/test_determinism.cpp).
#include <algorithm>
#include <cstring>
#include <memory>

#include "core/bond_pass.hpp"
#include "core/flat_joint_law.hpp"
#include "core/parallel.hpp"

namespace gradem {
namespace {

constexpr int kJointLanes = 16;
constexpr std::size_t kMaxLaneElements = 8;  ///< joints with more elements take the scalar path
constexpr std::int64_t kPrefetchAhead = 16;  ///< bonds: particle j's state (a random access)

/// Inputs, intermediates and results of up to kJointLanes joints (structure of arrays).
struct JointLanes {
    int count = 0;
    // inputs: the pair's particles, the joint's header and element shear forces, its constants
    double xa[3][kJointLanes], xb[3][kJointLanes], va[3][kJointLanes], vb[3][kJointLanes];
    double wa[3][kJointLanes], wb[3][kJointLanes], ra[kJointLanes], rb[kJointLanes];
    double axis[3][kJointLanes], bend[3][kJointLanes], twist[kJointLanes], normal[kJointLanes];
    double scale[kJointLanes], radius[kJointLanes], kn[kJointLanes], ks[kJointLanes];
    double strength[kJointLanes], cohesion[kJointLanes], tan_phi[kJointLanes];
    double shear[kMaxLaneElements][2][kJointLanes];  ///< F_s,e in (t1, t2): in, then out [N]
    // the frame and step constants after this step's increments
    double t1[3][kJointLanes], t2[3][kJointLanes], n[3][kJointLanes], arm_b[3][kJointLanes];
    double wy[kJointLanes], wz[kJointLanes], bend_total[3][kJointLanes];
    double jkn[kJointLanes], jks[kJointLanes], R2[kJointLanes], ksR4[kJointLanes], inv_ks_r2[kJointLanes];
    double du1[kJointLanes], du2[kJointLanes], dtwist[kJointLanes];
    // element sums and results
    double s1[kJointLanes], s2[kJointLanes], fn[kJointLanes], p1[kJointLanes], p2[kJointLanes];
    double tw[kJointLanes], stored[kJointLanes], fails[kJointLanes];
    double force[3][kJointLanes], torque[3][kJointLanes], shear_res[3][kJointLanes], bend_res[3][kJointLanes];
};

inline Vec3 lane(const double (&a)[3][kJointLanes], int l) { return {a[0][l], a[1][l], a[2][l]}; }
inline void set_lane(double (&a)[3][kJointLanes], int l, const Vec3& v) {
    a[0][l] = v.x;
    a[1][l] = v.y;
    a[2][l] = v.z;
}

/// Loop 1: kinematics, the carried frame and the step constants of every lane.
__attribute__((always_inline)) inline void frames(JointLanes& L, double dt) {
    using namespace flat_detail;
    const int count = L.count;
#pragma GCC ivdep
    for (int l = 0; l < count; ++l) {
        PairState s{lane(L.xa, l), lane(L.xb, l), lane(L.va, l), lane(L.vb, l),
                    lane(L.wa, l), lane(L.wb, l), L.ra[l], L.rb[l]};
        PairKinematics kin = pair_kinematics(s, dt);
        Vec3 bend_total;
        JointFrame f = advance_frame(lane(L.axis, l), lane(L.bend, l), L.twist[l], L.normal[l], kin, bend_total);
        JointStep js = joint_step(f, L.scale[l], {L.kn[l], L.ks[l]}, L.radius[l], kin);
        set_lane(L.t1, l, f.t1);
        set_lane(L.t2, l, f.t2);
        set_lane(L.n, l, kin.normal);
        set_lane(L.arm_b, l, kin.arm_b);
        set_lane(L.bend_total, l, bend_total);
        L.twist[l] = f.twist;
        L.normal[l] = f.normal;
        L.wy[l] = f.wy;
        L.wz[l] = f.wz;
        L.jkn[l] = js.kn;
        L.jks[l] = js.ks;
        L.R2[l] = js.R2;
        L.ksR4[l] = js.ksR4;
        L.inv_ks_r2[l] = js.inv_ks_r2;
        L.du1[l] = js.du1;
        L.du2[l] = js.du2;
        L.dtwist[l] = js.dtwist;
        L.s1[l] = L.s2[l] = L.fn[l] = L.p1[l] = L.p2[l] = L.tw[l] = L.stored[l] = 0.0;
        L.fails[l] = 0.0;
    }
}

/// Loop 2, for one element: FlatJointLaw::step's bonded branch, summed in element order.
__attribute__((always_inline)) inline void bonded_element(JointLanes& L, std::size_t e, const DiscElement& g) {
    using namespace flat_detail;
    const int count = L.count;
#pragma GCC ivdep
    for (int l = 0; l < count; ++l) {
        JointFrame f;
        f.wy = L.wy[l];
        f.wz = L.wz[l];
        f.twist = L.twist[l];
        f.normal = L.normal[l];
        JointStep js;
        js.kn = L.jkn[l];
        js.ks = L.jks[l];
        js.R = L.radius[l];
        js.R2 = L.R2[l];
        js.ksR4 = L.ksR4[l];
        js.inv_ks_r2 = L.inv_ks_r2[l];
        js.du1 = L.du1[l];
        js.du2 = L.du2[l];
        js.dtwist = L.dtwist[l];
        ElementTrial t = element_trial(g, f, js, L.shear[e][0][l], L.shear[e][1][l]);
        const double twist_energy = 0.5 * js.ksR4 * g.polar * f.twist * f.twist;
        NormalLoad load = linear_normal(g, f, js.kn, js.R, t.opening);
        const double inv_a = g.inv_area / js.R2;
        const bool fails = FlatJointLaw::element_fails(load.fn * inv_a, (t.s1 * t.s1 + t.s2 * t.s2) * inv_a * inv_a,
                                                       L.strength[l], L.cohesion[l], L.tan_phi[l]);
        L.fails[l] = fails ? 1.0 : L.fails[l];
        L.stored[l] += load.energy + 0.5 * (t.s1 * t.s1 + t.s2 * t.s2) * t.inv_ksa + twist_energy;
        L.shear[e][0][l] = t.s1;
        L.shear[e][1][l] = t.s2;
        L.s1[l] += t.s1;
        L.s2[l] += t.s2;
        L.fn[l] += load.fn;
        L.p1[l] += load.p1;
        L.p2[l] += load.p2;
        L.tw[l] += t.xy * t.s2 - t.xz * t.s1 - js.ksR4 * g.polar * f.twist;
    }
}

/// Loop 3: the resultant on B, and its torque about B's centre.
__attribute__((always_inline)) inline void resultants(JointLanes& L) {
    using namespace flat_detail;
    const int count = L.count;
#pragma GCC ivdep
    for (int l = 0; l < count; ++l) {
        JointSums sum;
        sum.s1 = L.s1[l];
        sum.s2 = L.s2[l];
        sum.fn = L.fn[l];
        sum.p1 = L.p1[l];
        sum.p2 = L.p2[l];
        sum.twist = L.tw[l];
        JointFrame f;
        f.t1 = lane(L.t1, l);
        f.t2 = lane(L.t2, l);
        JointResultant r = joint_resultant(sum, f, lane(L.n, l));
        set_lane(L.force, l, r.force);
        set_lane(L.torque, l, cross(lane(L.arm_b, l), r.force) + r.moment);
        set_lane(L.shear_res, l, r.shear);
        set_lane(L.bend_res, l, r.bend);
    }
}

#if defined(__x86_64__) && defined(__GNUC__) && !defined(__clang__) && !defined(GRADEM_NO_CLONES)
#define GRADEM_JOINT_CLONES __attribute__((target_clones("avx512f", "avx2", "default")))
#else
#define GRADEM_JOINT_CLONES
#endif

GRADEM_JOINT_CLONES __attribute__((flatten)) void joint_lanes(JointLanes& L, double dt,
                                                              std::span<const DiscElement> elements) {
    frames(L, dt);
    for (std::size_t e = 0; e < elements.size(); ++e) bonded_element(L, e, elements[e]);
    resultants(L);
}

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

/// FlatJointLaw::compute_all as a list of steps per batch of kJointLanes bonds: scan (the
/// fully bonded joints into lanes), the lane arithmetic, then in bond order the lanes that held
/// and every other acting joint through the law's scalar kernel.
struct FlatJointPass {
    const BondPass& pass;
    double dt;
    double* side_data;
    std::size_t stride;
    bool track;  ///< keep bond energies (sim.track_energy)
    std::vector<FlatJointLaw::Context> contexts;  ///< one per bond family pair
    bool use_lanes = false;
    std::span<const DiscElement> elements;
    std::vector<BondPassEnergy> partial;             ///< per bond block
    std::vector<std::vector<BreakEvent>> broken;     ///< per bond block, in bond order

    FlatJointPass(const BondPass& p, double step)
        : pass(p), dt(step), side_data(p.side.data()), stride(p.stride), track(p.sim.track_energy) {
        for (const BondParams& bp : p.family_params) contexts.push_back(FlatJointLaw::context(bp, track));
        use_lanes = p.sim.vectorised_bond_passes && same_elements(contexts);
        elements = contexts.front().elements;
        const auto blocks = static_cast<std::size_t>(block_count(static_cast<std::int64_t>(p.bonds.size())));
        partial.resize(blocks);
        broken.resize(blocks);
    }

    void block(std::int64_t begin, std::int64_t end, std::int64_t blk) {
        BondPassEnergy e;
        std::vector<BondBreak> breaks;
        auto lanes = std::make_unique_for_overwrite<JointLanes>();  // no zero-fill of 20 kB per block
        JointLanes& L = *lanes;
        std::int8_t which[kJointLanes];  // per bond of the batch: its lane, -1 scalar or not acting
        for (std::int64_t b0 = begin; b0 < end; b0 += kJointLanes) {
            const std::int64_t b1 = std::min(end, b0 + kJointLanes);
            scan(b0, b1, end, L, which);
            if (L.count > 0) joint_lanes(L, dt, elements);
            for (std::int64_t k = b0; k < b1; ++k) {
                const int l = which[static_cast<std::size_t>(k - b0)];
                if (l >= 0 && L.fails[l] == 0.0) {
                    store_lane(k, L, l, e);
                    ++e.lane_bonds;
                } else if (bond_acts(pass.bonds[static_cast<std::size_t>(k)])) {
                    scalar_joint(k, blk, breaks, e);
                    ++e.scalar_bonds;
                }
            }
        }
        partial[static_cast<std::size_t>(blk)] = e;
    }

    /// 1. The fully bonded joints of [b0, b1) into lanes: intact and interface 0
    ///    (kPartlyBonded: some element unbonded); `which` gets each bond's lane or -1.
    __attribute__((always_inline)) inline void scan(std::int64_t b0, std::int64_t b1, std::int64_t end, JointLanes& L,
                                                    std::int8_t* which) const {
        int count = 0;
        for (std::int64_t k = b0; k < b1; ++k) {
            prefetch_ahead(k, end);
            const auto slot = static_cast<std::size_t>(k - b0);
            which[slot] = -1;
            const ParallelBond& b = pass.bonds[static_cast<std::size_t>(k)];
            if (!use_lanes || b.state != BondState::intact || b.interface != 0) continue;
            const int l = count++;
            which[slot] = static_cast<std::int8_t>(l);
            load_joint(L, l, k, b);
        }
        L.count = count;
    }

    /// Prefetches for bond k: particle j of a bond a few bonds ahead (a random access), and that
    /// joint's own streams: its side state (the lines with the header and the element shears),
    /// its bond record further on, its constants.
    __attribute__((always_inline)) inline void prefetch_ahead(std::int64_t k, std::int64_t end) const {
        if (k + kPrefetchAhead >= end) return;
        const auto ka = static_cast<std::size_t>(k + kPrefetchAhead);
        const auto jn = static_cast<std::size_t>(pass.bonds[ka].j);
        __builtin_prefetch(&pass.particles.position[jn]);
        __builtin_prefetch(&pass.particles.velocity[jn]);
        __builtin_prefetch(&pass.particles.spin[jn]);
        const char* side_ahead = reinterpret_cast<const char*>(side_data + ka * stride);
        for (std::size_t line = 0; line < stride * sizeof(double); line += 64) __builtin_prefetch(side_ahead + line, 1);
        __builtin_prefetch(&pass.bonds[std::min(ka + kPrefetchAhead, pass.bonds.size() - 1)], 1);
        __builtin_prefetch(&pass.constants[ka]);
    }

    /// Lane l: joint k's particles, its header and element shear forces, its constants.
    __attribute__((always_inline)) inline void load_joint(JointLanes& L, int l, std::int64_t k, const ParallelBond& b) const {
        using namespace flat_side;
        const ParticleSet& particles = pass.particles;
        const double* side = side_data + static_cast<std::size_t>(k) * stride;
        const auto i = static_cast<std::size_t>(b.i), j = static_cast<std::size_t>(b.j);
        set_lane(L.xa, l, particles.position[i]);
        set_lane(L.xb, l, particles.position[j]);
        set_lane(L.va, l, particles.velocity[i]);
        set_lane(L.vb, l, particles.velocity[j]);
        set_lane(L.wa, l, particles.spin[i]);
        set_lane(L.wb, l, particles.spin[j]);
        L.ra[l] = particles.radius[i];
        L.rb[l] = particles.radius[j];
        set_lane(L.axis, l, {side[axis], side[axis + 1], side[axis + 2]});
        set_lane(L.bend, l, {side[bend], side[bend + 1], side[bend + 2]});
        L.twist[l] = side[twist];
        L.normal[l] = side[normal];
        L.scale[l] = side[stiffness_scale];
        for (std::size_t el = 0; el < elements.size(); ++el) {
            const double* p = side + kFlatJointHeader + el * kFlatElementSize;
            L.shear[el][0][l] = p[1];
            L.shear[el][1][l] = p[2];
        }
        const BondConstants& bc = pass.constants[static_cast<std::size_t>(k)];
        L.radius[l] = bc.radius;
        L.kn[l] = bc.stiffness.normal;
        L.ks[l] = bc.stiffness.shear;
        L.strength[l] = b.tensile_strength;
        L.cohesion[l] = b.cohesion;
        L.tan_phi[l] = contexts[b.family_pair].tan_phi;
    }

    /// A fully bonded joint whose elements all held: the lane's results become its state.
    __attribute__((always_inline)) inline void store_lane(std::int64_t k, const JointLanes& L, int l, BondPassEnergy& e) const {
        using namespace flat_side;
        ParallelBond& b = pass.bonds[static_cast<std::size_t>(k)];
        double* side = side_data + static_cast<std::size_t>(k) * stride;
        const Vec3 t1 = lane(L.t1, l), bend_total = lane(L.bend_total, l);
        side[axis] = t1.x, side[axis + 1] = t1.y, side[axis + 2] = t1.z;
        side[bend] = bend_total.x, side[bend + 1] = bend_total.y, side[bend + 2] = bend_total.z;
        side[twist] = L.twist[l];
        side[normal] = L.normal[l];
        for (std::size_t el = 0; el < elements.size(); ++el) {
            double* p = side + kFlatJointHeader + el * kFlatElementSize;
            p[1] = L.shear[el][0][l];
            p[2] = L.shear[el][1][l];
        }
        b.normal_force = L.fn[l];
        b.shear_force = lane(L.shear_res, l);
        b.twist_moment = L.tw[l];
        b.bend_moment = lane(L.bend_res, l);
        BondStepResult r;
        r.stored = track ? L.stored[l] : 0.0;
        e.stored += r.stored;  // every sum as the scalar path adds it (+0 adds change no bit)
        e.released += r.released;
        e.damage += r.damage;
        e.slip += r.slip;
        PairOutput& out = pass.pair_out[static_cast<std::size_t>(b.slot)];
        out.force_j += lane(L.force, l);
        out.torque_j += lane(L.torque, l);
    }

    /// A joint through the law's scalar kernel, as the generic bond phase does; its breaks
    /// into block `blk`'s events.
    void scalar_joint(std::int64_t k, std::int64_t blk, std::vector<BondBreak>& breaks, BondPassEnergy& e) {
        const ParticleSet& particles = pass.particles;
        ParallelBond& b = pass.bonds[static_cast<std::size_t>(k)];
        const auto i = static_cast<std::size_t>(b.i), j = static_cast<std::size_t>(b.j);
        const PairState s{particles.position[i], particles.position[j], particles.velocity[i], particles.velocity[j],
                          particles.spin[i],     particles.spin[j],     particles.radius[i],   particles.radius[j]};
        const PairKinematics kin = pair_kinematics(s, dt);
        const BondConstants& bc = pass.constants[static_cast<std::size_t>(k)];
        const BondSection sec = bond_section_of_radius(bc.radius, bc.inv_radius);
        double* side = side_data + static_cast<std::size_t>(k) * stride;
        const BondStepResult r = FlatJointLaw::step(contexts[b.family_pair], b, side, sec, bc.stiffness, kin, breaks);
        e.stored += r.stored;
        e.released += r.released;
        e.damage += r.damage;
        e.slip += r.slip;
        for (const BondBreak& x : breaks)
            broken[static_cast<std::size_t>(blk)].push_back({pass.step, pass.time, static_cast<std::int32_t>(k), b.i, b.j, x.mode,
                                                             s.xa + kin.arm_a + x.offset, kin.normal, sec.radius, x.tensile_stress,
                                                             x.shear_stress, x.element});
        breaks.clear();
        if (r.failure != BondState::intact) return;
        PairOutput& out = pass.pair_out[static_cast<std::size_t>(b.slot)];
        out.force_j += r.force_j;
        out.torque_j += cross(kin.arm_b, r.force_j) + r.moment_j;
    }
};

}  // namespace

BondPassEnergy FlatJointLaw::compute_all(const BondPass& pass, double dt) {
    FlatJointPass joints(pass, dt);
    for_each_block(static_cast<std::int64_t>(pass.bonds.size()),
                   [&](std::int64_t begin, std::int64_t end, std::int64_t blk) { joints.block(begin, end, blk); });
    for (auto& list : joints.broken) pass.breaks.insert(pass.breaks.end(), list.begin(), list.end());
    return ordered_sum(joints.partial);
}

}  // namespace gradem
