// Phase 3 for the flat joint, vectorised across joints: FlatJointLaw::compute_all, the law's own
// pass over every bond, which the World calls instead of its generic loop (core/bond_pass.hpp;
// core/flat_joint_law.hpp has the law; docs/bond_laws.md "Flat joint"). In a given step almost
// no element of a joint breaks, so the law is a fixed sequence of arithmetic per element, the
// same for every joint up to selects, and runs across joints in structure-of-arrays lanes:
//   1. a scalar scan over each block of bonds copies the inputs of every acting joint into lanes
//      (the joint's header and element shear forces, its constants): the fully bonded joints into
//      one set of kJointLanes lanes, the others (partly bonded, slit, gapped, broken; with their
//      elements' bonded flags) into a second, the mixed set; a set runs whenever it is full, so its
//      lanes are full but for the block's last, and its particles' state is copied in just before
//      (four lanes at a time by transposes where the processor has AVX2: core/lane_load.hpp);
//   2. loops over every lane of a set (a fixed trip count, so no scalar epilogue: the lanes past the
//      set's joints hold harmless dummies) run the pair kinematics and the frame, then each element
//      (element loop outside, lanes inside: one vector operation serves a vector's worth of joints;
//      for the fully bonded set all elements of a lane in one loop, its frame and sums in registers),
//      then the resultant — compiled for AVX-512, AVX2 and the baseline ISA (function
//      multiversioning, picked at load time). For the mixed set the element loop is split: the normal
//      load of every element (bonded: linear with its failure test; unbonded: linear if closed over
//      its whole extent, nil if open), the elements the zero line cuts (gathered from
//      all the set's joints into one list and run through unbonded_normal's closed form written
//      without branches, core/disc_elements_branchless.hpp, vectorised across the list), then the
//      shear with the Coulomb cap and the sums in element order;
//   3. the lanes whose elements all held are written back, and every other joint (an element
//      that breaks this step, a separated joint to release: its lane result is discarded, its
//      state is still the old one) runs through FlatJointLaw::step as the generic bond phase
//      does. The energy terms of a block are summed in bond order and its break events sorted
//      into bond order, as the sets' joints run out of order;
//   4. with forces into particles (BondPass::force_owners), each thread runs a contiguous share
//      of the blocks and a block keeps its joints' outputs, then adds them in bond order to the
//      particles the thread owns (their gather's order), writing a slot only where a particle
//      is not owned or the joint was released; rebuild_slots() writes the others when read.
// The lanes call the law's own helpers (advance_frame, joint_step, element_trial, linear_normal,
// unbonded_normal, joint_resultant) in the law's order, selects stand for its branches, and
// every lane does the same IEEE operations as the scalar code (-ffp-contract=off: no FMA; no
// reassociation). So the results are bitwise those of the generic phase, for any thread count
// (tests/core/test_determinism.cpp: the pinned hashes, and the lanes against the scalar kernel).
#include <algorithm>
#include <cstring>
#include <memory>
#include <utility>

#include "core/bond_pass.hpp"
#include "core/disc_elements_branchless.hpp"
#include "core/flat_joint_law.hpp"
#include "core/lane_load.hpp"
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
    // inputs of joints not fully bonded: elements' bonded flags (1/0), g_0 [m], μ_r, ρ (the
    // unbonded elements' share of k̄_n), the surface gap beyond which a separated joint is released [m]
    double bonded[kMaxLaneElements][kJointLanes];
    double gap0[kJointLanes], friction[kJointLanes], unbonded_kn[kJointLanes], release_gap[kJointLanes];
    // the frame and step constants after this step's increments
    double t1[3][kJointLanes], t2[3][kJointLanes], n[3][kJointLanes], arm_b[3][kJointLanes];
    double wy[kJointLanes], wz[kJointLanes], w_norm[kJointLanes], gap[kJointLanes], bend_total[3][kJointLanes];
    double jkn[kJointLanes], jks[kJointLanes], R2[kJointLanes], ksR4[kJointLanes], inv_ks_r2[kJointLanes];
    double du1[kJointLanes], du2[kJointLanes], dtwist[kJointLanes];
    // element sums and results
    double s1[kJointLanes], s2[kJointLanes], fn[kJointLanes], p1[kJointLanes], p2[kJointLanes];
    double tw[kJointLanes], stored[kJointLanes], fails[kJointLanes];
    double slip[kJointLanes], any_bonded[kJointLanes], all_open[kJointLanes];  ///< joints not fully bonded
    // each element's normal load (joints not fully bonded): F_n, P, energy, and whether the zero
    // line cuts it; whether it cuts any of the joint's
    double el_fn[kMaxLaneElements][kJointLanes], el_p1[kMaxLaneElements][kJointLanes];
    double el_p2[kMaxLaneElements][kJointLanes], el_energy[kMaxLaneElements][kJointLanes];
    double el_cut[kMaxLaneElements][kJointLanes], any_cut[kJointLanes];
    double force[3][kJointLanes], torque[3][kJointLanes], shear_res[3][kJointLanes], bend_res[3][kJointLanes];
};

