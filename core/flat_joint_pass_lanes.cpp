// The flat joint's lane kernels (core/flat_joint_pass_lanes.hpp): loops over every lane of a
// set (a fixed trip count, so no scalar epilogue: the lanes past the set's joints hold harmless
// dummies) run the pair kinematics and the frame, then each element (element loop outside, lanes
// inside: one vector operation serves a vector's worth of joints; for the fully bonded set all
// elements of a lane in one loop, its frame and sums in registers), then the resultant — compiled
// for AVX-512, AVX2 and the baseline ISA (function multiversioning, picked at load time). For the
// mixed set the element loop is split: the normal load of every element (bonded: linear with its
// failure test; unbonded: linear if closed over its whole extent, nil if open), the elements the
// zero line cuts (gathered from all the set's joints into one list and run through
// unbonded_normal's closed form written without branches, core/disc_elements_branchless.hpp,
// vectorised across the list), then the shear with the Coulomb cap and the sums in element order.
// The lanes call the law's own helpers (advance_frame, joint_step, element_trial, linear_normal,
// unbonded_normal, joint_resultant) in the law's order, selects stand for its branches, and
// every lane does the same IEEE operations as the scalar code (-ffp-contract=off: no FMA; no
// reassociation), so the results are bitwise those of FlatJointLaw::step
// (tests/core/test_determinism.cpp: the pinned hashes, and the lanes against the scalar kernel).
// A set's joints' state comes in and goes back four lanes at a time by 4x4 transposes of their
// side-state rows, constants and bond records (core/lane_load.hpp), not one double at a time: a
// copy of bits either way (1.10-1.18x on 2e4-grain specimens, bench/README.md).
#include "core/flat_joint_pass_lanes.hpp"

#include <algorithm>
#include <array>
#include <cstddef>
#include <utility>

#include "core/disc_elements_branchless.hpp"
#include "core/flat_joint_law.hpp"
#include "core/lane_load.hpp"

