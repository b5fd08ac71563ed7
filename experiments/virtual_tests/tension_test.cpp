#include "experiments/virtual_tests/tension_test.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <stdexcept>

#include "core/world.hpp"
#include "experiments/virtual_tests/axial_loading.hpp"
#include "experiments/virtual_tests/cube_specimen.hpp"

namespace gradem::exp {

std::optional<std::string> TensionTestSpec::invalid_reason() const {
    if (auto why = test.invalid_reason()) return why;
    std::ostringstream out;
    if (!(grip_depth_fraction >= 0.0 && grip_depth_fraction < 0.25))
        out << "TensionTestSpec::grip_depth_fraction = " << grip_depth_fraction << " violates in [0, 0.25)";
    if (out.str().empty()) return std::nullopt;
    return out.str();
}

GripSelection select_grips(const Packing& k, double grip_depth_fraction) {
    GripSelection g;
    g.depth = grip_depth_fraction * k.edge();
    for (std::size_t i = 0; i < k.position.size(); ++i) {
        const double z = k.position[i].z, r = k.radius[i];
        const double reach = std::max(g.depth, r);  // within the depth, or touching the face
        const bool bottom = z - k.box_lo.z <= reach, top = k.box_hi.z - z <= reach;
        if (bottom && top)
            throw std::invalid_argument("tension test: grain " + std::to_string(i) +
                                        " belongs to both grips; the specimen is too short for its grains");
        if (bottom) g.bottom.push_back(static_cast<std::int32_t>(i));
        if (top) g.top.push_back(static_cast<std::int32_t>(i));
        if (bottom || top) g.reach = std::max(g.reach, bottom ? z - k.box_lo.z : k.box_hi.z - z);
    }
    if (g.bottom.empty() || g.top.empty()) throw std::invalid_argument("tension test: a grip holds no grain");
    return g;
}

namespace {

// The gauge slabs start (1 - g - s) / 2 x height from each end face (gauges.hpp); a grip grain
// inside a slab would pin the extensometer to the grip.
void check_grips_clear_gauges(const GripSelection& g, const Packing& k, const TensionTestSpec& spec) {
    const CubeTestSpec& t = spec.test;
    const double height = k.box_hi.z - k.box_lo.z;
    const double slab_start = 0.5 * (1.0 - t.gauge_length_fraction - t.slab_fraction) * height;
    if (g.reach < slab_start) return;
    std::ostringstream why;
    why << "TensionTestSpec::grip_depth_fraction = " << spec.grip_depth_fraction << " violates: the grips reach "
        << g.reach * 1e3 << " mm from the end faces, into the gauge slabs that start at " << slab_start * 1e3
        << " mm (lower the grip depth, test.gauge_length_fraction or test.slab_fraction)";
    throw std::invalid_argument(why.str());
}

// Step 2: the grip grains move only as their grips say; the platens go.
void hold_grips(World& world, const GripSelection& g) {
    ParticleSet& p = world.edit_particles();
    for (const auto* ids : {&g.bottom, &g.top})
        for (std::int32_t i : *ids) p.flags[static_cast<std::size_t>(i)] |= kFixedVelocity | kFixedSpin;
    for (const auto* ids : {&g.bottom, &g.top})
        for (std::int32_t i : *ids) world.set_particle_motion(i, {}, {});
    world.remove_wall(1);
    world.remove_wall(0);
}

// The two grips as the loading frame: the bottom one moves down (-z), the top one up, each as a
// rigid body. The grip displacement is integrated from the prescribed speed; the grains' own
// displacements are compared against it (grip_slip) to prove they follow.
class GripFrame {
public:
    GripFrame(const World& world, const GripSelection& g, double height, double area, const Gauges& gauges)
        : grips_(g), gauges_(gauges), height_(height), area_(area), last_time_(world.time()) {
        for (const auto* ids : {&g.bottom, &g.top})
            for (std::int32_t i : *ids) start_.push_back(world.particles().position[static_cast<std::size_t>(i)]);
    }

    AxialFrame axial() {
        AxialFrame f;
        f.height = height_;
        f.area = area_;
        f.drive = [this](World& w, double speed) { drive(w, speed); };
        f.measure = [this](const World& w, CurvePoint& pt) { measure(w, pt); };
        return f;
    }

    [[nodiscard]] double slip() const { return slip_; }
    [[nodiscard]] double spin() const { return spin_; }

private:
    // Opening of one grip since the start [m] (each grip moves by this, outwards).
    [[nodiscard]] double opening(double time) const { return opening_ + speed_ * (time - last_time_); }