inline Vec3 lane(const double (&a)[3][kJointLanes], int l) { return {a[0][l], a[1][l], a[2][l]}; }
inline void set_lane(double (&a)[3][kJointLanes], int l, const Vec3& v) {
    a[0][l] = v.x;
    a[1][l] = v.y;
    a[2][l] = v.z;
}

/// The particles of lanes [0, count): positions, velocities and spins of both ends, one double
/// at a time, from lane `first` on.
inline void load_particles_scalar(JointLanes& L, const ParticleSet& particles, const std::int32_t* ia,
                                  const std::int32_t* ib, int first, int count) {
    for (int l = first; l < count; ++l) {
        const auto i = static_cast<std::size_t>(ia[l]), j = static_cast<std::size_t>(ib[l]);
        set_lane(L.xa, l, particles.position[i]);
        set_lane(L.xb, l, particles.position[j]);
        set_lane(L.va, l, particles.velocity[i]);
        set_lane(L.vb, l, particles.velocity[j]);
        set_lane(L.wa, l, particles.spin[i]);
        set_lane(L.wb, l, particles.spin[j]);
    }
}

#ifdef GRADEM_LANE_TRANSPOSE
/// The same copy by transposes, four lanes at a time (core/lane_load.hpp), the lanes past the
/// last multiple of four one double at a time: the same bits.
__attribute__((target("avx2"))) void load_particles_transposed(JointLanes& L, const ParticleSet& particles,
                                                               const std::int32_t* ia, const std::int32_t* ib, int count) {
    int l0 = 0;
    for (; l0 + 4 <= count; l0 += 4) {
        transposed_lanes4(&L.xa[0][l0], &L.xa[1][l0], &L.xa[2][l0], particles.position.data(), &ia[l0]);
        transposed_lanes4(&L.xb[0][l0], &L.xb[1][l0], &L.xb[2][l0], particles.position.data(), &ib[l0]);
        transposed_lanes4(&L.va[0][l0], &L.va[1][l0], &L.va[2][l0], particles.velocity.data(), &ia[l0]);
        transposed_lanes4(&L.vb[0][l0], &L.vb[1][l0], &L.vb[2][l0], particles.velocity.data(), &ib[l0]);
        transposed_lanes4(&L.wa[0][l0], &L.wa[1][l0], &L.wa[2][l0], particles.spin.data(), &ia[l0]);
        transposed_lanes4(&L.wb[0][l0], &L.wb[1][l0], &L.wb[2][l0], particles.spin.data(), &ib[l0]);
    }
    load_particles_scalar(L, particles, ia, ib, l0, count);
}
#endif

/// The particles of a set's lanes [0, count) (the lanes past it keep their dummies).
inline void load_particles(JointLanes& L, const ParticleSet& particles, const std::int32_t* ia, const std::int32_t* ib,
                           int count) {
#ifdef GRADEM_LANE_TRANSPOSE
    if (lane_transpose_available()) return load_particles_transposed(L, particles, ia, ib, count);
#endif
    load_particles_scalar(L, particles, ia, ib, 0, count);
}

