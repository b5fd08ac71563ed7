#pragma once
// Soft bond (PFC softbond semantics; docs/bond_laws.md "Soft bond"). The bond disc is the
// parallel bond's (R̄, Ā, Ī, J̄, k̄_n, k̄_s; bond_law.hpp); instead of breaking at its tensile
// strength it softens:
//   * effective (undamaged) F̄_n, F̄_s, M̄_t, M̄_b follow the parallel-bond update (docs/bond_laws.md);
//   * periphery opening, bending included:  δ = σ̄/k̄_n,  σ̄ = F̄_n/Ā + β̄ |M̄_b| R̄/Ī  [m];
//     δ_max = max over the history of δ;  δ_c = σ̄_c/k̄_n;
//   * softening branch (slope -ζ k̄_n):  σ_s(δ) = σ̄_c - ζ k̄_n (δ - δ_c)  for δ > δ_c;
//   * secant damage  ω = 1 - σ_s(δ_max)/(k̄_n δ_max)  (0 while δ_max <= δ_c), in [0, 1];
//   * transmitted:  F_n = (1-ω) F̄_n in tension, F̄_n in compression;  F_s = (1-ω) F̄_s,
//     M_t = (1-ω) M̄_t, M_b = (1-ω) M̄_b: unloading and reloading follow the damaged secant;
//   * tension break when σ_s(δ_max) <= γ σ̄_c  <=>  δ_max >= δ_c + (1-γ) σ̄_c/(ζ k̄_n);
//   * shear break when (1-ω) τ̄ >= (1-ω) c̄ - σ tan φ̄, τ̄ = |F̄_s|/Ā + β̄ |M̄_t| R̄/J̄, σ = F_n/Ā
//     capped at σ̄_c (effective-stress criterion: with ω = 0 it is the parallel bond's).
// Energy: stored = (1-ω) x (undamaged energy of the damageable parts: all but a compressive F̄_n)
// + ½ F̄_n²/(k̄_n Ā) if F̄_n < 0; a step that raises ω by Δω dissipates Δω x ½ k u_old u_new
// summed over the damaged parts (ΔD = ½ k δ² Δω, in the form that matches the
// leap-frog's trapezoidal work) -> EnergyLedger::bond_damage; the energy still stored at the
// break is released -> EnergyLedger::bond_break. Pure tension to break: the total is
//     G Ā,  G = σ̄_c²/(2 k̄_n) [1 + (1-γ²)/ζ]  [J/m²].
// Contact: by default (BondParams::replaces_contact) an intact soft bond REPLACES the pair's
// linear contact, as PFC's softbond has one spring set: the bond alone carries compression
// (undamaged, k̄_n Ā), and the linear contact acts only once the bond has broken
// (World::compute_contacts). replaces_contact = false keeps the contact in parallel (the
// parallel bond's arrangement). Installed at zero force (locked-in contact forces are released).
// Simplifications: damage is isotropic (one ω on all four components); no shear
// softening; compression never damages. Time step: the undamaged stiffness.
#include <array>
#include <cmath>
#include <span>

#include "core/law_parameters.hpp"
#include "core/parallel_bond_law.hpp"

