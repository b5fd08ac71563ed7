#pragma once
// Flat joint (Potyondy 2012, "A flat-jointed bonded-particle material for hard rock"; PFC's
// flatjoint, 3D; docs/bond_laws.md "Flat joint"). The interface is the bond disc of radius
// R̄ = λ̄ min(R_A, R_B) split into N_r x N_α annular-sector elements (disc_elements.hpp),
// in a frame (t1, t2) installed once and carried with the pair (rotate_into_plane).
//
// Kinematics, per step, with the pair's increments (pair_kinematics.hpp): the joint keeps its
// normal displacement since installation U_n [m] (opening +) and its bending rotation θ_b and
// twist θ_t [rad], accumulated in the carried frame; each element keeps its shear force F_s,e on
// B [N] as components in (t1, t2), so it turns with the frame:
//     δ_e = U_n + w.x_e,  w = n x θ_b          F_s,e -= k̄_s A_e (dU_s + dθ_t n x x_e)
// so the gap over the interface is linear, g(x) = g_0 + U_n + w.x.
//
// Bonded element (linear, tension and compression): F_n,e = k̄_n A_e δ_e (tension +), its own
// bending moment n x (k̄_n C_e w) and twist moment -k̄_s (C_yy + C_zz) θ_t n (the linear stress
// field over it; with every element bonded the joint is exactly the parallel bond's disc). It
// breaks in tension if σ_e = F_n,e/A_e >= σ̄_c, else in shear if
//     τ_e = |F_s,e|/A_e >= c̄ - min(σ_e, σ̄_c) tan φ̄      (σ tension +, so compression adds).
// Unbonded element (broken, or of a slit or gapped joint): normal stress ρ k̄_n min(g(x), 0)
// integrated over the element's compressed part (closed form, disc_elements.hpp), so a partly
// open element carries its share and a closed one its full bending stiffness. ρ (FlatJointParams::
// unbonded_stiffness_ratio, in (0, 1]) is 1 in PFC's flatjoint, whose broken element closes with
// the bonded k̄_n; under 1 a crack's faces close with a fraction of it, as the rough faces of a
// closed rock joint are more compliant in normal compression than the intact material (Bandis,
// Lumsden & Barton 1983, Int. J. Rock Mech. Min. Sci. 20(6) 249-268): a break then costs the
// joint compressive stiffness as well as tension. Shear stiffness stays k̄_s. Shear Coulomb,
// |F_s,e| <= μ |F_n,e| (μ = FlatJointParams::residual_friction), slip energy counted.
// Resultant on B about the contact point: F = Σ (F_s,e - F_n,e n), M = Σ (x_e x F_s,e + n x P_e)
// with P_e the first moment of the element's normal stresses (+ the twist of bonded elements).
// The bond record holds that resultant (normal_force = -F.n, ...).
//
// Joint types (Potyondy 2012 §2; PFC fj_mtype), drawn per joint with the strength seed:
// bonded (φ_B: every element bonded, g_0 = 0), gapped (φ_G: unbonded, initial gap
// g_0 = gap_ratio R̄) and slit (the rest: unbonded, g_0 = 0).
// ParallelBond::interface of a joint: 0 every element bonded, kPartlyBonded (2) intact with an
// unbonded element (so the vectorised pass, flat_joint_pass.cpp, tells the fully bonded joints
// from the bond record alone, without reading the element flags of the side state), 1 none bonded.
// A joint with no bonded element stays an interface (BondState none for slit and gapped joints,
// broken_* once its last element broke; ParallelBond::interface = 1) until its surfaces have
// separated: every element open AND the pair's surface gap beyond the installation reach
// (BondInstall::reach, the gap up to which bonds were installed). Then it is released and the
// pair continues as a plain linear contact (as PFC gives new contacts the linear model).
// Cracks: one BreakEvent per element break (element index, centroid position).
// Installation across a gap g > 0 (FlatJointParams::stiffness_over_gap): k̄_n and k̄_s scale by
// (R_A + R_B)/(R_A + R_B + g), a cement bridge as long as the centre distance; the reference
// state is the installed one (zero force, δ_e = 0).
// Simplified (stated): element strengths use the element's mean stresses (no β̄, so a 1x1
// joint cannot break in pure bending); an unbonded element's shear acts at its centroid and
// has no twist moment of its own; no residual cohesion (fj_cohres); the time step uses the
// undamaged touching disc (an upper bound on the stiffness).
// Contact: by default (BondParams::replaces_contact) an acting joint REPLACES the pair's linear
// contact (PFC's flatjoint is the pair's whole contact model).
#include <array>
#include <cmath>
#include <optional>
#include <span>
#include <sstream>
#include <string>
#include <vector>