/// Loop 1: kinematics, the carried frame and the step constants of every lane.
__attribute__((always_inline)) inline void frames(JointLanes& L, double dt) {
    using namespace flat_detail;
    constexpr int count = kJointLanes;  // every lane: a fixed trip count, no scalar epilogue
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
        L.w_norm[l] = f.w_norm;
        L.gap[l] = kin.gap;
        L.jkn[l] = js.kn;
        L.jks[l] = js.ks;
        L.R2[l] = js.R2;
        L.ksR4[l] = js.ksR4;
        L.inv_ks_r2[l] = js.inv_ks_r2;
        L.du1[l] = js.du1;
        L.du2[l] = js.du2;
        L.dtwist[l] = js.dtwist;
        L.s1[l] = L.s2[l] = L.fn[l] = L.p1[l] = L.p2[l] = L.tw[l] = L.stored[l] = 0.0;
        L.fails[l] = L.slip[l] = L.any_bonded[l] = L.any_cut[l] = 0.0;
        L.all_open[l] = 1.0;
    }
}

/// The frame and step constants of lane l, as FlatJointLaw::step has them.
__attribute__((always_inline)) inline void lane_frame(const JointLanes& L, int l, flat_detail::JointFrame& f,
                                                      flat_detail::JointStep& js) {
    f.wy = L.wy[l];
    f.wz = L.wz[l];
    f.w_norm = L.w_norm[l];
    f.twist = L.twist[l];
    f.normal = L.normal[l];
    js.kn = L.jkn[l];
    js.ks = L.jks[l];
    js.R = L.radius[l];
    js.R2 = L.R2[l];
    js.ksR4 = L.ksR4[l];
    js.inv_ks_r2 = L.inv_ks_r2[l];
    js.du1 = L.du1[l];
    js.du2 = L.du2[l];
    js.dtwist = L.dtwist[l];
}

/// Whether lane l's bonded element fails at its linear load and trial shear (the law's test on
/// the element's mean stresses).
__attribute__((always_inline)) inline bool lane_element_fails(const JointLanes& L, int l, const DiscElement& g,
                                                              const flat_detail::JointStep& js,
                                                              const flat_detail::NormalLoad& load,
                                                              const flat_detail::ElementTrial& t) {
    const double inv_a = g.inv_area / js.R2;
    return FlatJointLaw::element_fails(load.fn * inv_a, (t.s1 * t.s1 + t.s2 * t.s2) * inv_a * inv_a, L.strength[l],
                                       L.cohesion[l], L.tan_phi[l]);
}

/// Loop 2a of a joint not fully bonded, for one element: its normal load as FlatJointLaw::step
/// has it, for every lane at once. Bonded: the linear stress and the failure test (a failure
/// sends the joint to the scalar kernel). Unbonded (unbonded_normal): closed over its whole
/// extent, the linear stress at gap g_0 + δ_e; open, none; cut by the zero line, marked for
/// cut_elements(). Every selected value is the scalar kernel's, bit for bit.
__attribute__((always_inline)) inline void mixed_normal(JointLanes& L, std::size_t e, const DiscElement& g) {
    using namespace flat_detail;
    constexpr int count = kJointLanes;  // every lane: a fixed trip count, no scalar epilogue
#pragma GCC ivdep
    for (int l = 0; l < count; ++l) {
        JointFrame f;
        JointStep js;
        lane_frame(L, l, f, js);
        const ElementTrial t = element_trial(g, f, js, L.shear[e][0][l], L.shear[e][1][l]);
        const bool bonded = L.bonded[e][l] != 0.0;
        const double gap = L.gap0[l] + t.opening;
        const double spread = js.R * f.w_norm * g.reach;
        const bool closed = gap + spread <= 0.0;
        const bool open = !closed & (gap - spread >= 0.0);
        // the linear stress: bonded at its opening, or unbonded and closed at its gap (else none)
        const bool loaded = bonded | closed;
        const NormalLoad load = linear_normal(g, f, bonded ? js.kn : js.kn * L.unbonded_kn[l], js.R, bonded ? t.opening : gap);
        const bool fails = lane_element_fails(L, l, g, js, load, t);
        const bool cut = !bonded & !closed & !open;
        L.el_fn[e][l] = loaded ? load.fn : 0.0;
        L.el_p1[e][l] = loaded ? load.p1 : 0.0;
        L.el_p2[e][l] = loaded ? load.p2 : 0.0;
        L.el_energy[e][l] = loaded ? load.energy : 0.0;
        L.el_cut[e][l] = cut ? 1.0 : 0.0;
        L.any_cut[l] = cut ? 1.0 : L.any_cut[l];
        L.fails[l] = (bonded & fails) ? 1.0 : L.fails[l];
        L.any_bonded[l] = bonded ? 1.0 : L.any_bonded[l];
        L.all_open[l] = (!bonded & open) ? L.all_open[l] : 0.0;
    }
}

