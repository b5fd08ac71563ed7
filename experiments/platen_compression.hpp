#pragma once
// Unconfined compression between two rigid platens (the loading frame of ASTM C109): the
// bottom platen moves up and the top platen down, each at half the closing speed, after a
// half-cosine velocity ramp; lateral faces are free. Records the platen stresses (load over the
// initial cross-section) against platen strain and stops after the peak once the stress has
// fallen to a fraction of it, at a maximum strain, or when the run diverges.
#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "core/world.hpp"
#include "experiments/gauges.hpp"

namespace gradem::exp {

struct PlatenTestSpec {
    double strain_rate = 1.0;         ///< platen closing speed / initial height [1/s]
    double ramp_strain = 2.0e-4;      ///< the speed ramps up (half cosine) over the time this strain takes at full rate [-]
    double platen_friction = 0.5;     ///< mu_w [-]
    double stop_fraction = 0.7;       ///< stop once stress < this x peak, after the peak [-]
    double max_strain = 0.03;         ///< hard stop [-]
    std::int64_t record_interval = 50;  ///< steps between curve points
    [[nodiscard]] std::optional<std::string> invalid_reason() const;
};

struct CurvePoint {
    std::int64_t step = 0;
    double time = 0.0;            ///< [s]
    double platen_strain = 0.0;   ///< closing / initial height, compression positive [-]
    double gauge_strain = 0.0;    ///< extensometer strain, compression positive [-] (NaN without gauges)
    double lateral_strain = 0.0;  ///< lateral gauge strain, expansion positive [-] (NaN without gauges)
    double stress_top = 0.0;      ///< top platen load / initial area [Pa], compression positive
    double stress_bottom = 0.0;   ///< bottom platen load / initial area [Pa]
    double stress = 0.0;          ///< mean of the two [Pa]
    std::int64_t broken_tension = 0, broken_shear = 0;
    double kinetic_energy = 0.0;  ///< [J]
};

struct PlatenTestResult {
    std::vector<CurvePoint> curve;
    double area = 0.0, height = 0.0;      ///< initial cross-section [m^2] and height [m]
    double peak_stress = 0.0;             ///< [Pa]
    double strain_at_peak = 0.0;          ///< platen strain at the peak [-]
    double secant_modulus_40 = 0.0;       ///< stress / strain at 40 % of the peak [Pa]
    std::string stop_reason;              ///< "post-peak", "max strain", "diverged: ..."
    bool diverged = false;
    std::int64_t steps = 0;
    double wall_seconds = 0.0;
};

/// Adds the two platens (wall 0 bottom, wall 1 top) touching the specimen's top and bottom faces. The World must not have walls yet.
void add_platens(World& world, double friction);

using ProgressCallback = std::function<void(const CurvePoint&, double peak)>;
/// Called at every recorded point with the World (e.g. for ParaView snapshots).
using SnapshotCallback = std::function<void(const World&, const CurvePoint&)>;

/// Runs the test on a World with bonds installed. `progress` (optional) is called at every
/// recorded point; `gauges` (optional) add the extensometer strains to the curve. The peak and
/// strain at peak here are the platen-based ones.
PlatenTestResult run_platen_compression(World& world, const PlatenTestSpec& spec,
                                        const ProgressCallback& progress = {},
                                        const Gauges* gauges = nullptr,
                                        const SnapshotCallback& snapshot = {});

}  // namespace gradem::exp