#include "core/disc_elements.hpp"
#include "core/law_parameters.hpp"
#include "core/parallel_bond_law.hpp"
#include "core/random.hpp"

namespace gradem {

struct BondPass;        // core/bond_pass.hpp
struct BondPassEnergy;  // core/bond_pass.hpp

/// Flat joint shape parameters: the interface disc split into elements, and the joint's
/// microstructural types (Potyondy 2012): each joint is drawn bonded, gapped or slit with these
/// fractions (slit = 1 - bonded - gapped).
struct FlatJointParams {
    std::int32_t radial_elements = 1;   ///< N_r, in [1, 64]
    std::int32_t angular_elements = 4;  ///< N_α, in [1, 64]
    double residual_friction = 0.5;     ///< μ of an unbonded element, >= 0 [-]
    double bonded_fraction = 1.0;       ///< φ_B, joints installed bonded, in [0, 1] [-]
    double gapped_fraction = 0.0;       ///< φ_G, joints installed unbonded with gap g_0, in [0, 1] [-]
    double gap_ratio = 0.0;             ///< g_0 / R̄ of a gapped joint, >= 0 [-]
    /// true: a joint installed across a surface gap g > 0 has k̄_n = Ē*/(R_A + R_B + g), the
    /// stiffness of a cement bridge as long as the centre distance; false: Ē*/(R_A + R_B), the
    /// touching pair's, whatever the gap.
    bool stiffness_over_gap = false;
    /// ρ = k̄_n of an unbonded (broken, slit or gapped) element / the bonded element's, in (0, 1]:
    /// 1 is PFC's flatjoint; under 1 a crack closes with a fraction of the bonded stiffness.
    double unbonded_stiffness_ratio = 1.0;
};

/// Microstructural type of a joint (PFC fj_mtype order).
enum class FlatJointType : std::uint8_t { bonded = 0, gapped = 1, slit = 2 };

/// Side-state layout: a header, then kFlatElementSize doubles per element: bonded (1/0) and
/// the element's shear force on B in the joint frame, (F_s,e.t1, F_s,e.t2) [N].
namespace flat_side {
inline constexpr std::size_t axis = 0;             ///< t1 (3)
inline constexpr std::size_t bend = 3;             ///< θ_b (3) [rad]
inline constexpr std::size_t twist = 6;            ///< θ_t [rad]
inline constexpr std::size_t normal = 7;           ///< U_n, normal displacement since installation [m], opening +
inline constexpr std::size_t type = 8;             ///< FlatJointType as a double
inline constexpr std::size_t initial_gap = 9;      ///< g_0 [m]
inline constexpr std::size_t stiffness_scale = 10; ///< (R_A+R_B)/(R_A+R_B+g) or 1 [-]
inline constexpr std::size_t release_gap = 11;     ///< surface gap beyond which a separated joint is released [m]
}  // namespace flat_side
inline constexpr std::size_t kFlatJointHeader = 12, kFlatElementSize = 3;
/// ParallelBond::interface of an intact joint with at least one unbonded element.
inline constexpr std::uint8_t kPartlyBonded = 2;

inline bool flat_joint_element_bonded(std::span<const double> s, std::size_t e) {
    return s[kFlatJointHeader + e * kFlatElementSize] != 0.0;
}
inline FlatJointType flat_joint_type(std::span<const double> s) {
    return static_cast<FlatJointType>(static_cast<int>(s[flat_side::type]));
}

/// The installed in-plane axis t1 for normal n: n x (the axis of n's smallest component).
inline Vec3 flat_joint_initial_axis(const Vec3& n) {
    const double ax = std::fabs(n.x), ay = std::fabs(n.y), az = std::fabs(n.z);
    const Vec3 e = (ax <= ay && ax <= az) ? Vec3{1, 0, 0} : (ay <= az ? Vec3{0, 1, 0} : Vec3{0, 0, 1});
    const Vec3 t = cross(n, e);
    return (1.0 / norm(t)) * t;
}

/// The type of the joint of pair `key` (uniform draw against φ_B, φ_B + φ_G).
inline FlatJointType draw_flat_joint_type(const FlatJointParams& f, std::uint64_t seed, std::uint64_t key) {
    if (f.bonded_fraction >= 1.0) return FlatJointType::bonded;
    const double u = hashed_uniform(seed ^ 0x2545f4914f6cdd1dull, key, 0);
    if (u < f.bonded_fraction) return FlatJointType::bonded;
    if (u < f.bonded_fraction + f.gapped_fraction) return FlatJointType::gapped;
    return FlatJointType::slit;
}

namespace flat_detail {

/// The joint's frame and rotations after this step's increments.
struct JointFrame {
    Vec3 t1, t2;
    double wy = 0, wz = 0;  ///< w = n x θ_b in (t1, t2) [rad]
    double w_norm = 0;      ///< |w| [rad]
    double twist = 0;       ///< θ_t [rad]
    double normal = 0;      ///< U_n [m], opening +
};

/// The frame after this step's increments from the stored header (axis t1, bending θ_b, twist
/// θ_t, U_n); `bend_total` receives the carried θ_b. Pure: the vectorised pass over joints
/// (flat_joint_pass_lanes.cpp) calls it as carry_frame() does, so both give the same bits.
inline JointFrame advance_frame(const Vec3& axis0, const Vec3& bend0, double twist0, double normal0,
                                const PairKinematics& kin, Vec3& bend_total) {
    JointFrame f;
    const Vec3 t1 = rotate_into_plane(axis0, kin);
    f.t1 = (1.0 / norm(t1)) * t1;
    f.t2 = cross(kin.normal, f.t1);
    bend_total = rotate_into_plane(bend0, kin) + kin.bend_angle;
    f.twist = twist0 + kin.twist_angle;
    f.normal = normal0 + kin.du_normal;
    // θ_b = a t1 + b t2  ->  w = n x θ_b = a t2 - b t1.
    const double a = dot(bend_total, f.t1), b = dot(bend_total, f.t2);
    f.wy = -b;
    f.wz = a;
    f.w_norm = std::sqrt(a * a + b * b);
    return f;
}

inline JointFrame carry_frame(double* side, const PairKinematics& kin) {
    using namespace flat_side;
    Vec3 bend_total;
    const JointFrame f = advance_frame({side[axis], side[axis + 1], side[axis + 2]},
                                       {side[bend], side[bend + 1], side[bend + 2]}, side[twist], side[normal], kin,
                                       bend_total);
    side[axis] = f.t1.x, side[axis + 1] = f.t1.y, side[axis + 2] = f.t1.z;
    side[bend] = bend_total.x, side[bend + 1] = bend_total.y, side[bend + 2] = bend_total.z;
    side[twist] = f.twist;
    side[normal] = f.normal;
    return f;
}

/// The joint's per-step constants: k̄_n, k̄_s across the installation gap [Pa/m], R̄ [m] and
/// the shear increments of the contact point in (t1, t2) [m].
struct JointStep {
    double kn = 0, ks = 0, R = 0, R2 = 0, ksR4 = 0, inv_ks_r2 = 0;
    double du1 = 0, du2 = 0, dtwist = 0;
};
inline JointStep joint_step(const JointFrame& f, double scale, const BondStiffness& k_touching, double radius,
                            const PairKinematics& kin) {
    JointStep j;
    j.kn = k_touching.normal * scale;
    j.ks = k_touching.shear * scale;
    j.R = radius;
    j.R2 = j.R * j.R;
    j.ksR4 = j.ks * j.R2 * j.R2;
    j.inv_ks_r2 = 1.0 / (j.ks * j.R2);
    j.du1 = dot(kin.du_shear, f.t1);
    j.du2 = dot(kin.du_shear, f.t2);
    j.dtwist = kin.twist_angle;
    return j;
}

/// One element's kinematics and elastic trial shear: centroid x_e [m] in (t1, t2), opening
/// δ_e [m], shear increment dU_s + dθ_t n x x_e [m], trial F_s,e [N].
struct ElementTrial {
    double xy = 0, xz = 0, inv_ksa = 0, opening = 0, du1 = 0, du2 = 0, s1 = 0, s2 = 0;
};
inline ElementTrial element_trial(const DiscElement& g, const JointFrame& f, const JointStep& j, double old1,
                                  double old2) {
    ElementTrial t;
    t.xy = j.R * g.y;
    t.xz = j.R * g.z;
    const double ksa = j.ks * j.R2 * g.area;
    t.inv_ksa = j.inv_ks_r2 * g.inv_area;
    t.opening = f.normal + f.wy * t.xy + f.wz * t.xz;
    // Elastic trial shear: F_s,e -= k̄_s A_e (dU_s + dθ_t n x x_e), in (t1, t2).
    t.du1 = j.du1 - j.dtwist * t.xz;
    t.du2 = j.du2 + j.dtwist * t.xy;
    t.s1 = old1 - ksa * t.du1;
    t.s2 = old2 - ksa * t.du2;
    return t;
}

/// Σ over the elements, in element order: shear (t1, t2) [N], normal force (tension +) [N],
/// first moment P [N m], twist moment [N m], strain energy [J].
struct JointSums {
    double s1 = 0, s2 = 0, fn = 0, p1 = 0, p2 = 0, twist = 0, stored = 0;
};

/// Resultant on B about the contact point: F = Σ F_s,e - Σ F_n,e n;
/// M = Σ x_e x F_s,e + n x Σ P_e + twist of bonded elements.
struct JointResultant {
    Vec3 shear, bend, force, moment;
};
inline JointResultant joint_resultant(const JointSums& s, const JointFrame& f, const Vec3& n) {
    JointResultant r;
    r.shear = s.s1 * f.t1 + s.s2 * f.t2;
    r.bend = s.p1 * f.t2 - s.p2 * f.t1;
    r.force = s.s1 * f.t1 + s.s2 * f.t2 - s.fn * n;
    r.moment = s.twist * n + s.p1 * f.t2 - s.p2 * f.t1;
    return r;
}

/// The normal part of one element: F_n (tension +) [N], the first moment P = ∫ σ x dA of its
/// normal stresses in the joint frame [N m] (their moment on B is n x P), their strain energy
/// [J], and whether the element is open over its whole extent.
struct NormalLoad {
    double fn = 0, p1 = 0, p2 = 0, energy = 0;
    bool open = false;
};

/// Linear stress field over the whole element (bonded, or unbonded and closed everywhere):
/// F_n = k̄_n A g_e, P = k̄_n (A g_e x_e + C w), U = ½ k̄_n (A g_e² + wᵀ C w).
inline NormalLoad linear_normal(const DiscElement& g, const JointFrame& f, double kn, double R, double gap) {
    const double R2 = R * R, knR4 = kn * R2 * R2;
    const double cwy = g.cyy * f.wy + g.cyz * f.wz, cwz = g.cyz * f.wy + g.czz * f.wz;  // C w (unit disc)
    NormalLoad out;
    const double kna_gap = kn * R2 * g.area * gap;
    out.fn = kna_gap;
    out.p1 = kna_gap * R * g.y + knR4 * cwy;
    out.p2 = kna_gap * R * g.z + knR4 * cwz;
    out.energy = 0.5 * (kna_gap * gap + knR4 * (f.wy * cwy + f.wz * cwz));
    return out;
}

/// Unbonded element at centroid gap g_e = g_0 + δ_e: no tension, compressed part integrated
/// (γ = g_0 + U_n, the gap at the disc centre [m]; the joint's zero line comes from `line`,
/// made by the joint's first cut element and reused by the others).
inline NormalLoad unbonded_normal(const DiscElement& g, const JointFrame& f, double kn, double R, double gap,
                                  double gamma, ZeroLineCache& line) {
    const double spread = R * f.w_norm * g.reach;  // bounds |g(x) - g_e| over the element
    if (gap + spread <= 0.0) return linear_normal(g, f, kn, R, gap);
    NormalLoad out;
    if (gap - spread >= 0.0) {
        out.open = true;
        return out;
    }
    line.prepare(gamma, R * f.wy, R * f.wz);
    const CompressedPart c = compressed_part(g, line.field, line.crossing(g.ring, g.r0), line.crossing(g.ring + 1, g.r1));
    const double knR2 = kn * R * R;
    out.fn = knR2 * c.force;
    out.p1 = knR2 * R * c.py;
    out.p2 = knR2 * R * c.pz;
    out.energy = 0.5 * knR2 * c.energy;
    return out;
}

}  // namespace flat_detail

struct FlatJointLaw {
    using Params = FlatJointParams;
    // Designated initializers leave the other members at their defaults on purpose.
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wmissing-field-initializers"
    static constexpr std::array<LawParameter<FlatJointParams>, 8> kParameters = {{
        {.key = "radial_elements", .description = "N_r, elements across the joint radius (flat_joint)",
         .field = law_field<&FlatJointParams::radial_elements>, .core_field = "FlatJointParams::radial_elements",
         .range = {1.0, 64.0, false, false}, .calibration = Calibration::fixed_only, .lower = 1.0, .upper = 64.0},
        {.key = "angular_elements", .description = "N_alpha, elements around the joint (flat_joint)",
         .field = law_field<&FlatJointParams::angular_elements>, .core_field = "FlatJointParams::angular_elements",
         .range = {1.0, 64.0, false, false}, .calibration = Calibration::fixed_only, .lower = 1.0, .upper = 64.0},
        {.key = "residual_friction", .description = "mu of a broken joint element (flat_joint)",
         .field = law_field<&FlatJointParams::residual_friction>, .core_field = "FlatJointParams::residual_friction",
         .range = ranges::non_negative, .calibration = Calibration::free, .lower = 0.2, .upper = 1.0},
        {.key = "bonded_fraction",
         .description = "phi_B, fraction of joints installed bonded (flat_joint; the rest gapped or slit)",
         .field = law_field<&FlatJointParams::bonded_fraction>, .core_field = "FlatJointParams::bonded_fraction",
         .range = ranges::unit_closed, .calibration = Calibration::free, .lower = 0.3, .upper = 1.0},
        {.key = "gapped_fraction",
         .description = "phi_G, fraction of joints installed unbonded with an initial gap (flat_joint; slit = 1 - phi_B - phi_G)",
         .field = law_field<&FlatJointParams::gapped_fraction>, .core_field = "FlatJointParams::gapped_fraction",
         .range = ranges::unit_closed, .calibration = Calibration::free, .lower = 0.0, .upper = 0.5},
        {.key = "gap_ratio", .description = "g_0 / joint radius, the initial gap of a gapped joint (flat_joint)",
         .field = law_field<&FlatJointParams::gap_ratio>, .core_field = "FlatJointParams::gap_ratio",
         .range = ranges::non_negative, .calibration = Calibration::free, .lower = 0.0, .upper = 0.05},
        {.key = "stiffness_over_gap",
         .description = "true: a joint installed across a gap g has k_n = E*/(R_A + R_B + g) (a bridge as long as the "
                        "centre distance); false: E*/(R_A + R_B) (flat_joint)",
         .field = law_field<&FlatJointParams::stiffness_over_gap>, .core_field = "FlatJointParams::stiffness_over_gap",
         .range = ranges::flag, .calibration = Calibration::fixed_only, .lower = 0.0, .upper = 1.0},
        {.key = "unbonded_stiffness_ratio",
         .description = "rho, k_n of a broken, slit or gapped element / the bonded element's (flat_joint; 1: PFC's "
                        "flat joint; under 1 a crack closes more softly than the intact cement)",
         .field = law_field<&FlatJointParams::unbonded_stiffness_ratio>,
         .core_field = "FlatJointParams::unbonded_stiffness_ratio", .range = ranges::unit_open_left,
         .calibration = Calibration::free, .lower = 0.1, .upper = 1.0},
    }};
#pragma GCC diagnostic pop

