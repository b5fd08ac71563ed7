#include "experiments/virtual_tests/axial_loading.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <sstream>
#include <stdexcept>

namespace gradem::exp {

std::optional<std::string> PlatenTestSpec::invalid_reason() const {
    std::ostringstream out;
    if (!(strain_rate > 0.0)) out << "PlatenTestSpec::strain_rate = " << strain_rate << " violates > 0";
    else if (!(ramp_strain >= 0.0)) out << "PlatenTestSpec::ramp_strain = " << ramp_strain << " violates >= 0";
    else if (!(platen_friction >= 0.0)) out << "PlatenTestSpec::platen_friction = " << platen_friction << " violates >= 0";
    else if (!(stop_fraction > 0.0 && stop_fraction < 1.0)) out << "PlatenTestSpec::stop_fraction = " << stop_fraction << " violates in (0, 1)";
    else if (!(stop_strain_ratio == 0.0 || (stop_strain_ratio > 1.0 && std::isfinite(stop_strain_ratio))))
        out << "PlatenTestSpec::stop_strain_ratio = " << stop_strain_ratio << " violates 0 (off) or > 1";
    else if (!(max_strain > 0.0 && max_strain < 0.5)) out << "PlatenTestSpec::max_strain = " << max_strain << " violates in (0, 0.5)";
    else if (record_interval < 1) out << "PlatenTestSpec::record_interval = " << record_interval << " violates >= 1";
    if (out.str().empty()) return std::nullopt;
    return out.str();
}

ParticleBounds particle_bounds(const ParticleSet& p) {
    ParticleBounds b{{1e300, 1e300, 1e300}, {-1e300, -1e300, -1e300}};
    for (std::size_t i = 0; i < p.size(); ++i) {
        const Vec3 r{p.radius[i], p.radius[i], p.radius[i]};
        const Vec3 lo = p.position[i] - r, hi = p.position[i] + r;
        b.lo = {std::min(b.lo.x, lo.x), std::min(b.lo.y, lo.y), std::min(b.lo.z, lo.z)};
        b.hi = {std::max(b.hi.x, hi.x), std::max(b.hi.y, hi.y), std::max(b.hi.z, hi.z)};
    }
    return b;
}

double ramp_factor(double time, double ramp_time) {
    if (ramp_time <= 0.0 || time >= ramp_time) return 1.0;
    return 0.5 * (1.0 - std::cos(kPi * time / ramp_time));
}

namespace {

/// The strain a curve is reduced on: the gauge strain, the platen strain without gauges [-].
double reduced_strain(const CurvePoint& pt) {
    return std::isfinite(pt.gauge_strain) ? pt.gauge_strain : pt.platen_strain;
}

/// The strain stop: the curve's strain `strain` has run past stop_strain_ratio × its value
/// `strain_at_peak` (> 0) at a peak reached after the ramp (platen strain `platen_at_peak` past
/// ramp_strain: a peak inside the ramp is the seating's, not the specimen's).
bool past_peak_strain(const PlatenTestSpec& spec, double strain, double strain_at_peak, double platen_at_peak) {
    return spec.stop_strain_ratio > 0.0 && platen_at_peak > spec.ramp_strain && strain_at_peak > 0.0 &&
           strain > spec.stop_strain_ratio * strain_at_peak;
}

}  // namespace

PlatenTestResult run_axial_loading(World& world, const PlatenTestSpec& spec, const AxialFrame& frame,
                                   const ProgressCallback& progress, const SnapshotCallback& snapshot) {
    if (auto why = spec.invalid_reason()) throw std::invalid_argument(*why);
    if (!(frame.height > 0.0 && frame.area > 0.0) || !frame.drive || !frame.measure)
        throw std::invalid_argument("run_axial_loading: the frame needs a positive height and area, drive and measure");
    const auto start = std::chrono::steady_clock::now();
    PlatenTestResult r;
    r.height = frame.height;
    r.area = frame.area;
    const double full_speed = 0.5 * spec.strain_rate * r.height;  // each end
    const double ramp_time = spec.ramp_strain / spec.strain_rate;
    const double t0 = world.time();
    double peak = 0.0;
    double reduced_at_peak = 0.0;  // the curve's reduced strain at the peak [-]
    std::int64_t tension = 0, shear = 0;
    std::size_t seen_breaks = 0;
    for (std::int64_t step = 0;; ++step) {
        frame.drive(world, full_speed * ramp_factor(world.time() - t0, ramp_time));
        if (world.step() == RunStatus::diverged) {
            r.diverged = true;
            r.stop_reason = "diverged: " + world.status_reason();
            break;
        }
        if (step % spec.record_interval != 0) continue;
        const auto& events = world.break_events();
        for (; seen_breaks < events.size(); ++seen_breaks)
            (events[seen_breaks].mode == BondState::broken_tension ? tension : shear)++;
        CurvePoint pt;
        pt.step = world.step_count();
        pt.time = world.time();
        frame.measure(world, pt);
        pt.stress = 0.5 * (pt.stress_top + pt.stress_bottom);
        pt.broken_tension = tension;
        pt.broken_shear = shear;
        pt.kinetic_energy = world.energy().kinetic;
        r.curve.push_back(pt);
        if (pt.stress > peak) {
            peak = pt.stress;
            r.peak_stress = pt.stress;
            r.strain_at_peak = pt.platen_strain;
            reduced_at_peak = reduced_strain(pt);
        }
        if (progress) progress(pt, peak);
        if (snapshot) snapshot(world, pt);
        if (peak > 0.0 && pt.stress < spec.stop_fraction * peak && pt.platen_strain > r.strain_at_peak) {
            r.stop_reason = "post-peak";
            break;
        }
        if (past_peak_strain(spec, reduced_strain(pt), reduced_at_peak, r.strain_at_peak)) {
            r.stop_reason = "post-peak strain";
            break;
        }
        if (pt.platen_strain >= spec.max_strain) {
            r.stop_reason = "max strain";
            break;
        }
    }
    for (const CurvePoint& p : r.curve)
        if (p.stress >= 0.4 * r.peak_stress && p.platen_strain > 0.0) {
            r.secant_modulus_40 = p.stress / p.platen_strain;
            break;
        }
    r.steps = world.step_count();
    r.wall_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    return r;
}

}  // namespace gradem::exp
