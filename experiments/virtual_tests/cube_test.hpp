#pragma once
// The virtual ASTM C109 cube test with the study's extensometer (docs/virtual_tests.md):
//   1. the packing is bonded (parallel bonds at every pair within the installation gap) with the
//      material parameters of this run - one packing serves every parameter set;
//   2. the lateral vessel walls are removed, the top and bottom ones become frictional platens,
//      and the bonded specimen is cycled to equilibrium (locked-in forces relax);
//   3. the platens close at the test strain rate after a half-cosine ramp; at every output
//      interval the curve records platen stresses, platen strain, gauge (extensometer) strain
//      from particle slabs in the central part of the cube, lateral strain, breaks and energy;
//   4. the test stops after the peak once the stress has fallen to a fraction of it, at a
//      maximum strain, or on divergence;
//   5. the macro response is computed by the lab's reduce_curve (ASTM C109 strength, C469 chord
//      modulus, Poisson's ratio) - the same code that reduces real load-frame exports.
// run_cube_test is a pure function of (packing, material, spec): it can run anywhere.
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "core/world_types.hpp"
#include "experiments/specimen/packing.hpp"
#include "experiments/virtual_tests/material_params.hpp"
#include "experiments/virtual_tests/platen_compression.hpp"
#include "lab_data/curve_reduction.hpp"

namespace gradem::exp {

/// Where the loading branch of the platen-imbalance check ends, as a fraction of the peak [-].
inline constexpr double kImbalanceBranchEnd = 0.95;

struct CubeTestSpec {
    PlatenTestSpec loading;                 ///< rate, ramp, stop rule, output interval
    double gauge_length_fraction = 0.5;     ///< extensometer gauge length / cube height [-]
    double slab_fraction = 0.1;             ///< thickness of a gauge slab / cube edge [-]
    double core_fraction = 0.6;             ///< gauge slabs use the central part of this width [-]
    double settle_ratio = 1.0e-4;           ///< unbalanced-force ratio before loading [-]
    std::int64_t max_settle_steps = 20000;  ///< settling budget (a warning if exceeded)
    double imbalance_warning = 0.02;        ///< warn if the loading branch's platen forces differ more [-]
    SnapshotCallback snapshot;              ///< optional: called at every recorded point (ParaView)
    [[nodiscard]] std::optional<std::string> invalid_reason() const;
};

struct CubeTestResult {
    PlatenTestResult test;               ///< curve (with gauge and lateral strain), stop reason
    lab::CurveReduction macro;           ///< ASTM reductions of the gauge-strain curve
    std::vector<BreakEvent> cracks;      ///< every bond break, in order
    std::size_t particles = 0, bonds = 0;
    /// Explicit paste: bonds installed per family pair, by the end particles' families
    /// (sand-sand, sand-paste (ITZ), paste-paste); all 0 for a parallel-bond specimen.
    std::size_t bonds_sand_sand = 0, bonds_itz = 0, bonds_paste_paste = 0;
    double strain_at_peak_platen = 0.0;  ///< platen strain at the peak [-]
    /// max |σ_top - σ_bottom| / σ on the loading branch, from 20 % of the peak to the first
    /// point at kImbalanceBranchEnd × the peak [-]
    double platen_imbalance = 0.0;
    double settle_ratio = 0.0;           ///< unbalanced-force ratio reached before loading [-]
    std::int64_t settle_steps = 0;
    double time_step = 0.0;              ///< [s]
    std::vector<std::string> warnings;   ///< dynamic test, settling not reached, ...
    [[nodiscard]] bool diverged() const { return test.diverged; }
};

/// Runs the whole test. `progress` (optional) sees every recorded curve point.
CubeTestResult run_cube_test(const Packing& packing, const MaterialParams& material,
                             const CubeTestSpec& spec, const ProgressCallback& progress = {});

/// Total particle mass / total particle volume [kg/m^3]: the sand density for a sand-only
/// packing; for explicit paste the paste particles' own (scaled) density weighs in by volume.
double mean_particle_density(const Packing& packing);

/// The strain rate [1/s] that keeps the time to the expected peak at least `transits` wave
/// transit times L/c, with c = sqrt(E*/rho) and rho = mean_particle_density(packing), the
/// specimen's actual particle masses (docs/virtual_tests.md "Loading rate").
double quasi_static_strain_rate(const Packing& packing, const MaterialParams& material,
                                double expected_peak_strain = 0.003, double transits = 200.0);

}  // namespace gradem::exp