    /// The rule across fields: φ_B + φ_G <= 1 (the ranges come from the rows).
    static std::optional<std::string> invalid_reason(const FlatJointParams& f) {
        if (f.bonded_fraction + f.gapped_fraction <= 1.0 + 1e-12) return std::nullopt;
        std::ostringstream out;
        out << "FlatJointParams::gapped_fraction = " << f.gapped_fraction
            << " violates <= 1 - FlatJointParams::bonded_fraction (the fractions sum to at most 1)";
        return out.str();
    }

    /// Broken joints slide on at μ_r after the peak, so a compression test runs on to ≈ 4.0 σ/E
    /// at the default stop fraction 0.7, with the peak at ≈ 1.5 σ/E (stopped at 0.85 × the peak,
    /// at 2.75 σ/E). Measured on the main job's runs (calibrate/configs/joint.toml: φ_B 0.7,
    /// ρ 0.5, μ_r 0.4, stop 0.85; D ≈ 1.6): their steps against --plan's, weighted by each run's
    /// cost (pre-blended 1.25-1.30×, Van Buren 1.0-1.12× what 1.3 / 3.2 predicted, which were
    /// measured on stiffer cracks, ρ 1 and D ≈ 1.4; joints of that shape end ≈ 20 % sooner).
    /// A tension test, mostly before its peak, costs 1.17× per particle-step what the bonded
    /// specimen at rest costs (0.99-1.15× measured), and so is a compression test up to its peak
    /// taken to; after it, broken and slit joints and the contacts the cracks make cost 1.4×
    /// (1.28-1.45×: the median compression run of each sand and specimen set against the probe,
    /// with the split above; 2.32× before the pass took the joints that are not fully bonded into
    /// its lanes; 2 workers on 2 cores; docs/calibration.md "The cost before the run"). Its
    /// direct-tension tests peak at 0.75-1.06 σ̄_c/Ē (8 tension runs), the rate aims at 0.75,
    /// and stopped at 0.85 × the peak they end at 1.17 × that expected strain (platen; the main
    /// job's 11 tension runs against --plan's steps).
    static constexpr PlatenTestCost kPlatenTestCost{.compression_end_over_elastic = 4.0,
                                                    .compression_peak_over_elastic = 1.5,
                                                    .pre_peak_cost_factor = 1.17,
                                                    .post_peak_cost_factor = 1.4,
                                                    .tension_cost_factor = 1.17,
                                                    .tension_peak_over_bond_strain = 0.75,
                                                    .tension_end_over_expected = 1.17};