/// The elements of a set's lanes that the zero line cuts, one (lane, element) item each, with
/// what the closed form needs (structure of arrays), and their loads.
struct CutItems {
    /// The list is padded to a multiple of this, so the vector loop (8 doubles with AVX-512, 4 with
    /// AVX2) never reaches its scalar epilogue, which runs the closed form's every path one item at a time.
    static constexpr int kChunk = 8;
    static constexpr int kMax = kJointLanes * static_cast<int>(kMaxLaneElements);
    static_assert(kMax % kChunk == 0);
    int count = 0;
    std::int32_t lane[kMax], element[kMax];
    double gamma[kMax], wy[kMax], wz[kMax];  ///< the joint's gap field: γ [m], R̄ w [m]
    double kn[kMax], R[kMax];                ///< ρ k̄_n [Pa/m], R̄ [m]
    double r0[kMax], r1[kMax], a0[kMax], a1[kMax], cos0[kMax], sin0[kMax], cos1[kMax], sin1[kMax];
    double fn[kMax], p1[kMax], p2[kMax], energy[kMax];  ///< the element's NormalLoad
};

/// Loop 2b, part 1, one lane at a time: every cut element of the lanes that hold (no element
/// failed) as an item, with its joint's gap field as unbonded_normal() makes it.
inline void collect_cuts(CutItems& C, const JointLanes& L, std::span<const DiscElement> elements) {
    using namespace flat_detail;
    C.count = 0;
    for (int l = 0; l < L.count; ++l) {
        if (L.any_cut[l] == 0.0 || L.fails[l] != 0.0) continue;
        JointFrame f;
        JointStep js;
        lane_frame(L, l, f, js);
        for (std::size_t e = 0; e < elements.size(); ++e) {
            if (L.el_cut[e][l] == 0.0) continue;
            const int n = C.count++;
            const DiscElement& g = elements[e];
            C.lane[n] = l;
            C.element[n] = static_cast<std::int32_t>(e);
            C.gamma[n] = L.gap0[l] + f.normal;
            C.wy[n] = js.R * f.wy;
            C.wz[n] = js.R * f.wz;
            C.kn[n] = js.kn * L.unbonded_kn[l];
            C.R[n] = js.R;
            C.r0[n] = g.r0, C.r1[n] = g.r1, C.a0[n] = g.a0, C.a1[n] = g.a1;
            C.cos0[n] = g.cos0, C.sin0[n] = g.sin0, C.cos1[n] = g.cos1, C.sin1[n] = g.sin1;
        }
    }
}

/// The items after the last up to a whole chunk: copies of the first item's inputs (finite; their
/// results are never read).
inline int pad_to_chunks(CutItems& C) {
    int n = C.count;
    for (; n % CutItems::kChunk != 0; ++n) {
        C.gamma[n] = C.gamma[0], C.wy[n] = C.wy[0], C.wz[n] = C.wz[0], C.kn[n] = C.kn[0], C.R[n] = C.R[0];
        C.r0[n] = C.r0[0], C.r1[n] = C.r1[0], C.a0[n] = C.a0[0], C.a1[n] = C.a1[0];
        C.cos0[n] = C.cos0[0], C.sin0[n] = C.sin0[0], C.cos1[n] = C.cos1[0], C.sin1[n] = C.sin1[0];
    }
    return n;
}

/// Loop 2b, part 2, across items: each cut element's normal load over its compressed part,
/// unbonded_normal()'s closed form without branches (core/disc_elements_branchless.hpp), the
/// same bits.
template <bool InnerKinks>
__attribute__((always_inline)) inline void cut_loads(CutItems& C, int padded) {
    const int chunks = padded / CutItems::kChunk;
#pragma GCC ivdep
    for (int n = 0; n < chunks * CutItems::kChunk; ++n) {
        const SectorBounds g{C.r0[n], C.r1[n], C.a0[n], C.a1[n], C.cos0[n], C.sin0[n], C.cos1[n], C.sin1[n]};
        const CompressedPart c = compressed_part_branchless<InnerKinks>(g, C.gamma[n], C.wy[n], C.wz[n]);
        const double R = C.R[n], knR2 = C.kn[n] * R * R;
        C.fn[n] = knR2 * c.force;
        C.p1[n] = knR2 * R * c.py;
        C.p2[n] = knR2 * R * c.pz;
        C.energy[n] = 0.5 * knR2 * c.energy;
    }
}

