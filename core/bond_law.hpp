#pragma once
// What every bond law shares: the bond record, the bond disc geometry and stiffness,
// and the interface of a law kernel. The laws themselves are pure kernels, one header each
// (core/<law>_law.hpp; core/parallel_bond_law.hpp, Potyondy & Cundall 2004, is the reference),
// and core/bond_models.hpp holds the one list of laws (BondModel <-> kernel <-> name).
//
// Geometry (Potyondy & Cundall 2004; docs/bond_laws.md): a bond is a disc of cement of radius R̄ = λ̄ min(R_A, R_B) with
// area Ā = π R̄², moment of inertia Ī = π R̄⁴/4 and polar moment J̄ = π R̄⁴/2, and stiffness per
// unit area k̄_n = Ē*/(R_A + R_B), k̄_s = k̄_n/κ̄. Sign convention: the bond normal force is
// TENSION positive; shear force, twist and bending moments are stored as acting on B (A gets
// the opposite).
//
// Law kernel interface (a struct with static members; see ParallelBondLaw for the reference):
//     Params                          its own parameter struct (NoLawParams for none), held by
//                                     BondParams (params.law<Law>(), law_params<Law>(params))
//     kParameters                     one LawParameter row per member of Params
//                                     (core/law_parameters.hpp: key, unit, range, calibration)
//     Context context(params, track)  per-step constants (tan φ̄, element tables, ...)
//     side_size(params)               doubles of per-bond side state (0: none, no memory used)
//     install(params, install, bond, side)  initialises a new bond (side state, state)
//     step(ctx, bond, side, section, stiffness, kinematics, breaks) -> BondStepResult
//     time_step_stiffness(section, stiffness, r) -> TimeStepStiffness (undamaged)
// `params` is the bond family's BondParams; context, side_size and install take it as a template
// argument (const auto&), so a law's header needs only its own parameter struct. Optional hooks:
//     invalid_reason(own) -> optional<string>  rules across fields (ranges come from the rows)
//     analytic_ductility(own, h) -> double     the analytic stand-in's extra shape index for a
//                                              sand of ductility coefficient h
//                                              (calibrate/analytic_model.cpp)
//     kPlatenTestCost                          what its platen tests cost, as --plan prices
//                                              them (core/law_parameters.hpp, calibrate/plan.cpp)
//     compute_all(pass, dt) -> BondPassEnergy  the law's own pass over every bond, instead of
//                                              the World's generic loop (core/bond_pass.hpp)
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

#include "core/law_parameters.hpp"
#include "core/pair_kinematics.hpp"