    /// The analytic stand-in's extra shape index for a sand of ductility coefficient h
    /// (calibrate/analytic_model.cpp): h μ_r / 2, the frictional residual of broken elements.
    static double analytic_ductility(const FlatJointParams& f, double h) { return 0.5 * h * f.residual_friction; }

    struct Context {
        std::span<const DiscElement> elements;  ///< the layout's table (built once per process)
        double tan_phi = 0.0, friction = 0.5;
        double unbonded_kn = 1.0;  ///< ρ, FlatJointParams::unbonded_stiffness_ratio
        bool track = true;
    };
    /// The World's bond phase for flat joints: every joint vectorised across joints but those
    /// with an element that breaks in the step, which go through step(); bitwise step()'s
    /// results (core/flat_joint_pass.cpp).
    static BondPassEnergy compute_all(const BondPass& pass, double dt);
    /// The pair slots a pass into particles (BondPass::force_owners) did not write, from the
    /// bonds and the moments it kept (flat_joint_pass.cpp): the same bits as writing them.
    static void rebuild_slots(const BondPass& pass);

    static Context context(const auto& p, bool track) {
        const FlatJointParams& own = law_params<FlatJointLaw>(p);
        return {disc_element_table(own.radial_elements, own.angular_elements),
                std::tan(p.friction_angle_deg * kPi / 180.0), own.residual_friction, own.unbonded_stiffness_ratio, track};
    }
    static std::size_t side_size(const auto& p) {
        const FlatJointParams& own = law_params<FlatJointLaw>(p);
        return kFlatJointHeader + kFlatElementSize * static_cast<std::size_t>(own.radial_elements) *
                                      static_cast<std::size_t>(own.angular_elements);
    }
    static void install(const auto& p, const BondInstall& in, ParallelBond& b, double* side) {
        using namespace flat_side;
        const FlatJointParams& own = law_params<FlatJointLaw>(p);
        const Vec3 t = flat_joint_initial_axis(in.normal);
        side[axis] = t.x, side[axis + 1] = t.y, side[axis + 2] = t.z;
        const FlatJointType type_drawn = draw_flat_joint_type(own, p.seed, in.key);
        const double joint_radius = p.radius_multiplier * std::min(in.radius_a, in.radius_b);
        side[type] = static_cast<double>(static_cast<int>(type_drawn));
        side[initial_gap] = type_drawn == FlatJointType::gapped ? own.gap_ratio * joint_radius : 0.0;
        const double length = in.radius_a + in.radius_b;
        side[stiffness_scale] = own.stiffness_over_gap && in.gap > 0.0 ? length / (length + in.gap) : 1.0;
        side[release_gap] = std::max(in.reach, in.gap);
        const std::size_t n = (side_size(p) - kFlatJointHeader) / kFlatElementSize;
        const double bonded = type_drawn == FlatJointType::bonded ? 1.0 : 0.0;
        for (std::size_t e = 0; e < n; ++e) side[kFlatJointHeader + e * kFlatElementSize] = bonded;
        if (type_drawn != FlatJointType::bonded) {
            b.state = BondState::none;
            b.interface = 1;
        }
    }