namespace gradem {

/// Soft bond shape parameters: at σ̄_c the bond softens instead of breaking.
struct SoftBondParams {
    double softening_factor = 0.3;  ///< ζ: softening slope is -ζ k̄_n [Pa/m], > 0 [-]
    double cut_fraction = 0.2;      ///< γ: breaks once the softened stress is <= γ σ̄_c, in [0, 1) [-]
};

/// Decoded side state of one soft bond.
struct SoftBondState {
    ParallelBond effective;  ///< the undamaged forces F̄_n, F̄_s, M̄_t, M̄_b (other fields unset)
    double max_opening = 0.0;  ///< δ_max [m]
    double damage = 0.0;       ///< ω [-]
};

inline constexpr std::size_t kSoftBondSideSize = 10;

inline SoftBondState soft_bond_state(std::span<const double> s) {
    SoftBondState out;
    out.effective.normal_force = s[0];
    out.effective.shear_force = {s[1], s[2], s[3]};
    out.effective.twist_moment = s[4];
    out.effective.bend_moment = {s[5], s[6], s[7]};
    out.max_opening = s[8];
    out.damage = s[9];
    return out;
}

inline void store_soft_bond_state(const SoftBondState& st, double* s) {
    const ParallelBond& e = st.effective;
    s[0] = e.normal_force;
    s[1] = e.shear_force.x, s[2] = e.shear_force.y, s[3] = e.shear_force.z;
    s[4] = e.twist_moment;
    s[5] = e.bend_moment.x, s[6] = e.bend_moment.y, s[7] = e.bend_moment.z;
    s[8] = st.max_opening;
    s[9] = st.damage;
}

/// ω(δ_max) of the softening law; 1 once the branch reaches zero stress.
inline double soft_bond_damage(double max_opening, double strength, double kn, double softening) {
    const double onset = strength / kn;  // δ_c [m]
    if (!(max_opening > onset)) return 0.0;
    const double stress = strength - softening * kn * (max_opening - onset);  // σ_s [Pa]
    const double omega = 1.0 - stress / (kn * max_opening);
    return omega < 1.0 ? omega : 1.0;
}

/// ½ F̄_old . F̄_new / stiffness over the damageable parts [J]: a step that raises ω by Δω
/// dissipates Δω times this. With the leap-frog's trapezoidal work ½ (F_old + F_new) . ΔU this
/// closes the energy balance exactly for a linear path (½ k u_old u_new Δω per component).
inline double soft_bond_damage_energy(const ParallelBond& before, const ParallelBond& after,
                                      const BondSection& s, const BondStiffness& k) {
    const double inv_inertia = s.radius_over_inertia * s.inv_area * kPi * s.radius;
    const double axial = after.normal_force > 0.0 ? before.normal_force * after.normal_force : 0.0;
    const double normal_part = axial * s.inv_area + dot(before.bend_moment, after.bend_moment) * inv_inertia;
    const double shear_part = dot(before.shear_force, after.shear_force) * s.inv_area +
                              before.twist_moment * after.twist_moment * 0.5 * inv_inertia;
    return 0.5 * (normal_part / k.normal + shear_part / k.shear);
}

/// Energy of the damageable parts (all but compressive F̄_n) and of compressive F̄_n [J].
struct SoftBondEnergy {
    double damageable = 0.0, compressive = 0.0;
};
inline SoftBondEnergy soft_bond_energy(const ParallelBond& eff, const BondSection& s,
                                       const BondStiffness& k) {
    const double total = bond_strain_energy(eff, s, k);
    const double axial = 0.5 * eff.normal_force * eff.normal_force * s.inv_area / k.normal;
    if (eff.normal_force < 0.0) return {total - axial, axial};
    return {total, 0.0};
}

struct SoftBondLaw {
    using Params = SoftBondParams;
    // Designated initializers leave the other members at their defaults on purpose.
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wmissing-field-initializers"
    static constexpr std::array<LawParameter<SoftBondParams>, 2> kParameters = {{
        {.key = "softening_factor",
         .description = "zeta, softening slope / bond normal stiffness (soft_bond)",
         .field = law_field<&SoftBondParams::softening_factor>, .core_field = "SoftBondParams::softening_factor",
         .range = ranges::positive, .calibration = Calibration::free, .lower = 0.05, .upper = 1.0, .log_scale = true},
        {.key = "cut_fraction",
         .description = "gamma, the bond breaks once its softened stress <= gamma x sigma-bar_c (soft_bond)",
         .field = law_field<&SoftBondParams::cut_fraction>, .core_field = "SoftBondParams::cut_fraction",
         .range = ranges::unit_open_right, .calibration = Calibration::free, .lower = 0.0, .upper = 0.5},
    }};
#pragma GCC diagnostic pop