namespace gradem {

/// The law a bond follows; its enumerators are the rows of core/bond_models.hpp.
enum class BondModel : std::uint8_t;

/// A law's own parameters in a BondParams (core/params.hpp): law_params<Law>(params).
template <class Law, class AnyBondParams>
const typename Law::Params& law_params(const AnyBondParams& params) {
    return params.template law<Law>();
}

/// PFC pb_state codes: 0 never bonded, 1 broken in tension, 2 broken in shear, 3 bonded.
enum class BondState : std::uint8_t { none = 0, broken_tension = 1, broken_shear = 2, intact = 3 };

/// One bond. Stiffnesses come from the World's BondParams (they depend only on the radii and
/// Ē*); strengths are per bond (drawn at installation). The force fields are what the bond
/// TRANSMITS (for a damage law: the damaged forces; for a law of several elements: their
/// resultant about the contact point). Law-specific state lives in the World's side array.
struct ParallelBond {
    std::int32_t i = -1, j = -1;   ///< particle indices, i < j
    std::int32_t slot = -1;        ///< index of the pair in the World's interaction list
    BondState state = BondState::intact;
    BondModel model{};             ///< the law this bond follows (0: the parallel bond)
    std::uint8_t family_pair = 0;  ///< its parameters: World::bond_family_params()[family_pair]
    /// 1 while a bond that is not (or no longer) bonded still acts as an interface (a joint
    /// whose elements are all unbonded: it carries compression and friction until its
    /// surfaces separate); its law keeps stepping it, and it replaces the pair's contact. A law of
    /// several elements may keep its own marks here (e.g. an intact bond with an unbonded
    /// element), so its pass tells fully bonded bonds from the record alone.
    std::uint8_t interface = 0;
    double tensile_strength = 0.0; ///< σ̄_c [Pa]
    double cohesion = 0.0;         ///< c̄ [Pa]
    double normal_force = 0.0;     ///< F̄_n, tension positive [N]
    Vec3 shear_force;              ///< F̄_s on j [N]
    double twist_moment = 0.0;     ///< M̄_t about n, on j [N m]
    Vec3 bend_moment;              ///< M̄_b on j [N m]
};

/// Whether the bond law still acts on this pair (intact, or an unbonded interface).
inline bool bond_acts(const ParallelBond& b) { return b.state == BondState::intact || b.interface != 0; }

/// What a law's install() knows of a new bond: the pair's geometry at installation and the
/// key that seeds per-bond draws (same seed + pair = same draw, whatever the thread count).
struct BondInstall {
    Vec3 normal;            ///< n, unit, A -> B
    double gap = 0.0;       ///< surface gap at installation [m] (< 0: overlap)
    double radius_a = 0.0, radius_b = 0.0;  ///< R_A, R_B [m]
    std::uint64_t key = 0;  ///< (i << 32) | j
    double reach = 0.0;     ///< the largest surface gap bonds were installed across [m]
};

/// Bond cross-section; reciprocals are kept so the per-step kernel needs one division.
struct BondSection {
    double radius = 0, area = 0, inertia = 0, polar = 0;  ///< R̄ [m], Ā [m²], Ī, J̄ [m⁴]
    double inv_area = 0;             ///< 1/Ā [1/m²]
    double radius_over_inertia = 0;  ///< R̄/Ī [1/m³]
    double radius_over_polar = 0;    ///< R̄/J̄ [1/m³]
};

/// The section of a disc of radius R̄ [m] given with its reciprocal 1/R̄ [1/m] (multiplications
/// only: the World keeps R̄ and 1/R̄ per bond and rebuilds the rest each step).
inline BondSection bond_section_of_radius(double radius, double inv_r) {
    BondSection s;
    s.radius = radius;
    s.area = kPi * s.radius * s.radius;
    s.inertia = 0.25 * s.area * s.radius * s.radius;
    s.polar = 2.0 * s.inertia;
    s.inv_area = inv_r * inv_r * (1.0 / kPi);
    s.radius_over_inertia = 4.0 * s.inv_area * inv_r;
    s.radius_over_polar = 0.5 * s.radius_over_inertia;
    return s;
}

inline BondSection bond_section(double radius_multiplier, double ra, double rb) {
    const double radius = radius_multiplier * (ra < rb ? ra : rb);
    return bond_section_of_radius(radius, 1.0 / radius);
}

struct BondStiffness {
    double normal = 0, shear = 0;  ///< k̄_n, k̄_s per unit area [Pa/m]
};

inline BondStiffness bond_stiffness(double effective_modulus, double stiffness_ratio, double ra,
                                    double rb) {
    const double kn = effective_modulus / (ra + rb);
    return {kn, kn / stiffness_ratio};
}

struct BondStress {
    double tensile = 0.0;  ///< σ̄ [Pa], tension positive
    double shear = 0.0;    ///< τ̄ [Pa]
    double axial = 0.0;    ///< σ = F̄_n/Ā [Pa]
};

/// A break reported by a law kernel: the whole bond (element = -1) or one element of it.
struct BondBreak {
    BondState mode = BondState::broken_tension;
    std::int32_t element = -1;  ///< flat-joint element index, -1 for the whole bond
    Vec3 offset;                ///< from the contact point to the crack centre [m]
    double tensile_stress = 0.0;  ///< [Pa] at break
    double shear_stress = 0.0;    ///< [Pa] at break
};

/// What one step of a law kernel produced for one bond.
struct BondStepResult {
    BondState failure = BondState::intact;  ///< != intact: the bond stopped acting this step (released)
    Vec3 force_j;       ///< force on j [N] (zero once broken)
    Vec3 moment_j;      ///< moment on j about the contact point, lever arm excluded [N m]
    double stored = 0.0;    ///< elastic energy after the step (if tracked) [J]
    double released = 0.0;  ///< stored energy lost by breaks this step [J]
    double damage = 0.0;    ///< energy dissipated by damage (softening) this step [J]
    double slip = 0.0;      ///< energy dissipated by friction of broken elements this step [J]
};

/// Stiffness a bond adds to its particles for the critical time step (undamaged values).
struct TimeStepStiffness {
    double translational = 0.0;  ///< [N/m]
    double rotational = 0.0;     ///< [N m/rad], for a particle of radius r
};

/// Advances F̄_n, F̄_s, M̄_t, M̄_b by one step of relative motion (Potyondy & Cundall 2004):
///     F̄_n += k̄_n Ā dU_n,  F̄_s = rot(F̄_s) - k̄_s Ā dU_s,
///     M̄_t -= k̄_s J̄ dθ_t,  M̄_b = rot(M̄_b) - k̄_n Ī dθ_b.
inline void update_bond_forces(ParallelBond& b, const BondSection& s, const BondStiffness& k,
                               const PairKinematics& kin) {
    b.shear_force = rotate_into_plane(b.shear_force, kin);
    b.bend_moment = rotate_into_plane(b.bend_moment, kin);
    b.normal_force += k.normal * s.area * kin.du_normal;
    b.shear_force -= (k.shear * s.area) * kin.du_shear;
    b.twist_moment -= k.shear * s.polar * kin.twist_angle;
    b.bend_moment -= (k.normal * s.inertia) * kin.bend_angle;
}

/// Peak stresses at the periphery (beam theory, β̄ = moment-contribution factor):
///     σ̄ = F̄_n/Ā + β̄ |M̄_b| R̄/Ī,   τ̄ = |F̄_s|/Ā + β̄ |M̄_t| R̄/J̄.
inline BondStress bond_peak_stress(const ParallelBond& b, const BondSection& s,
                                   double moment_factor) {
    BondStress out;
    out.axial = b.normal_force * s.inv_area;
    out.tensile = out.axial + moment_factor * norm(b.bend_moment) * s.radius_over_inertia;
    out.shear = norm(b.shear_force) * s.inv_area +
                moment_factor * std::fabs(b.twist_moment) * s.radius_over_polar;
    return out;
}

/// Elastic energy of a bond disc carrying these forces [J]:
///     ½ (F̄_n²/Ā + |M̄_b|²/Ī)/k̄_n + ½ (|F̄_s|²/Ā + M̄_t²/J̄)/k̄_s.
inline double bond_strain_energy(const ParallelBond& b, const BondSection& s,
                                 const BondStiffness& k) {
    // 1/I = (R/I)/R and 1/J = 1/(2I): one division for the four compliances.
    const double inv_inertia = s.radius_over_inertia * s.inv_area * kPi * s.radius;
    const double normal_part = b.normal_force * b.normal_force * s.inv_area +
                               norm2(b.bend_moment) * inv_inertia;
    const double shear_part = norm2(b.shear_force) * s.inv_area +
                              b.twist_moment * b.twist_moment * 0.5 * inv_inertia;
    return 0.5 * (normal_part / k.normal + shear_part / k.shear);
}

/// Breaks the bond: forces and moments vanish at once; never re-formed.
inline void release_bond(ParallelBond& b, BondState mode) {
    b.state = mode;
    b.normal_force = 0.0;
    b.shear_force = {};
    b.twist_moment = 0.0;
    b.bend_moment = {};
}

/// Force on j [N] and moment on j [N m] exerted by a bond with normal n.
inline Vec3 bond_force_on_j(const ParallelBond& b, const Vec3& n) {
    return b.shear_force - b.normal_force * n;
}
inline Vec3 bond_moment_on_j(const ParallelBond& b, const Vec3& n) {
    return b.bend_moment + b.twist_moment * n;
}

/// Time-step stiffness of an undamaged bond disc (PFC "Timestep Determination"):
/// translational max(k̄_n, k̄_s) Ā, rotational k̄_s Ā r² + k̄_n Ī + k̄_s J̄.
inline TimeStepStiffness disc_time_step_stiffness(const BondSection& s, const BondStiffness& k,
                                                  double r) {
    return {std::max(k.normal, k.shear) * s.area,
            k.shear * s.area * r * r + k.normal * s.inertia + k.shear * s.polar};
}

/// Adds a pair's time-step stiffness to its particle's `sum`: the contact's, and the acting
/// bond's if any (`bond` null: none). The bond acts beside the contact (the parallel bond: two
/// springs in parallel): both, contact first. The bond replaces the contact (the pair has one
/// spring or the other, never both: the bond while it acts, the contact once it is released):
/// the larger, so the step stays stable in either state.
inline void add_pair_time_step_stiffness(TimeStepStiffness& sum, const TimeStepStiffness& contact,
                                         const TimeStepStiffness* bond, bool bond_replaces_contact) {
    if (bond && bond_replaces_contact) {
        sum.translational += std::max(contact.translational, bond->translational);
        sum.rotational += std::max(contact.rotational, bond->rotational);
        return;
    }
    sum.translational += contact.translational;
    sum.rotational += contact.rotational;
    if (!bond) return;
    sum.translational += bond->translational;
    sum.rotational += bond->rotational;
}

}  // namespace gradem
