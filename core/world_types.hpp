#pragma once
// Value types the World reports: run status, energy ledger, crack events, per-phase timings.
#include <cstdint>
#include <string>

#include "core/bond_law.hpp"
#include "core/vec3.hpp"

namespace gradem {

enum class RunStatus : std::uint8_t { running, diverged };

/// Energy bookkeeping (PFC-style). State terms are values at the current step; the others are
/// cumulative since the first step. Balance: kinetic + strain + dissipated - boundary work is
/// constant (= its value at the first step) up to the time-discretisation error.
struct EnergyLedger {
    double kinetic = 0.0;        ///< ½ m v(t-½).v(t+½) + ½ I w.w: the leap-frog invariant [J]
    double strain_contact = 0.0; ///< linear springs, grain-grain and grain-wall [J]
    double strain_bond = 0.0;    ///< bonds [J]
    double damping = 0.0;        ///< dissipated by local damping, cumulative, >= 0 [J]
    double friction = 0.0;       ///< dissipated by Coulomb slip, cumulative, >= 0 [J]
    double bond_break = 0.0;     ///< strain energy released by broken bonds, cumulative [J]
    double bond_damage = 0.0;    ///< dissipated by bond softening (soft bond), cumulative [J]
    double boundary_work = 0.0;  ///< work done on the particles by walls and prescribed particles [J]
    double reference = 0.0;      ///< total at the first step after the latest set-up change

    [[nodiscard]] double total() const {
        return kinetic + strain_contact + strain_bond + damping + friction + bond_break +
               bond_damage - boundary_work;
    }
    /// total() - reference: zero for an exact integrator.
    [[nodiscard]] double balance_error() const { return total() - reference; }
};

/// A bond break: one crack (docs/model.md "Crack events"). Flat joints log one event per element break.
struct BreakEvent {
    std::int64_t step = 0;
    double time = 0.0;          ///< [s]
    std::int32_t bond = -1, i = -1, j = -1;
    BondState mode = BondState::broken_tension;
    Vec3 position;              ///< contact point [m]
    Vec3 normal;                ///< unit normal i -> j
    double bond_radius = 0.0;   ///< R̄ [m]
    double tensile_stress = 0.0;  ///< σ̄ at break [Pa]
    double shear_stress = 0.0;    ///< τ̄ at break [Pa]
    std::int32_t element = -1;    ///< flat-joint element that broke, -1: the whole bond
};

/// Wall-clock seconds spent per phase, cumulative. With the parallel bond, contacts and bonds
/// are one pass (core/world_pairs.cpp) timed under `bonds`; `contacts` then stays 0.
struct StepProfile {
    double neighbors = 0.0, contacts = 0.0, bonds = 0.0, walls = 0.0, integrate = 0.0;
    std::int64_t rebuilds = 0;
    /// Bond-steps a law's own pass (Law::compute_all) took in its SIMD lanes and through its
    /// scalar kernel; 0 for laws without one.
    std::int64_t bond_lane_steps = 0, bond_scalar_steps = 0;
    /// Pair-steps whose force and moments the parallel bond's or the flat joint's pass added to
    /// the particles itself instead of writing the pair's slot for the gather
    /// (SimParams::forces_in_pass).
    std::int64_t pair_steps_into_particles = 0;
    [[nodiscard]] double total() const { return neighbors + contacts + bonds + walls + integrate; }
};

}  // namespace gradem
