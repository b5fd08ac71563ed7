#pragma once
// Dense random packing by soft-sphere enthalpy minimisation (positions only, no dynamics):
// grains are dropped at random in the cubic vessel [0, L]^3 (overlapping), then the enthalpy
//     H(x, L) = sum_contacts 1/2 k_n delta^2 + p L_x L_y L_z
// is minimised over the grain centres x and the three box edges L_a with FIRE (Bitzek et al.
// 2006, PRL 97:170201; the FIRE 2.0 variant of Guenole et al. 2020, CMS 175:109584). The
// contacts are exactly the World's frictionless linear law (core/contact_law.hpp): grain-grain
// k_n = pi min(R)^2 E* / (R_i + R_j), grain-wall k_n = pi R E*, delta the overlap, the six walls
// the planes x_a = 0 and x_a = L_a. The box edges move affinely (every centre is scaled with
// its edge), so compaction is collective, not a wave from the walls.
// At a minimum every grain is in force balance and dH/dL_a = 0 means the force on each wall
// over its area equals p (the virial identity: L_a dH/dL_a = L_a F_wall,a - p V when every
// grain is balanced), so the "servo" to the locked-in stress is part of the minimisation.
// Pressure is lowered in decades from 1e-3 E* to the locked-in stress (a compress-then-
// decompress protocol: the packing jams once, at a high pressure where FIRE converges fast, and
// is unloaded to the target, which keeps its random isotropic fabric).
// Fictitious masses m_i = pi R_i E* (each grain's wall stiffness) make every grain's natural
// frequency about one (the "unit-mass scaling" of the reference): small grains do not set the
// step. Box edges get the mass sum_i m_i (2 R_i)^2.
// Determinism: forces are gathered per grain over a neighbour list in a fixed order, sums go
// through fixed blocks in block order (core/parallel.hpp): bitwise identical for any thread count.
#include <cstdint>
#include <memory>
#include <vector>

#include "core/neighbor_search.hpp"
#include "core/vec3.hpp"

namespace gradem::exp {

/// Contact state and equilibrium measures of the packing (as the World defines them).
struct PackingBalance {
    double unbalanced_ratio = 0.0;  ///< mean |resultant| per grain / mean contact force [-]
    Vec3 wall_stress_lo, wall_stress_hi;  ///< normal stress on the x-, y-, z- and x+, y+, z+ walls [Pa]
    double max_overlap = 0.0;       ///< largest grain-grain overlap / smaller diameter [-]
    double mean_overlap = 0.0;      ///< mean grain-grain overlap / smaller diameter over contacts [-]
    std::int64_t contacts = 0;      ///< touching grain pairs and grain-wall contacts
};

class DensePacker {
public:
    /// Drops spheres of the given diameters [m] at random (seed) into [0, edge]^3 [m], with
    /// contact modulus E* `modulus` [Pa].
    DensePacker(const std::vector<double>& diameters, double edge, double modulus, std::uint64_t seed);

    /// Minimises at isotropic stress `pressure` [Pa] until the unbalanced-force ratio is
    /// <= ratio_tol and every wall stress is within stress_tol x pressure, or `budget`
    /// iterations are spent. Returns whether it converged.
    bool relax(double pressure, double ratio_tol, double stress_tol, std::int64_t budget);
    /// Multiplies the radius of grain i by `factor` (floater enlargement).
    void grow(std::size_t i, double factor);

    [[nodiscard]] const std::vector<Vec3>& positions() const { return x_; }
    [[nodiscard]] const std::vector<double>& radii() const { return r_; }
    [[nodiscard]] Vec3 box() const { return box_; }  ///< edges L_x, L_y, L_z [m]; lower corner at 0
    [[nodiscard]] std::int64_t iterations() const { return iterations_; }
    [[nodiscard]] std::int64_t rebuilds() const { return rebuilds_; }
    [[nodiscard]] double solid_fraction() const;
    /// Grain-grain and grain-wall contacts (overlap > 0) per grain.
    [[nodiscard]] std::vector<std::int32_t> contact_counts();
    /// Measures at the current positions (recomputes the forces).
    [[nodiscard]] PackingBalance balance();

private:
    struct Sums;
    void rebuild_neighbors();
    Sums compute_forces(double pressure);
    void move(double dt, double alpha, double v_norm, double f_norm);
    [[nodiscard]] PackingBalance balance_of(const Sums& s) const;

    double modulus_;
    std::vector<Vec3> x_, v_, f_, x_at_rebuild_;
    std::vector<double> r_, m_;
    Vec3 box_, box_rate_, box_force_, box_mass_;  ///< edges [m], strain rates, dH/d ln L, masses
    std::vector<std::int32_t> nbr_start_, nbr_;    ///< CSR neighbour lists (both directions)
    double skin_ = 0.0;
    bool rebuild_needed_ = true;
    std::int64_t iterations_ = 0, rebuilds_ = 0;
    double pressure_ = 0.0;  ///< of the latest relax() [Pa]
    std::unique_ptr<NeighborSearch> search_;
    std::vector<ParticlePair> pairs_;
};

}  // namespace gradem::exp