/// Loop 2b: the normal load of the elements cut by the zero line, over their compressed part
/// (unbonded_normal), into their lanes.
inline void cut_elements(JointLanes& L, std::span<const DiscElement> elements) {
    CutItems C;
    collect_cuts(C, L, elements);
    if (C.count == 0) return;
    const int padded = pad_to_chunks(C);
    const bool inner_kinks = std::any_of(elements.begin(), elements.end(), [](const DiscElement& g) { return g.r0 > 0.0; });
    if (inner_kinks) cut_loads<true>(C, padded);
    else cut_loads<false>(C, padded);
    for (int n = 0; n < C.count; ++n) {
        const auto e = static_cast<std::size_t>(C.element[n]);
        const int l = C.lane[n];
        L.el_fn[e][l] = C.fn[n];
        L.el_p1[e][l] = C.p1[n];
        L.el_p2[e][l] = C.p2[n];
        L.el_energy[e][l] = C.energy[n];
    }
}

/// Loop 2c, for one element: its shear (the Coulomb cap |F_s| <= μ_r max(-F_n, 0) of an unbonded
/// element, with its slip energy) and the joint's sums in element order, as FlatJointLaw::step.
__attribute__((always_inline)) inline void mixed_shear(JointLanes& L, std::size_t e, const DiscElement& g) {
    using namespace flat_detail;
    constexpr int count = kJointLanes;  // every lane: a fixed trip count, no scalar epilogue
#pragma GCC ivdep
    for (int l = 0; l < count; ++l) {
        JointFrame f;
        JointStep js;
        lane_frame(L, l, f, js);
        const double old1 = L.shear[e][0][l], old2 = L.shear[e][1][l];
        const ElementTrial t = element_trial(g, f, js, old1, old2);
        const bool bonded = L.bonded[e][l] != 0.0;
        const double fn = L.el_fn[e][l];
        const double limit = fn < 0.0 ? -L.friction[l] * fn : 0.0;
        const double m2 = t.s1 * t.s1 + t.s2 * t.s2;
        const bool capped = !bonded & (m2 > limit * limit);
        const double cap = m2 > 0.0 ? limit / std::sqrt(m2) : 0.0;
        const double c1 = cap * t.s1, c2 = cap * t.s2;
        const double slip = -0.5 * ((old1 + c1) * t.du1 + (old2 + c2) * t.du2) -
                            0.5 * (c1 * c1 + c2 * c2 - old1 * old1 - old2 * old2) * t.inv_ksa;
        const double s1 = capped ? c1 : t.s1;
        const double s2 = capped ? c2 : t.s2;
        // The bonded element's twist energy (>= +0) times its flag (1 or 0): the scalar kernel's
        // select, bit for bit, written as a product so that the compiler keeps the loop straight.
        const double twist_energy = 0.5 * js.ksR4 * g.polar * f.twist * f.twist * L.bonded[e][l];
        const double twist_moment = bonded ? js.ksR4 * g.polar * f.twist : 0.0;
        L.slip[l] += capped ? slip : 0.0;
        L.stored[l] += L.el_energy[e][l] + 0.5 * (s1 * s1 + s2 * s2) * t.inv_ksa + twist_energy;
        L.shear[e][0][l] = s1;
        L.shear[e][1][l] = s2;
        L.s1[l] += s1;
        L.s2[l] += s2;
        L.fn[l] += fn;
        L.p1[l] += L.el_p1[e][l];
        L.p2[l] += L.el_p2[e][l];
        L.tw[l] += t.xy * s2 - t.xz * s1 - twist_moment;
    }
}

/// A joint not fully bonded whose elements are all unbonded and open and whose surfaces are
/// farther apart than its release gap is released by the scalar kernel.
__attribute__((always_inline)) inline void mark_releases(JointLanes& L) {
    constexpr int count = kJointLanes;  // every lane: a fixed trip count, no scalar epilogue
#pragma GCC ivdep
    for (int l = 0; l < count; ++l) {
        const bool releases = (L.any_bonded[l] == 0.0) & (L.all_open[l] != 0.0) & (L.gap[l] > L.release_gap[l]);
        L.fails[l] = releases ? 1.0 : L.fails[l];
    }
}