    static BondStepResult step(const Context& c, ParallelBond& b, double* side,
                               const BondSection& sec, const BondStiffness& k_touching,
                               const PairKinematics& kin, std::vector<BondBreak>& breaks) {
        using namespace flat_detail;
        BondStepResult r;
        const Vec3& n = kin.normal;
        const JointFrame f = carry_frame(side, kin);
        const JointStep js = joint_step(f, side[flat_side::stiffness_scale], k_touching, sec.radius, kin);
        const double g0 = side[flat_side::initial_gap];
        ZeroLineCache zero_line;  // the unbonded elements' zero line, made when first needed

        JointSums sum;
        bool any_bonded = false, all_bonded = true, all_open = true;
        BondState last_mode = BondState::intact;
        for (std::size_t e = 0; e < c.elements.size(); ++e) {
            const DiscElement& g = c.elements[e];
            double* p = side + kFlatJointHeader + e * kFlatElementSize;
            const double old1 = p[1], old2 = p[2];
            ElementTrial t = element_trial(g, f, js, old1, old2);
            const double twist_energy = 0.5 * js.ksR4 * g.polar * f.twist * f.twist;
            bool bonded = p[0] != 0.0, broke_now = false;
            double energy_before = 0.0;
            NormalLoad load;
            if (bonded) {
                load = linear_normal(g, f, js.kn, js.R, t.opening);
                const double inv_a = g.inv_area / js.R2;
                const BondState mode =
                    element_failure(c, b, load.fn * inv_a, (t.s1 * t.s1 + t.s2 * t.s2) * inv_a * inv_a);
                if (mode != BondState::intact) {
                    const double tau = std::sqrt(t.s1 * t.s1 + t.s2 * t.s2) * inv_a;
                    energy_before = load.energy + 0.5 * (t.s1 * t.s1 + t.s2 * t.s2) * t.inv_ksa + twist_energy;
                    breaks.push_back({mode, static_cast<std::int32_t>(e), t.xy * f.t1 + t.xz * f.t2, load.fn * inv_a, tau});
                    bonded = false;
                    broke_now = true;
                    last_mode = mode;
                }
            }
            if (!bonded) {
                load = unbonded_normal(g, f, js.kn * c.unbonded_kn, js.R, g0 + t.opening, g0 + f.normal, zero_line);
                frictional_cap(c, t.s1, t.s2, old1, old2, t.du1, t.du2, load.fn, t.inv_ksa, !broke_now, r.slip);
            }
            const double energy =
                load.energy + 0.5 * (t.s1 * t.s1 + t.s2 * t.s2) * t.inv_ksa + (bonded ? twist_energy : 0.0);
            if (broke_now) r.released += energy_before - energy;
            sum.stored += energy;
            p[0] = bonded ? 1.0 : 0.0;
            p[1] = t.s1;
            p[2] = t.s2;
            sum.s1 += t.s1;
            sum.s2 += t.s2;
            sum.fn += load.fn;
            sum.p1 += load.p1;
            sum.p2 += load.p2;
            sum.twist += t.xy * t.s2 - t.xz * t.s1 - (bonded ? js.ksR4 * g.polar * f.twist : 0.0);
            any_bonded = any_bonded || bonded;
            all_bonded = all_bonded && bonded;
            all_open = all_open && load.open;
        }
        if (any_bonded) b.interface = all_bonded ? 0 : kPartlyBonded;  // intact here
        if (!any_bonded) {
            if (b.state == BondState::intact) {  // the last element broke: an unbonded interface now
                b.state = last_mode == BondState::intact ? BondState::broken_tension : last_mode;
                b.interface = 1;
            }
            if (all_open && kin.gap > side[flat_side::release_gap]) {  // separated: released
                if (c.track) r.released += sum.stored;
                release_bond(b, b.state);
                b.interface = 0;
                r.failure = b.state;  // broken_* or none: no longer acting
                return r;
            }
        }
        store_resultant(c, b, r, sum, f, n);
        return r;
    }