    /// The analytic stand-in's extra shape index for a sand of ductility coefficient h:
    /// h ln(1 + (1 − γ²)/ζ), ln of the bond's fracture energy over its elastic energy at σ̄_c (above).
    static double analytic_ductility(const SoftBondParams& p, double h) {
        return h * std::log(1.0 + (1.0 - p.cut_fraction * p.cut_fraction) / p.softening_factor);
    }

    struct Context {
        double tan_phi = 0.0, moment_factor = 1.0;
        double softening = 0.3;  ///< ζ
        double cut = 0.2;        ///< γ
        bool track = true;
    };
    static Context context(const auto& p, bool track) {
        const SoftBondParams& own = law_params<SoftBondLaw>(p);
        return {std::tan(p.friction_angle_deg * kPi / 180.0), p.moment_factor, own.softening_factor,
                own.cut_fraction, track};
    }
    static std::size_t side_size(const auto&) { return kSoftBondSideSize; }
    static void install(const auto&, const BondInstall&, ParallelBond&, double* side) {
        store_soft_bond_state({}, side);
    }

    static BondStepResult step(const Context& c, ParallelBond& b, double* side,
                               const BondSection& sec, const BondStiffness& stiff,
                               const PairKinematics& kin, std::vector<BondBreak>& breaks) {
        BondStepResult r;
        SoftBondState st = soft_bond_state({side, kSoftBondSideSize});
        const ParallelBond before = st.effective;
        update_bond_forces(st.effective, sec, stiff, kin);
        const BondStress eff = bond_peak_stress(st.effective, sec, c.moment_factor);
        const double opening = eff.tensile / stiff.normal;  // δ [m]
        if (opening > st.max_opening) st.max_opening = opening;
        const double omega_old = st.damage;
        st.damage = soft_bond_damage(st.max_opening, b.tensile_strength, stiff.normal, c.softening);
        const double intact = 1.0 - st.damage;
        const SoftBondEnergy energy = soft_bond_energy(st.effective, sec, stiff);
        if (st.damage != omega_old)
            r.damage = (st.damage - omega_old) *
                       soft_bond_damage_energy(before, st.effective, sec, stiff);

        // Transmitted (damaged) forces into the bond record.
        const ParallelBond& e = st.effective;
        b.normal_force = e.normal_force > 0.0 ? intact * e.normal_force : e.normal_force;
        b.shear_force = intact * e.shear_force;
        b.twist_moment = intact * e.twist_moment;
        b.bend_moment = intact * e.bend_moment;
        store_soft_bond_state(st, side);

        const double stored = intact * energy.damageable + energy.compressive;
        const double softened =  // σ_s(δ_max) [Pa]; the break test of the cut-off
            b.tensile_strength - c.softening * stiff.normal * (st.max_opening - b.tensile_strength / stiff.normal);
        const double axial = b.normal_force * sec.inv_area;
        const double sigma = axial < b.tensile_strength ? axial : b.tensile_strength;
        const double shear = intact * eff.shear;
        BondState failure = BondState::intact;
        if (st.damage > 0.0 && softened <= c.cut * b.tensile_strength)
            failure = BondState::broken_tension;
        else if (shear >= intact * b.cohesion - sigma * c.tan_phi)
            failure = BondState::broken_shear;
        if (failure != BondState::intact) {
            if (c.track) r.released = stored;
            breaks.push_back({failure, -1, {}, intact * eff.tensile, shear});
            release_bond(b, failure);
            r.failure = failure;
            return r;
        }
        if (c.track) r.stored = stored;
        r.force_j = bond_force_on_j(b, kin.normal);
        r.moment_j = bond_moment_on_j(b, kin.normal);
        return r;
    }

    static TimeStepStiffness time_step_stiffness(const BondSection& s, const BondStiffness& k,
                                                 double r) {
        return disc_time_step_stiffness(s, k, r);
    }
};

}  // namespace gradem