/// Loop 3: the resultant on B, and its torque about B's centre.
__attribute__((always_inline)) inline void resultants(JointLanes& L) {
    using namespace flat_detail;
    constexpr int count = kJointLanes;  // every lane: a fixed trip count, no scalar epilogue
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

/// The fully bonded joints of E elements (E known when compiled), loops 1-3 in one: each lane's
/// frame, its elements in order (FlatJointLaw::step's bonded branch, summed in element order)
/// and its resultant, the frame and the sums in registers. The same operations in the same
/// order as frames() and resultants() (which the mixed joints' kernel runs), so the same bits.
/// Its first lines are frames()'s on purpose: a helper handing back the kinematics, frame and
/// step constants (returned or through references) kept them in memory and the loop did not
/// vectorise (0.65× on 2e4-grain specimens).
template <std::size_t E>
__attribute__((always_inline)) inline void fused_bonded_joints(JointLanes& L, double dt, const DiscElement* elements) {
    using namespace flat_detail;
#pragma GCC ivdep
    for (int l = 0; l < kJointLanes; ++l) {
        PairState s{lane(L.xa, l), lane(L.xb, l), lane(L.va, l), lane(L.vb, l),
                    lane(L.wa, l), lane(L.wb, l), L.ra[l],       L.rb[l]};
        PairKinematics kin = pair_kinematics(s, dt);
        Vec3 bend_total;
        JointFrame f = advance_frame(lane(L.axis, l), lane(L.bend, l), L.twist[l], L.normal[l], kin, bend_total);
        JointStep js = joint_step(f, L.scale[l], {L.kn[l], L.ks[l]}, L.radius[l], kin);
        double s1 = 0.0, s2 = 0.0, fn = 0.0, p1 = 0.0, p2 = 0.0, tw = 0.0, stored = 0.0;
        bool fails = false;
#pragma GCC unroll 8
        for (std::size_t e = 0; e < E; ++e) {
            const DiscElement& g = elements[e];
            ElementTrial t = element_trial(g, f, js, L.shear[e][0][l], L.shear[e][1][l]);
            const double twist_energy = 0.5 * js.ksR4 * g.polar * f.twist * f.twist;
            NormalLoad load = linear_normal(g, f, js.kn, js.R, t.opening);
            fails |= lane_element_fails(L, l, g, js, load, t);
            stored += load.energy + 0.5 * (t.s1 * t.s1 + t.s2 * t.s2) * t.inv_ksa + twist_energy;
            L.shear[e][0][l] = t.s1;
            L.shear[e][1][l] = t.s2;
            s1 += t.s1;
            s2 += t.s2;
            fn += load.fn;
            p1 += load.p1;
            p2 += load.p2;
            tw += t.xy * t.s2 - t.xz * t.s1 - js.ksR4 * g.polar * f.twist;
        }
        JointSums sum;
        sum.s1 = s1;
        sum.s2 = s2;
        sum.fn = fn;
        sum.p1 = p1;
        sum.p2 = p2;
        sum.twist = tw;
        JointResultant r = joint_resultant(sum, f, kin.normal);
        set_lane(L.t1, l, f.t1);
        set_lane(L.bend_total, l, bend_total);
        L.twist[l] = f.twist;
        L.normal[l] = f.normal;
        L.fn[l] = fn;
        L.tw[l] = tw;
        L.stored[l] = stored;
        L.slip[l] = 0.0;
        L.fails[l] = fails ? 1.0 : 0.0;
        set_lane(L.force, l, r.force);
        set_lane(L.torque, l, cross(kin.arm_b, r.force) + r.moment);
        set_lane(L.shear_res, l, r.shear);
        set_lane(L.bend_res, l, r.bend);
    }
}

#if defined(__x86_64__) && defined(__GNUC__) && !defined(__clang__) && !defined(GRADEM_NO_CLONES)
#define GRADEM_JOINT_CLONES __attribute__((target_clones("avx512f", "avx2", "default")))
#else
#define GRADEM_JOINT_CLONES
#endif

/// fused_bonded_joints<E> for the joints' element count E in [1, kMaxLaneElements].
template <std::size_t... E>
__attribute__((always_inline)) inline void bonded_joints(JointLanes& L, double dt, std::span<const DiscElement> elements,
                                                         std::index_sequence<E...>) {
    (void)((elements.size() == E + 1 ? (fused_bonded_joints<E + 1>(L, dt, elements.data()), true) : false) || ...);
}

GRADEM_JOINT_CLONES __attribute__((flatten)) void joint_lanes(JointLanes& L, double dt,
                                                              std::span<const DiscElement> elements) {
    bonded_joints(L, dt, elements, std::make_index_sequence<kMaxLaneElements>{});
}

GRADEM_JOINT_CLONES __attribute__((flatten)) void mixed_joint_lanes(JointLanes& L, double dt,
                                                                    std::span<const DiscElement> elements) {
    frames(L, dt);
    for (std::size_t e = 0; e < elements.size(); ++e) mixed_normal(L, e, elements[e]);
    cut_elements(L, elements);
    for (std::size_t e = 0; e < elements.size(); ++e) mixed_shear(L, e, elements[e]);
    mark_releases(L);
    resultants(L);
}

/// Every lane's inputs a harmless dummy joint (two unit spheres apart and at rest, a unit joint
/// without load): the kernels' loops run over all kJointLanes lanes, and the lanes past a set's
/// joints must stay finite. Their results are never read.
void dummy_inputs(JointLanes& L) {
    for (int l = 0; l < kJointLanes; ++l) {
        set_lane(L.xa, l, {});
        set_lane(L.xb, l, {3.0, 0.0, 0.0});
        set_lane(L.va, l, {});
        set_lane(L.vb, l, {});
        set_lane(L.wa, l, {});
        set_lane(L.wb, l, {});
        set_lane(L.axis, l, {0.0, 1.0, 0.0});
        set_lane(L.bend, l, {});
        L.ra[l] = L.rb[l] = 1.0;
        L.twist[l] = L.normal[l] = L.tan_phi[l] = L.gap0[l] = L.friction[l] = L.release_gap[l] = 0.0;
        L.scale[l] = L.radius[l] = L.kn[l] = L.ks[l] = L.strength[l] = L.cohesion[l] = L.unbonded_kn[l] = 1.0;
        for (std::size_t e = 0; e < kMaxLaneElements; ++e) L.shear[e][0][l] = L.shear[e][1][l] = L.bonded[e][l] = 0.0;
    }
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
        for (std::size_t n = 0; n < acted.size(); ++n) {
            if (!acted[n]) continue;
            e.stored += terms[n].stored;
            e.released += terms[n].released;
            e.damage += terms[n].damage;
            e.slip += terms[n].slip;
        }
        e.lane_bonds = lanes;
        e.scalar_bonds = scalars;
        e.releases = releases;
        return e;
    }
};

