#include "experiments/platen_compression.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <sstream>
#include <stdexcept>

namespace gradem::exp {

std::optional<std::string> PlatenTestSpec::invalid_reason() const {
    std::ostringstream out;
    if (!(strain_rate > 0.0)) out << "PlatenTestSpec::strain_rate = " << strain_rate << " violates > 0";
    else if (!(ramp_strain >= 0.0)) out << "PlatenTestSpec::ramp_strain = " << ramp_strain << " violates >= 0";
    else if (!(platen_friction >= 0.0)) out << "PlatenTestSpec::platen_friction = " << platen_friction << " violates >= 0";
    else if (!(stop_fraction > 0.0 && stop_fraction < 1.0)) out << "PlatenTestSpec::stop_fraction = " << stop_fraction << " violates in (0, 1)";
    else if (!(max_strain > 0.0 && max_strain < 0.5)) out << "PlatenTestSpec::max_strain = " << max_strain << " violates in (0, 0.5)";
    else if (record_interval < 1) out << "PlatenTestSpec::record_interval = " << record_interval << " violates >= 1";
    if (out.str().empty()) return std::nullopt;
    return out.str();
}

namespace {

struct Box {
    Vec3 lo, hi;
};

Box specimen_box(const ParticleSet& p) {
    Box b{{1e300, 1e300, 1e300}, {-1e300, -1e300, -1e300}};
    for (std::size_t i = 0; i < p.size(); ++i) {
        const Vec3 r{p.radius[i], p.radius[i], p.radius[i]};
        const Vec3 lo = p.position[i] - r, hi = p.position[i] + r;
        b.lo = {std::min(b.lo.x, lo.x), std::min(b.lo.y, lo.y), std::min(b.lo.z, lo.z)};
        b.hi = {std::max(b.hi.x, hi.x), std::max(b.hi.y, hi.y), std::max(b.hi.z, hi.z)};
    }
    return b;
}

// Half-cosine ramp from 0 to 1 over the time `ramp_time` [s]: no velocity jump, no stress wave.
double ramp_factor(double time, double ramp_time) {
    if (ramp_time <= 0.0 || time >= ramp_time) return 1.0;
    return 0.5 * (1.0 - std::cos(kPi * time / ramp_time));
}

}  // namespace

void add_platens(World& world, double friction) {
    if (!world.walls().empty()) throw std::invalid_argument("add_platens: the World already has walls");
    const Box b = specimen_box(world.particles());
    WallContactParams contact;
    contact.effective_modulus = world.contact_params().effective_modulus;
    contact.stiffness_ratio = world.contact_params().stiffness_ratio;
    contact.friction = friction;
    world.add_wall({"bottom", {0, 0, 1}, {0, 0, b.lo.z}, {}, contact, {}, {}});
    world.add_wall({"top", {0, 0, -1}, {0, 0, b.hi.z}, {}, contact, {}, {}});
}

PlatenTestResult run_platen_compression(World& world, const PlatenTestSpec& spec,
                                        const ProgressCallback& progress, const Gauges* gauges,
                                        const SnapshotCallback& snapshot) {
    if (auto why = spec.invalid_reason()) throw std::invalid_argument(*why);
    if (world.walls().size() != 2) add_platens(world, spec.platen_friction);
    const auto start = std::chrono::steady_clock::now();
    const Box b = specimen_box(world.particles());
    PlatenTestResult r;
    r.height = world.walls()[1].point.z - world.walls()[0].point.z;
    r.area = (b.hi.x - b.lo.x) * (b.hi.y - b.lo.y);
    const double full_speed = 0.5 * spec.strain_rate * r.height;  // each platen
    const double ramp_time = spec.ramp_strain / spec.strain_rate;
    const double t0 = world.time();
    const Vec3 platen_start{world.walls()[0].displacement.z, world.walls()[1].displacement.z, 0.0};
    double peak = 0.0;
    std::int64_t tension = 0, shear = 0;
    std::size_t seen_breaks = 0;
    for (std::int64_t step = 0;; ++step) {
        const double speed = full_speed * ramp_factor(world.time() - t0, ramp_time);
        world.wall(0).velocity = {0, 0, speed};
        world.wall(1).velocity = {0, 0, -speed};
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
        pt.platen_strain = ((world.walls()[0].displacement.z - platen_start.x) -
                            (world.walls()[1].displacement.z - platen_start.y)) / r.height;
        constexpr double kNoGauge = std::numeric_limits<double>::quiet_NaN();
        pt.gauge_strain = gauges ? gauges->axial_strain(world.particles()) : kNoGauge;
        pt.lateral_strain = gauges ? gauges->lateral_strain(world.particles()) : kNoGauge;
        pt.stress_bottom = -world.walls()[0].reaction.z / r.area;
        pt.stress_top = world.walls()[1].reaction.z / r.area;
        pt.stress = 0.5 * (pt.stress_top + pt.stress_bottom);
        pt.broken_tension = tension;
        pt.broken_shear = shear;
        pt.kinetic_energy = world.energy().kinetic;
        r.curve.push_back(pt);
        if (pt.stress > peak) {
            peak = pt.stress;
            r.peak_stress = pt.stress;
            r.strain_at_peak = pt.platen_strain;
        }
        if (progress) progress(pt, peak);
        if (snapshot) snapshot(world, pt);
        if (peak > 0.0 && pt.stress < spec.stop_fraction * peak && pt.platen_strain > r.strain_at_peak) {
            r.stop_reason = "post-peak";
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