namespace gradem::flat_lanes {
namespace {

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

// The transposes below copy fixed runs of a joint's side state: these places.
static_assert(flat_side::axis == 0 && flat_side::bend == 3 && flat_side::twist == 6 && flat_side::normal == 7);
static_assert(flat_side::type == 8 && flat_side::initial_gap == 9 && flat_side::stiffness_scale == 10 &&
              flat_side::release_gap == 11 && kFlatJointHeader == 12 && kFlatElementSize == 3);
// ... and of its record: F̄_n, F̄_s, M̄_t, M̄_b one after the other.
static_assert(offsetof(ParallelBond, shear_force) == offsetof(ParallelBond, normal_force) + sizeof(double) &&
              offsetof(ParallelBond, twist_moment) == offsetof(ParallelBond, shear_force) + sizeof(Vec3) &&
              offsetof(ParallelBond, bend_moment) == offsetof(ParallelBond, twist_moment) + sizeof(double));
static_assert(offsetof(BondConstants, inv_radius) == sizeof(double) &&
              offsetof(BondConstants, stiffness) == 2 * sizeof(double) && sizeof(BondStiffness) == 2 * sizeof(double));

/// Joint k's side state.
inline double* side_of(const JointStore& s, std::int64_t k) { return s.side + static_cast<std::size_t>(k) * s.stride; }

/// Lane l from joint k's state, one double at a time.
inline void load_joint_scalar(JointLanes& L, const JointStore& s, std::int64_t k, int l, std::size_t elements) {
    using namespace flat_side;
    const double* side = side_of(s, k);
    set_lane(L.axis, l, {side[axis], side[axis + 1], side[axis + 2]});
    set_lane(L.bend, l, {side[bend], side[bend + 1], side[bend + 2]});
    L.twist[l] = side[twist];
    L.normal[l] = side[normal];
    L.gap0[l] = side[initial_gap];
    L.scale[l] = side[stiffness_scale];
    L.release_gap[l] = side[release_gap];
    for (std::size_t el = 0; el < elements; ++el) {
        const double* p = side + kFlatJointHeader + el * kFlatElementSize;
        L.bonded[el][l] = p[0];
        L.shear[el][0][l] = p[1];
        L.shear[el][1][l] = p[2];
    }
    const BondConstants& bc = s.constants[k];
    L.radius[l] = bc.radius;
    L.kn[l] = bc.stiffness.normal;
    L.ks[l] = bc.stiffness.shear;
}

/// Lane l's results into joint k's state, one double at a time.
inline void store_joint_scalar(const JointLanes& L, const JointStore& s, std::int64_t k, int l, std::size_t elements) {
    using namespace flat_side;
    double* side = side_of(s, k);
    const Vec3 t1 = lane(L.t1, l), bend_total = lane(L.bend_total, l);
    side[axis] = t1.x, side[axis + 1] = t1.y, side[axis + 2] = t1.z;
    side[bend] = bend_total.x, side[bend + 1] = bend_total.y, side[bend + 2] = bend_total.z;
    side[twist] = L.twist[l];
    side[normal] = L.normal[l];
    for (std::size_t el = 0; el < elements; ++el) {
        double* p = side + kFlatJointHeader + el * kFlatElementSize;
        p[1] = L.shear[el][0][l];
        p[2] = L.shear[el][1][l];
    }
    ParallelBond& b = s.bonds[k];
    b.normal_force = L.fn[l];
    b.shear_force = lane(L.shear_res, l);
    b.twist_moment = L.tw[l];
    b.bend_moment = lane(L.bend_res, l);
}

#ifdef GRADEM_LANE_TRANSPOSE
/// load_joint_scalar for lanes [0, count), four at a time by transposes (core/lane_load.hpp):
/// the same bits.
__attribute__((target("avx2"))) void load_joints_transposed(JointLanes& L, const JointStore& s, const std::int64_t* bond,
                                                            int count, std::size_t elements) {
    double type[4], inv_radius[4];  // read with their neighbours, not needed
    int l0 = 0;
    for (; l0 + 4 <= count; l0 += 4) {
        const double* const side[4] = {side_of(s, bond[l0]), side_of(s, bond[l0 + 1]), side_of(s, bond[l0 + 2]),
                                       side_of(s, bond[l0 + 3])};
        const auto at = [&](std::size_t offset) {
            return std::array<const double*, 4>{side[0] + offset, side[1] + offset, side[2] + offset, side[3] + offset};
        };
        rows_to_lanes4(at(0).data(), std::array<double*, 4>{&L.axis[0][l0], &L.axis[1][l0], &L.axis[2][l0], &L.bend[0][l0]}.data());
        rows_to_lanes4(at(4).data(), std::array<double*, 4>{&L.bend[1][l0], &L.bend[2][l0], &L.twist[l0], &L.normal[l0]}.data());
        rows_to_lanes4(at(8).data(), std::array<double*, 4>{type, &L.gap0[l0], &L.scale[l0], &L.release_gap[l0]}.data());
        for (std::size_t el = 0; el < elements; ++el)
            rows_to_lanes4(at(kFlatJointHeader + el * kFlatElementSize).data(),
                           std::array<double*, 4>{&L.bonded[el][l0], &L.shear[el][0][l0], &L.shear[el][1][l0], nullptr}.data(),
                           3);
        const std::array<const double*, 4> constants{&s.constants[bond[l0]].radius, &s.constants[bond[l0 + 1]].radius,
                                                     &s.constants[bond[l0 + 2]].radius, &s.constants[bond[l0 + 3]].radius};
        rows_to_lanes4(constants.data(), std::array<double*, 4>{&L.radius[l0], inv_radius, &L.kn[l0], &L.ks[l0]}.data());
    }
    for (int l = l0; l < count; ++l) load_joint_scalar(L, s, bond[l], l, elements);
}

/// store_joint_scalar for the lanes of [0, count) that took the common path, four at a time by
/// transposes where all four did: the same bits.
__attribute__((target("avx2"))) void store_joints_transposed(const JointLanes& L, const JointStore& s,
                                                             const std::int64_t* bond, int count, std::size_t elements) {
    int l0 = 0;
    for (; l0 + 4 <= count; l0 += 4) {
        if (L.fails[l0] != 0.0 || L.fails[l0 + 1] != 0.0 || L.fails[l0 + 2] != 0.0 || L.fails[l0 + 3] != 0.0) {
            for (int l = l0; l < l0 + 4; ++l)
                if (L.fails[l] == 0.0) store_joint_scalar(L, s, bond[l], l, elements);
            continue;
        }
        double* const side[4] = {side_of(s, bond[l0]), side_of(s, bond[l0 + 1]), side_of(s, bond[l0 + 2]),
                                 side_of(s, bond[l0 + 3])};
        const auto at = [&](std::size_t offset) {
            return std::array<double*, 4>{side[0] + offset, side[1] + offset, side[2] + offset, side[3] + offset};
        };
        lanes_to_rows4(std::array<const double*, 4>{&L.t1[0][l0], &L.t1[1][l0], &L.t1[2][l0], &L.bend_total[0][l0]}.data(),
                       at(0).data());
        lanes_to_rows4(std::array<const double*, 4>{&L.bend_total[1][l0], &L.bend_total[2][l0], &L.twist[l0], &L.normal[l0]}.data(),
                       at(4).data());
        for (std::size_t el = 0; el < elements; ++el)
            lane_pairs_to_rows4(&L.shear[el][0][l0], &L.shear[el][1][l0], at(kFlatJointHeader + el * kFlatElementSize + 1).data());
        double* const record[4] = {&s.bonds[bond[l0]].normal_force, &s.bonds[bond[l0 + 1]].normal_force,
                                   &s.bonds[bond[l0 + 2]].normal_force, &s.bonds[bond[l0 + 3]].normal_force};
        lanes_to_rows4(std::array<const double*, 4>{&L.fn[l0], &L.shear_res[0][l0], &L.shear_res[1][l0], &L.shear_res[2][l0]}.data(),
                       record);
        double* const moments[4] = {record[0] + 4, record[1] + 4, record[2] + 4, record[3] + 4};
        lanes_to_rows4(std::array<const double*, 4>{&L.tw[l0], &L.bend_res[0][l0], &L.bend_res[1][l0], &L.bend_res[2][l0]}.data(),
                       moments);
    }
    for (int l = l0; l < count; ++l)
        if (L.fails[l] == 0.0) store_joint_scalar(L, s, bond[l], l, elements);
}
#endif

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

}  // namespace

void load_particles(JointLanes& L, const ParticleSet& particles, const std::int32_t* ia, const std::int32_t* ib,
                    int count) {
#ifdef GRADEM_LANE_TRANSPOSE
    if (lane_transpose_available()) return load_particles_transposed(L, particles, ia, ib, count);
#endif
    load_particles_scalar(L, particles, ia, ib, 0, count);
}

void load_joints(JointLanes& L, const JointStore& store, const std::int64_t* bond, int count, std::size_t elements) {
#ifdef GRADEM_LANE_TRANSPOSE
    if (lane_transpose_available()) return load_joints_transposed(L, store, bond, count, elements);
#endif
    for (int l = 0; l < count; ++l) load_joint_scalar(L, store, bond[l], l, elements);
}

void store_joints(const JointLanes& L, const JointStore& store, const std::int64_t* bond, int count,
                  std::size_t elements) {
#ifdef GRADEM_LANE_TRANSPOSE
    if (lane_transpose_available()) return store_joints_transposed(L, store, bond, count, elements);
#endif
    for (int l = 0; l < count; ++l)
        if (L.fails[l] == 0.0) store_joint_scalar(L, store, bond[l], l, elements);
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

/// Two unit spheres 3 m apart on x and at rest, a unit joint without load: the lanes past a
/// set's joints must stay finite. Their results are never read.
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

}  // namespace gradem::flat_lanes
