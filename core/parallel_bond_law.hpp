#pragma once
// Parallel bond (Potyondy & Cundall 2004, §2.2; PFC linearpbond; docs/bond_laws.md). Elastic disc
// updated incrementally (update_bond_forces in bond_law.hpp); peak periphery stresses
//     σ̄ = F̄_n/Ā + β̄ |M̄_b| R̄/Ī,   τ̄ = |F̄_s|/Ā + β̄ |M̄_t| R̄/J̄.
// Failure: σ̄ >= σ̄_c -> tension; else τ̄ >= τ̄_c = c̄ - σ tan φ̄ with σ = min(F̄_n/Ā, σ̄_c)
// -> shear. A broken bond carries nothing and is never re-formed. No side state.
#include <array>
#include <cmath>

#include "core/bond_law.hpp"

namespace gradem {

/// τ̄_c = c̄ - σ tan φ̄, with σ capped at σ̄_c (PFC linearpbond).
inline double bond_shear_strength(const ParallelBond& b, double axial_stress, double tan_phi) {
    const double sigma = axial_stress < b.tensile_strength ? axial_stress : b.tensile_strength;
    return b.cohesion - sigma * tan_phi;
}

/// Failure mode for the current stresses: intact, broken_tension or broken_shear.
inline BondState bond_failure(const ParallelBond& b, const BondStress& s, double tan_phi) {
    const bool shear = s.shear >= bond_shear_strength(b, s.axial, tan_phi);
    return s.tensile >= b.tensile_strength ? BondState::broken_tension
                                           : (shear ? BondState::broken_shear : BondState::intact);
}

struct ParallelBondLaw {
    using Params = NoLawParams;  ///< its parameters are BondParams' shared ones
    static constexpr std::array<LawParameter<NoLawParams>, 0> kParameters{};
    /// Its curves are near-linear to the peak (D = 1.1-1.3) and drop soon after it: a
    /// compression test ends at 1.45 × 1.2 σ/E (parallel-bond calibrations of 2.5 mm cubes). In
    /// direct tension they peak at 0.62 σ̄_c/Ē; the rate aims at 0.5, and they end at 1.6 × that.
    static constexpr PlatenTestCost kPlatenTestCost{.compression_end_over_elastic = 1.74,
                                                    .compression_peak_over_elastic = 1.2,
                                                    .pre_peak_cost_factor = 1.0,
                                                    .post_peak_cost_factor = 1.0,
                                                    .tension_cost_factor = 1.0,
                                                    .tension_peak_over_bond_strain = 0.5,
                                                    .tension_end_over_expected = 1.6};

    struct Context {
        double tan_phi = 0.0;        ///< tan φ̄ [-]
        double moment_factor = 1.0;  ///< β̄ [-]
        bool track = true;           ///< compute energies
    };
    static Context context(const auto& p, bool track) {
        return {std::tan(p.friction_angle_deg * kPi / 180.0), p.moment_factor, track};
    }
    static std::size_t side_size(const auto&) { return 0; }
    static void install(const auto&, const BondInstall&, ParallelBond&, double*) {}

    /// The arithmetic of one step: advances b's forces and moments, and returns the failure
    /// mode, the peak stresses, the strain energy of the advanced state (0 if not tracked) and
    /// the force and moment on j. No bookkeeping, no branches: the fused pair pass runs it over
    /// many bonds at once (world_pairs.cpp); step() below is it plus the break bookkeeping.
    struct Advance {
        BondState failure;
        BondStress stress;
        double energy;       ///< [J]
        Vec3 force_j;        ///< [N]
        Vec3 moment_j;       ///< [N m]
    };
    [[gnu::always_inline]] static Advance advance(const Context& c, ParallelBond& b, const BondSection& sec,
                           const BondStiffness& stiff, const PairKinematics& kin) {
        update_bond_forces(b, sec, stiff, kin);
        const BondStress stress = bond_peak_stress(b, sec, c.moment_factor);
        return {bond_failure(b, stress, c.tan_phi), stress,
                c.track ? bond_strain_energy(b, sec, stiff) : 0.0, bond_force_on_j(b, kin.normal),
                bond_moment_on_j(b, kin.normal)};
    }

    static BondStepResult step(const Context& c, ParallelBond& b, double*, const BondSection& sec,
                               const BondStiffness& stiff, const PairKinematics& kin,
                               std::vector<BondBreak>& breaks) {
        const Advance a = advance(c, b, sec, stiff, kin);
        if (a.failure != BondState::intact) {
            breaks.push_back({a.failure, -1, {}, a.stress.tensile, a.stress.shear});
            release_bond(b, a.failure);
            return {.failure = a.failure, .force_j = {}, .moment_j = {}, .stored = 0.0, .released = a.energy};
        }
        return {.failure = BondState::intact, .force_j = a.force_j, .moment_j = a.moment_j, .stored = a.energy};
    }

    static TimeStepStiffness time_step_stiffness(const BondSection& s, const BondStiffness& k,
                                                 double r) {
        return disc_time_step_stiffness(s, k, r);
    }
};

}  // namespace gradem
