#pragma once
// Parameter structs of the bonded-particle model. Plain structs with documented defaults (SI
// units) and one validator each, which names the field, its value and the rule it breaks
// (Ceres' Options::IsValid pattern). Entry points call invalid_reason() once and refuse to run.
#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <tuple>
#include <vector>

#include "core/bond_models.hpp"

namespace gradem {

/// Linear contact ("linear" part of PFC linearpbond). Deformability form (PFC 5+):
/// ball-ball k_n = A E*/L with A = pi min(R)^2, L = R_A + R_B; ball-wall k_n = pi R E*;
/// k_s = k_n / kappa. No tension; Coulomb slip with coefficient `friction`.
struct ContactParams {
    double effective_modulus = 1.0e9;  ///< E* [Pa]
    double stiffness_ratio = 1.5;      ///< kappa* = k_n / k_s [-]
    double friction = 0.5;             ///< mu, grain-grain Coulomb coefficient [-]
    [[nodiscard]] std::optional<std::string> invalid_reason() const;
};

/// The BondModel's name (the names configs and reports use: core/bond_models.hpp's rows);
/// to_string(model) of common/named_enum.hpp.
const char* bond_model_name(BondModel model);
/// The model of that name, or nullopt for an unknown name (parse_enum<BondModel>).
std::optional<BondModel> parse_bond_model(const std::string& name);

/// Bond parameters (Potyondy & Cundall 2004; PFC linearpbond) shared by every bond model. Bond stiffness per unit area
/// k̄_n = Ē*/(R_A + R_B), k̄_s = k̄_n / κ̄. Strengths are drawn per bond from normal
/// distributions truncated to positive values (mean, std), seeded by `seed` and the pair ids.
struct BondParams {
    double effective_modulus = 1.0e9;       ///< Ē* [Pa]
    double stiffness_ratio = 1.5;           ///< κ̄ = k̄_n / k̄_s [-]
    double radius_multiplier = 1.0;         ///< λ̄, R̄ = λ̄ min(R_A, R_B), in (0, 1] [-]
    double moment_factor = 1.0;             ///< β̄ (PFC pb_mcf), in [0, 1] [-]
    double tensile_strength_mean = 10.0e6;  ///< σ̄_c mean [Pa]
    double tensile_strength_std = 0.0;      ///< σ̄_c standard deviation [Pa]
    double cohesion_mean = 10.0e6;          ///< c̄ mean [Pa]
    double cohesion_std = 0.0;              ///< c̄ standard deviation [Pa]
    double friction_angle_deg = 0.0;        ///< φ̄ [degrees], in [0, 90)
    std::uint64_t seed = 1;                 ///< strength draws: same seed + pair = same strength
    BondModel model = BondModel::parallel_bond;  ///< which law the bonds follow
    /// Every law's own parameters (core/bond_models.hpp); the model's are used.
    BondLawParams laws;
    /// Every law but the parallel bond: while the bond is intact it REPLACES the pair's linear
    /// contact (PFC softbond/flatjoint: one spring set, the bond carries compression too; the
    /// linear contact acts once the bond has broken). false: bond and contact act in parallel
    /// (the parallel bond's arrangement, which the parallel bond always keeps).
    bool replaces_contact = true;
    /// Whether this law's bonds replace their pair's contact while they act (the contact pass
    /// skips the pair, the time step counts one spring): replaces_contact, never for the
    /// parallel bond.
    [[nodiscard]] bool bond_replaces_contact() const { return model != BondModel::parallel_bond && replaces_contact; }
    /// A law's own parameters: params.law<Law>() (Law::Params, the law header's struct).
    template <class Law>
    typename Law::Params& law() {
        return std::get<bond_law_index<Law>>(laws);
    }
    template <class Law>
    const typename Law::Params& law() const {
        return std::get<bond_law_index<Law>>(laws);
    }
    /// The shared fields' rules, then every law's rows (ranges) and its invalid_reason hook.
    [[nodiscard]] std::optional<std::string> invalid_reason() const;
};

/// Rigid planar wall (platen) contact: linear, k_n = pi R E*_w, k_s = k_n / kappa_w.
struct WallContactParams {
    double effective_modulus = 1.0e9;  ///< E*_w [Pa]
    double stiffness_ratio = 1.5;      ///< kappa_w [-]
    double friction = 0.0;             ///< mu_w, platen friction [-]
    [[nodiscard]] std::optional<std::string> invalid_reason() const;
};

/// Integration and bookkeeping settings of a World.
struct SimParams {
    double local_damping = 0.7;      ///< Cundall local non-viscous damping alpha, in [0, 1) [-]
    double time_step = 0.0;          ///< [s]; 0 = automatic (safety * critical estimate)
    double time_step_safety = 0.8;   ///< fraction of the critical time step, in (0, 1] [-]
    double skin_fraction = 0.15;     ///< Verlet skin as a fraction of the minimum radius [-]
    bool track_energy = true;        ///< energy bookkeeping every step (small cost)
    double divergence_energy_factor = 10.0;  ///< diverged if E_kin > factor * energy supplied
    double divergence_energy_floor = 0.0;    ///< ... and E_kin > this [J] (round-off motion of a stress-free specimen is not a blow-up)
    /// The pair pass prefetches its output slots only when its arrays outgrow this many bytes (a
    /// last-level cache: the development machine's L3, 32 MiB) and it writes every slot
    /// (forces_in_pass off). Speed only: the results are bitwise the same either way
    /// (tests/core/test_pair_pass.cpp).
    std::size_t stream_prefetch_above_bytes = std::size_t{32} << 20;
    /// A law's own vectorised pass over its bonds (Law::compute_all, core/bond_pass.hpp: its
    /// bonds across SIMD lanes), bitwise the same results as its scalar kernel: off only to
    /// compare the two.
    bool vectorised_bond_passes = true;
    /// The parallel bond's pass adds each pair's force and moments to those of its particles
    /// whose pairs all lie in the same thread's share of the pass, as it goes, in pair order
    /// (their gather's order, so the same bits), instead of writing the pair's output slot for
    /// the gather to read back: 72 bytes per pair and step neither written nor read
    /// (bench/README.md). The flat joint's pass does the same for the particles whose pairs are
    /// all acting joints, in bond order at the end of each block of joints (its lane sets run
    /// out of order). Only the pairs of particles whose pairs span two shares (or, for the flat
    /// joint, include a contact) keep their slots. The slots are rebuilt from the state when
    /// something reads them (World::pair_outputs). Off only to compare the two.
    bool forces_in_pass = true;
    /// How the threads share a pass with forces into particles (forces_in_pass: the parallel
    /// bond's over its pairs, the flat joint's over its bonds) and the particle phases:
    /// empty, in proportion to each thread's measured speed (World::balance_pass_shares: the
    /// cores of one machine can differ by a fifth); else fixed relative shares, one per thread
    /// (> 0; used by a team of as many threads, else ignored). Speed only: the results are
    /// bitwise the same for any shares (a block cut by two shares is summed as one:
    /// core/parallel.hpp BlockPart).
    std::vector<double> thread_share_weights;
    [[nodiscard]] std::optional<std::string> invalid_reason() const;
};

/// Throws std::invalid_argument with the reason if `reason` holds one.
void require_valid(const std::optional<std::string>& reason);

}  // namespace gradem
