#pragma once
// An unbonded packing (docs/genesis.md): grain centres and radii in the vessel, and the report of
// how genesis made it. Bonds and material are applied by the virtual tests, so one packing
// serves every parameter set; packing_cache.hpp stores it on disk.
#include <cstdint>
#include <vector>

#include "core/vec3.hpp"
#include "experiments/specimen/grain_sampler.hpp"

namespace gradem::exp {

/// An unbonded packing and how it was made.
struct Packing {
    std::vector<Vec3> position;        ///< grain centres [m]
    std::vector<double> radius;        ///< [m]
    double density = 0.0;              ///< [kg/m^3]
    Vec3 box_lo, box_hi;               ///< vessel walls at the end of genesis [m]
    // --- report ---
    GrainSample grains;                ///< sampling report (diameters cleared to save space)
    std::int64_t steps = 0;            ///< DEM steps of genesis (the check, step 5)
    std::int64_t relax_iterations = 0; ///< minimisation iterations (steps 2 and 3)
    double porosity = 0.0;             ///< 1 - grain volume / box volume [-]
    double edge_over_d50 = 0.0;        ///< L / d50 [-]
    double mean_coordination = 0.0;    ///< contacts per grain (walls included) [-]
    double floaters_before = 0.0;      ///< fraction of grains with < min_contacts at the jamming pressure, before passes
    double floaters_after = 0.0;       ///< at the end, at the locked-in stress [-]
    Vec3 wall_stress;                  ///< final normal stress on the x, y, z walls [Pa]
    double unbalanced_ratio = 0.0;     ///< final mean unbalanced-force ratio [-]
    double radius_growth = 1.0;        ///< multiplier applied to every radius (1: the box moves instead) [-]
    bool converged = false;            ///< stress and equilibrium tolerances met (by the World)
    double seconds = 0.0;              ///< wall-clock time of genesis [s]
    // --- explicit paste (experiments/paste/paste_fill.hpp); empty / 0 for a sand-only packing ---
    std::vector<std::uint8_t> family;  ///< per grain: 0 sand, 1 paste; empty: all sand
    double paste_density = 0.0;        ///< density of paste particles [kg/m^3]
    [[nodiscard]] double edge() const { return box_hi.z - box_lo.z; }
};

}  // namespace gradem::exp