    void drive(World& w, double speed) {
        opening_ = opening(w.time());
        last_time_ = w.time();
        speed_ = speed;
        for (std::int32_t i : grips_.bottom) w.set_particle_motion(i, {0, 0, -speed}, {});
        for (std::int32_t i : grips_.top) w.set_particle_motion(i, {0, 0, speed}, {});
    }

    // Tension positive: grips opening, the specimen pulling the grips together.
    void measure(const World& w, CurvePoint& pt) {
        const ParticleSet& p = w.particles();
        const double open = opening(w.time());
        Vec3 bottom_force, top_force;
        double bottom_shift = 0.0, top_shift = 0.0;
        std::size_t k = 0;
        for (const auto* ids : {&grips_.bottom, &grips_.top}) {
            const bool top = ids == &grips_.top;
            const Vec3 expected{0, 0, top ? open : -open};
            for (std::int32_t id : *ids) {
                const auto i = static_cast<std::size_t>(id);
                const Vec3 moved = p.position[i] - start_[k++];
                slip_ = std::max(slip_, norm(moved - expected));
                spin_ = std::max(spin_, norm(p.spin[i]));
                (top ? top_force : bottom_force) += p.force[i];
                (top ? top_shift : bottom_shift) += moved.z;
            }
        }
        top_shift /= static_cast<double>(grips_.top.size());
        bottom_shift /= static_cast<double>(grips_.bottom.size());
        pt.platen_strain = (top_shift - bottom_shift) / height_;
        pt.gauge_strain = -gauges_.axial_strain(p);  // the gauges report compression positive
        pt.lateral_strain = gauges_.lateral_strain(p);
        pt.stress_bottom = bottom_force.z / area_;
        pt.stress_top = -top_force.z / area_;
    }

    const GripSelection& grips_;
    const Gauges& gauges_;
    double height_, area_;
    std::vector<Vec3> start_;  ///< grip-grain positions at the start, bottom then top [m]
    double opening_ = 0.0, speed_ = 0.0, last_time_ = 0.0;
    double slip_ = 0.0, spin_ = 0.0;
};

// ε1 of the chord: ASTM C469's 50 µε, or a quarter of the strain at 40 % of the peak when that
// lies below 200 µε (see tension_test.hpp).
lab::ReductionOptions tension_reduction(const PlatenTestResult& test) {
    lab::ReductionOptions o;
    o.fit_popovics = false;
    const double strain2 = lab::reduce_curve(to_stress_strain_curve(test), o).chord_strain2;
    if (std::isfinite(strain2) && strain2 > 0.0 && strain2 < 4.0 * o.chord_lower_strain) {
        o.chord_lower_strain = 0.25 * strain2;
        o.strain_window = std::min(o.strain_window, 0.5 * o.chord_lower_strain);
    }
    return o;
}

}  // namespace

TensionTestResult run_tension_test(const Packing& packing, const MaterialParams& material, const TensionTestSpec& spec,
                                   const ProgressCallback& progress) {
    if (auto why = spec.invalid_reason()) throw std::invalid_argument(*why);
    if (packing.position.empty()) throw std::invalid_argument("tension test: empty packing");
    TensionTestResult out;
    const GripSelection grips = select_grips(packing, spec.grip_depth_fraction);
    check_grips_clear_gauges(grips, packing, spec);
    out.grip_depth = grips.depth;
    out.grip_reach = grips.reach;
    out.grip_grains_bottom = grips.bottom.size();
    out.grip_grains_top = grips.top.size();

    CubeTestResult& r = out.cube;
    World world = settled_cube_specimen(packing, material, spec.test, r);
    const double height = world.walls()[1].point.z - world.walls()[0].point.z;
    const ParticleBounds b = particle_bounds(world.particles());
    const double area = (b.hi.x - b.lo.x) * (b.hi.y - b.lo.y);
    hold_grips(world, grips);
    const Gauges gauges = cube_gauges(world, packing, spec.test);
    r.time_step = world.time_step();
    GripFrame frame(world, grips, height, area, gauges);
    r.test = run_axial_loading(world, spec.test.loading, frame.axial(), progress, spec.test.snapshot);
    r.cracks = world.break_events();
    const lab::ReductionOptions options = tension_reduction(r.test);
    out.chord_lower_strain = options.chord_lower_strain;
    reduce_cube_result(r, spec.test, options);
    out.grip_slip = frame.slip();
    out.grip_spin = frame.spin();
    return out;
}

}  // namespace gradem::exp