/// FlatJointLaw::compute_all as a list of steps per batch of kJointLanes bonds: scan (the acting
/// joints into the fully bonded lanes and the others'), the lane arithmetic, then in bond order
/// the lanes that took the common path and every other acting joint through the law's scalar
/// kernel.
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
    /// Forces into particles (BondPass::force_owners): each particle's owning thread, else null;
    /// per bond block, the particles of the joints it released.
    std::int16_t* owner = nullptr;
    std::vector<std::vector<std::int32_t>> released_particles;

    FlatJointPass(const BondPass& p, double step)
        : pass(p), dt(step), side_data(p.side.data()), stride(p.stride), track(p.sim.track_energy) {
        for (const BondParams& bp : p.family_params) contexts.push_back(FlatJointLaw::context(bp, track));
        use_lanes = p.sim.vectorised_bond_passes && same_elements(contexts);
        elements = contexts.front().elements;
        const auto blocks = static_cast<std::size_t>(block_count(static_cast<std::int64_t>(p.bonds.size())));
        partial.resize(blocks);
        broken.resize(blocks);
        released_particles.resize(blocks);
    }

    /// Bonds [begin, end), block blk, run by thread `thread` (its index in the force owners).
    void block(std::int64_t begin, std::int64_t end, std::int64_t blk, std::int16_t thread = 0) {
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
        partial[static_cast<std::size_t>(blk)] = st.sum();
        partial[static_cast<std::size_t>(blk)].into_particles = into_particles;
        sort_breaks(broken[static_cast<std::size_t>(blk)]);
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
        load_joint(set.lanes, l, k, b);
        if (!fully_bonded) load_interface(set.lanes, l, k, b);
        if (set.lanes.count == kJointLanes) flush(set, st, blk);
    }

    /// 2-3. A set through its kernel: each joint whose lane took the common path stored, the
    ///    others through the scalar kernel; the set emptied.
    void flush(LaneSet& set, BlockState& st, std::int64_t blk) {
        JointLanes& L = set.lanes;
        if (L.count == 0) return;
        load_particles(L, pass.particles, set.ia, set.ib, L.count);
        if (set.mixed) mixed_joint_lanes(L, dt, elements);
        else joint_lanes(L, dt, elements);
        for (int l = 0; l < L.count; ++l) {
            if (L.fails[l] == 0.0) st.lane(set.bond[l], store_lane(set.bond[l], L, l, output(st, set.bond[l])));
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
        const double* side = side_data + ka * stride;
        for (std::size_t at = 0; at < stride; at += 8) __builtin_prefetch(side + at, 1);
        __builtin_prefetch(side + stride - 1, 1);
    }

    /// Lane l: joint k's radii, its header and element shear forces, its constants (its
    /// particles' vectors are copied in at flush()).
    __attribute__((always_inline)) inline void load_joint(JointLanes& L, int l, std::int64_t k, const ParallelBond& b) const {
        using namespace flat_side;
        const ParticleSet& particles = pass.particles;
        const double* side = side_data + static_cast<std::size_t>(k) * stride;
        const auto i = static_cast<std::size_t>(b.i), j = static_cast<std::size_t>(b.j);
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

    /// Lane l of a joint not fully bonded: its elements' bonded flags, g_0, μ_r, ρ, release gap.
    __attribute__((always_inline)) inline void load_interface(JointLanes& L, int l, std::int64_t k, const ParallelBond& b) const {
        using namespace flat_side;
        const double* side = side_data + static_cast<std::size_t>(k) * stride;
        for (std::size_t el = 0; el < elements.size(); ++el) L.bonded[el][l] = side[kFlatJointHeader + el * kFlatElementSize];
        L.gap0[l] = side[initial_gap];
        L.release_gap[l] = side[release_gap];
        L.friction[l] = contexts[b.family_pair].friction;
        L.unbonded_kn[l] = contexts[b.family_pair].unbonded_kn;
    }

    /// A joint whose lane took the law's common path (no element failed or was cut, nothing
    /// released): the lane's results become its state.
    __attribute__((always_inline)) inline BondStepResult store_lane(std::int64_t k, const JointLanes& L, int l,
                                                                    PairOutput& out) const {
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
        double* side = side_data + static_cast<std::size_t>(k) * stride;
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

/// Forces into particles: the particles' sums zeroed, then each thread its share of the bond
/// blocks, in order; the particles of the joints it released handed back.
void run_into_particles(FlatJointPass& joints, const BondPass& pass) {
    const auto nb = static_cast<std::int64_t>(pass.bonds.size());
    const auto n = static_cast<std::int64_t>(pass.particles.size());
#pragma omp parallel
    {
        const int team = team_size();
        const auto t = static_cast<std::int16_t>(thread_index());
        const auto [p0, p1] = thread_share(n, team, t);
        std::fill(pass.force + p0, pass.force + p1, Vec3{});
        std::fill(pass.torque + p0, pass.torque + p1, Vec3{});
#pragma omp single
        joints.owner = pass.force_owners(team);  // (a barrier: every share zeroed)
        const auto [first, last] = thread_share(block_count(nb), team, t);
        for (std::int64_t blk = first; blk < last; ++blk)
            joints.block(blk * kBlockSize, std::min(nb, (blk + 1) * kBlockSize), blk, t);
    }
    for (const auto& list : joints.released_particles)
        pass.released_particles->insert(pass.released_particles->end(), list.begin(), list.end());
}

}  // namespace

BondPassEnergy FlatJointLaw::compute_all(const BondPass& pass, double dt) {
    FlatJointPass joints(pass, dt);
    if (pass.force_owners) {
        pass.bond_torque->resize(pass.bonds.size());
        run_into_particles(joints, pass);
    } else {
        for_each_block(static_cast<std::int64_t>(pass.bonds.size()),
                       [&](std::int64_t begin, std::int64_t end, std::int64_t blk) { joints.block(begin, end, blk); });
    }
    for (auto& list : joints.broken) pass.breaks.insert(pass.breaks.end(), list.begin(), list.end());
    return ordered_sum(joints.partial);
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
