#include "experiments/virtual_tests/platen_compression.hpp"

#include <limits>
#include <stdexcept>

namespace gradem::exp {

void add_platens(World& world, double friction) {
    if (!world.walls().empty()) throw std::invalid_argument("add_platens: the World already has walls");
    const ParticleBounds b = particle_bounds(world.particles());
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
    const ParticleBounds b = particle_bounds(world.particles());
    AxialFrame frame;
    frame.height = world.walls()[1].point.z - world.walls()[0].point.z;
    frame.area = (b.hi.x - b.lo.x) * (b.hi.y - b.lo.y);
    const double bottom_start = world.walls()[0].displacement.z, top_start = world.walls()[1].displacement.z;
    // Platens close: the bottom one moves up (+z), the top one down.
    frame.drive = [](World& w, double speed) {
        w.wall(0).velocity = {0, 0, speed};
        w.wall(1).velocity = {0, 0, -speed};
    };
    // Compression positive: platen closing, the reactions pushing the platens apart.
    frame.measure = [&frame, bottom_start, top_start, gauges](const World& w, CurvePoint& pt) {
        pt.platen_strain = ((w.walls()[0].displacement.z - bottom_start) - (w.walls()[1].displacement.z - top_start)) / frame.height;
        constexpr double kNoGauge = std::numeric_limits<double>::quiet_NaN();
        pt.gauge_strain = gauges ? gauges->axial_strain(w.particles()) : kNoGauge;
        pt.lateral_strain = gauges ? gauges->lateral_strain(w.particles()) : kNoGauge;
        pt.stress_bottom = -w.walls()[0].reaction.z / frame.area;
        pt.stress_top = w.walls()[1].reaction.z / frame.area;
    };
    return run_axial_loading(world, spec, frame, progress, snapshot);
}

}  // namespace gradem::exp