    /// Whether a bonded element at mean stresses σ (tension +) [Pa] and τ² [Pa²] fails, as
    /// element_failure() decides it, without branches (the vectorised pass).
    static bool element_fails(double sigma, double tau2, double tensile_strength, double cohesion, double tan_phi) {
        const double strength = cohesion - sigma * tan_phi;
        return (sigma >= tensile_strength) | (strength <= 0.0) | (tau2 >= strength * strength);
    }

    static TimeStepStiffness time_step_stiffness(const BondSection& s, const BondStiffness& k,
                                                 double r) {
        return disc_time_step_stiffness(s, k, r);
    }

private:
    /// The acting joint's results: its energies, the resultant on B (bond record and pair force).
    static void store_resultant(const Context& c, ParallelBond& b, BondStepResult& r, const flat_detail::JointSums& sum,
                                const flat_detail::JointFrame& f, const Vec3& n) {
        if (!c.track) r.released = 0.0;
        if (c.track) r.stored = sum.stored;
        const flat_detail::JointResultant res = flat_detail::joint_resultant(sum, f, n);
        b.normal_force = sum.fn;
        b.shear_force = res.shear;
        b.twist_moment = sum.twist;
        b.bend_moment = res.bend;
        r.force_j = res.force;
        r.moment_j = res.moment;
    }

