#pragma once
// Unconfined compression between two rigid platens (the loading frame of ASTM C109): the
// bottom platen moves up and the top platen down, each at half the closing speed, after a
// half-cosine velocity ramp; lateral faces are free. Records the platen stresses (load over the
// initial cross-section) against platen strain and stops after the peak once the stress has
// fallen to a fraction of it, at a maximum strain, or when the run diverges. The loading loop,
// the curve and the stop rules are the shared ones of axial_loading.hpp, compression positive.
#include "core/world.hpp"
#include "experiments/virtual_tests/axial_loading.hpp"
#include "experiments/virtual_tests/gauges.hpp"

namespace gradem::exp {

/// Adds the two platens (wall 0 bottom, wall 1 top) touching the specimen's top and bottom faces. The World must not have walls yet.
void add_platens(World& world, double friction);

/// Runs the test on a World with bonds installed. `progress` (optional) is called at every
/// recorded point; `gauges` (optional) add the extensometer strains to the curve. The peak and
/// strain at peak here are the platen-based ones.
PlatenTestResult run_platen_compression(World& world, const PlatenTestSpec& spec,
                                        const ProgressCallback& progress = {},
                                        const Gauges* gauges = nullptr,
                                        const SnapshotCallback& snapshot = {});

}  // namespace gradem::exp
