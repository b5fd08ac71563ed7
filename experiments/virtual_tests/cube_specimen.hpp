#pragma once
// The steps the virtual cube tests share (compression, cube_test.hpp; direct tension,
// tension_test.hpp), so both test the same specimen and reduce their curves alike:
//   - the bonded specimen: the packing bonded with the run's material (parallel bonds at every
//     pair within the installation gap), between two fixed frictional platens (wall 0 bottom
//     at box_lo.z, wall 1 top at box_hi.z), lateral faces free, cycled until the
//     unbalanced-force ratio is small (the locked-in forces relax);
//   - the extensometer gauges picked on the settled state;
//   - the reduction of the finished curve by the lab's reduce_curve and the platen-balance
//     (quasi-static) warning.
#include "experiments/virtual_tests/cube_test.hpp"
#include "experiments/virtual_tests/gauges.hpp"

namespace gradem::exp {

/// The packing bonded with `material` between the two fixed frictional platens, not yet settled
/// (inputs not validated: settled_cube_specimen does that).
World bonded_cube_specimen(const Packing& packing, const MaterialParams& material);

/// Validates the inputs, builds and settles the specimen. Fills r.particles, r.bonds,
/// r.settle_ratio, r.settle_steps and a warning when settling stopped short.
World settled_cube_specimen(const Packing& packing, const MaterialParams& material, const CubeTestSpec& spec,
                            CubeTestResult& r);

/// The spec's extensometer gauges on the World's current state.
Gauges cube_gauges(const World& world, const Packing& packing, const CubeTestSpec& spec);

/// After the loading: strain at peak, the reduction of the gauge-strain curve and the platen
/// imbalance with its warning.
void reduce_cube_result(CubeTestResult& r, const CubeTestSpec& spec, const lab::ReductionOptions& options = {});

/// The recorded curve in the lab's form (gauge strain, stress, platen strain, lateral strain, time).
lab::StressStrainCurve to_stress_strain_curve(const PlatenTestResult& test);

}  // namespace gradem::exp