    /// Which way a bonded element fails at mean stresses σ (tension +) and τ² [Pa²], if it does:
    /// tension if σ >= σ̄_c, shear if τ >= c̄ - σ tan φ̄ (σ < σ̄_c here).
    static BondState element_failure(const Context& c, const ParallelBond& b, double sigma, double tau2) {
        if (sigma >= b.tensile_strength) return BondState::broken_tension;
        const double strength = b.cohesion - sigma * c.tan_phi;
        if (strength <= 0.0 || tau2 >= strength * strength) return BondState::broken_shear;
        return BondState::intact;
    }

    /// Coulomb cap |F_s| <= μ max(-F_n, 0) of an unbonded element, in (t1, t2); adds the slip
    /// energy of the step (trapezoidal work of the capped force on the slip increment) if asked.
    static void frictional_cap(const Context& c, double& s1, double& s2, double old1, double old2, double du1,
                               double du2, double fn, double inv_ksa, bool count_slip, double& slip) {
        const double limit = fn < 0.0 ? -c.friction * fn : 0.0;
        const double m2 = s1 * s1 + s2 * s2;
        if (!(m2 > limit * limit)) return;
        const double f = limit > 0.0 ? limit / std::sqrt(m2) : 0.0;  // an open element: no sqrt, the same +0
        const double c1 = f * s1, c2 = f * s2;
        if (count_slip && c.track)
            slip += -0.5 * ((old1 + c1) * du1 + (old2 + c2) * du2) -
                    0.5 * (c1 * c1 + c2 * c2 - old1 * old1 - old2 * old2) * inv_ksa;
        s1 = c1;
        s2 = c2;
    }
};

}  // namespace gradem
