#pragma once
// The displacement-controlled axial loading shared by the virtual cube tests (compression
// between platens, direct tension between grips; docs/virtual_tests.md): both ends move apart or
// together at half the test speed each after a half-cosine velocity ramp; at every output
// interval a curve point records the test's strains and end stresses (load over the initial
// cross-section), breaks and kinetic energy; the run stops after the peak once the stress has
// fallen to a fraction of it or (optionally) once the strain has run a set multiple past the
// strain at the peak, at a maximum strain, or when the simulation diverges.
// What differs between the tests (how the ends are driven, how load and strain are read, the
// sign convention) is an AxialFrame; the curve is always "positive = the test's loading
// direction" (compression positive in compression, tension positive in tension).
#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "core/world.hpp"

namespace gradem::exp {

struct PlatenTestSpec {
    double strain_rate = 1.0;         ///< end speed (closing or opening) / initial height [1/s]
    double ramp_strain = 2.0e-4;      ///< the speed ramps up (half cosine) over the time this strain takes at full rate [-]
    double platen_friction = 0.5;     ///< mu_w [-]
    double stop_fraction = 0.7;       ///< stop once stress < this x peak, after the peak [-]
    /// Stop once the curve's strain (the gauge strain, which the curve is reduced on; the platen
    /// strain without gauges) exceeds this × its value at the peak so far, for a peak reached
    /// after the ramp (a curve that wanders on a plateau near its peak ends there instead of at
    /// stop_fraction); 0: no such stop [-]. 0 or > 1.
    double stop_strain_ratio = 0.0;
    double max_strain = 0.03;         ///< hard stop [-]
    std::int64_t record_interval = 50;  ///< steps between curve points
    [[nodiscard]] std::optional<std::string> invalid_reason() const;
};

struct CurvePoint {
    std::int64_t step = 0;
    double time = 0.0;            ///< [s]
    double platen_strain = 0.0;   ///< end displacement / initial height, loading direction positive [-]
    double gauge_strain = 0.0;    ///< extensometer strain, loading direction positive [-] (NaN without gauges)
    double lateral_strain = 0.0;  ///< lateral gauge strain, expansion positive [-] (NaN without gauges)
    double stress_top = 0.0;      ///< top end load / initial area [Pa], loading direction positive
    double stress_bottom = 0.0;   ///< bottom end load / initial area [Pa]
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
    std::string stop_reason;              ///< "post-peak", "post-peak strain", "max strain", "diverged: ..."
    bool diverged = false;
    std::int64_t steps = 0;
    double wall_seconds = 0.0;
};

using ProgressCallback = std::function<void(const CurvePoint&, double peak)>;
/// Called at every recorded point with the World (e.g. for ParaView snapshots).
using SnapshotCallback = std::function<void(const World&, const CurvePoint&)>;

/// How one test drives its ends and reads them.
struct AxialFrame {
    double height = 0.0;  ///< initial distance between the ends [m] (strain = displacement / height)
    double area = 0.0;    ///< initial cross-section [m^2] (stress = load / area)
    /// Sets the motion of both ends for the next step: each moves at `speed` [m/s] (>= 0) in the
    /// test's loading direction.
    std::function<void(World&, double speed)> drive;
    /// Fills platen_strain, gauge_strain, lateral_strain, stress_top and stress_bottom of a point.
    std::function<void(const World&, CurvePoint&)> measure;
};

/// Axis-aligned box around every particle (centre +- radius) [m].
struct ParticleBounds {
    Vec3 lo, hi;
};
ParticleBounds particle_bounds(const ParticleSet& particles);

/// Half-cosine ramp from 0 to 1 over the time `ramp_time` [s]: no velocity jump, no stress wave.
double ramp_factor(double time, double ramp_time);

/// Runs the loading on a prepared World (bonds installed, ends in place) until a stop rule fires.
PlatenTestResult run_axial_loading(World& world, const PlatenTestSpec& spec, const AxialFrame& frame,
                                   const ProgressCallback& progress = {}, const SnapshotCallback& snapshot = {});

}  // namespace gradem::exp
