#include "experiments/genesis.hpp"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cmath>
#include <sstream>
#include <stdexcept>

#include "core/random.hpp"
#include "core/world.hpp"
#include "experiments/dense_placement.hpp"

namespace gradem::exp {

std::optional<std::string> GenesisSpec::invalid_reason() const {
    std::ostringstream out;
    auto rule = [&](const char* field, double v, const char* text) { out << "genesis." << field << " = " << v << " violates " << text; };
    if (!(edge > 0.0)) rule("edge", edge, "> 0");
    else if (!(target_solid_fraction > 0.3 && target_solid_fraction < 0.75)) rule("target_solid_fraction", target_solid_fraction, "in (0.3, 0.75)");
    else if (!(locked_in_stress > 0.0)) rule("locked_in_stress", locked_in_stress, "> 0");
    else if (!(stress_tolerance > 0.0 && stress_tolerance < 1.0)) rule("stress_tolerance", stress_tolerance, "in (0, 1)");
    else if (!(reference_modulus > 0.0)) rule("reference_modulus", reference_modulus, "> 0");
    else if (!(stiffness_ratio > 0.0)) rule("stiffness_ratio", stiffness_ratio, "> 0");
    else if (!(density > 0.0)) rule("density", density, "> 0");
    else if (!(damping >= 0.0 && damping < 1.0)) rule("damping", damping, "in [0, 1)");
    else if (min_contacts < 0) rule("min_contacts", min_contacts, ">= 0");
    else if (floater_passes < 0) rule("floater_passes", floater_passes, ">= 0");
    else if (!(floater_growth >= 0.0 && floater_growth < 0.5)) rule("floater_growth", floater_growth, "in [0, 0.5)");
    else if (!(equilibrium_ratio > 0.0)) rule("equilibrium_ratio", equilibrium_ratio, "> 0");
    else if (max_steps < 1) rule("max_steps", static_cast<double>(max_steps), ">= 1");
    if (out.str().empty()) return std::nullopt;
    return out.str();
}

std::optional<std::string> SpecimenSpec::invalid_reason() const {
    if (auto why = size_rule.invalid_reason()) return why;
    if (auto why = genesis.invalid_reason()) return why;
    const double d_max = size_rule.max_diameter > 0 ? size_rule.max_diameter * size_rule.scale : 0.0;
    if (d_max > 0.0 && genesis.edge < 3.0 * d_max) {
        std::ostringstream out;
        out << "genesis.edge = " << genesis.edge << " violates >= 3 x the largest grain (" << d_max
            << " m): the cube would hold fewer than three grains across";
        return out.str();
    }
    return std::nullopt;
}

namespace {

constexpr int kAxes = 3;
constexpr double kOvergrowth = 0.003;  // initial radius growth past the geometric contact state

// Six frictionless walls around the box, normals inward: x-, x+, y-, y+, z-, z+.
void add_vessel(World& world, const Vec3& lo, const Vec3& hi, const GenesisSpec& g) {
    WallContactParams c;
    c.effective_modulus = g.reference_modulus;
    c.stiffness_ratio = g.stiffness_ratio;
    c.friction = 0.0;
    const char* names[6] = {"x-", "x+", "y-", "y+", "z-", "z+"};
    for (int a = 0; a < kAxes; ++a) {
        Vec3 n;
        n = a == 0 ? Vec3{1, 0, 0} : (a == 1 ? Vec3{0, 1, 0} : Vec3{0, 0, 1});
        world.add_wall({names[2 * a], n, lo, {}, c, {}, {}});
        world.add_wall({names[2 * a + 1], -1.0 * n, hi, {}, c, {}, {}});
    }
}

double box_extent(const World& w, int axis) {
    return w.walls()[static_cast<std::size_t>(2 * axis + 1)].point[axis] -
           w.walls()[static_cast<std::size_t>(2 * axis)].point[axis];
}

// Compressive normal stress on wall k [Pa].
double wall_stress(const World& w, int k) {
    const int axis = k / 2;
    const double area = box_extent(w, (axis + 1) % 3) * box_extent(w, (axis + 2) % 3);
    const Wall& wall = w.walls()[static_cast<std::size_t>(k)];
    return -dot(wall.reaction, wall.normal) / area;
}

// Isotropic stress installation by uniform radius scaling (PFC material genesis): the vessel
// stays put and every radius is multiplied by (1 + dm), with dm a fraction of the volumetric
// strain that would close the error in the mean wall stress for a packing bulk modulus of
// 2 % of E* (jammed frictionless packings under 1e-5..1e-3 E* are that soft). Growth loads every contact at once (no wave from the walls), so the stress
// responds within a few steps and the loop is stable; dm is capped per update.
class RadiusServo {
    static constexpr double kBulkFraction = 0.02;

public:
    explicit RadiusServo(const GenesisSpec& g) : g_(g) {}
    /// Returns the multiplier applied.
    double update(World& world) {
        double mean = 0.0;
        for (int k = 0; k < 2 * kAxes; ++k) mean += wall_stress(world, k) / (2 * kAxes);
        const double error = g_.locked_in_stress - mean;
        if (std::fabs(error) < 0.01 * g_.locked_in_stress) return 1.0;  // dead band: let it settle
        const double dm = std::clamp(0.05 * error / (3.0 * kBulkFraction * g_.reference_modulus), -2.0e-6, 2.0e-6);
        if (std::fabs(dm) < 1e-12) return 1.0;
        world.scale_radii(1.0 + dm);
        return 1.0 + dm;
    }

private:
    GenesisSpec g_;
};

bool stresses_ok(const World& w, const GenesisSpec& g) {
    for (int k = 0; k < 6; ++k)
        if (std::fabs(wall_stress(w, k) - g.locked_in_stress) > g.stress_tolerance * g.locked_in_stress) return false;
    return true;
}

// Cycles until the stress and equilibrium tolerances hold (or the budget ends): the radius
// servo runs while the mean stress is off target; once it is within 1 % the servo rests, so
// the packing can settle undisturbed (the servo has a 1 % dead band on the mean stress).
// Returns whether both tolerances hold; `growth` accumulates the radius multiplier.
bool cycle_to_target(World& world, RadiusServo& servo, const GenesisSpec& g, std::int64_t budget,
                     double& growth) {
    const std::int64_t end = world.step_count() + budget;
    while (world.step_count() < end) {
        const bool on_target = stresses_ok(world, g);
        const double dm = servo.update(world);  // keeps the mean on target even while settling
        growth *= dm;
        world.run(dm == 1.0 ? 200 : 20);
        if (world.status() != RunStatus::running)
            throw std::runtime_error("genesis diverged: " + world.status_reason());
        if (std::getenv("GRADEM_DEBUG_GENESIS") && world.step_count() % 1000 == 0)
            std::fprintf(stderr, "genesis step %lld: stress %.4g %.4g %.4g %.4g %.4g %.4g MPa, ratio %.3g, growth %.6f\n",
                         static_cast<long long>(world.step_count()), wall_stress(world, 0) * 1e-6, wall_stress(world, 1) * 1e-6,
                         wall_stress(world, 2) * 1e-6, wall_stress(world, 3) * 1e-6, wall_stress(world, 4) * 1e-6,
                         wall_stress(world, 5) * 1e-6, world.unbalanced_force_ratio(), growth);
        if (on_target && stresses_ok(world, g) && world.unbalanced_force_ratio() < g.equilibrium_ratio) return true;
    }
    return false;
}

std::vector<std::int32_t> floaters(const World& w, int min_contacts) {
    const std::vector<std::int32_t> count = w.contact_counts();
    std::vector<std::int32_t> out;
    for (std::size_t i = 0; i < count.size(); ++i)
        if (count[i] < min_contacts) out.push_back(static_cast<std::int32_t>(i));
    return out;
}

}  // namespace

Packing generate_packing(const lab::GradationCurve& curve, const SpecimenSpec& spec) {
    if (auto why = spec.invalid_reason()) throw std::invalid_argument(*why);
    const auto start = std::chrono::steady_clock::now();
    const GenesisSpec& g = spec.genesis;
    const double box_volume = g.edge * g.edge * g.edge;
    Packing out;
    out.grains = sample_grains(curve, spec.size_rule, g.target_solid_fraction * box_volume, spec.seed);
    const double largest = *std::max_element(out.grains.diameters.begin(), out.grains.diameters.end());
    if (g.edge < 3.0 * largest) {
        std::ostringstream why;
        why << "genesis.edge = " << g.edge << " m is smaller than 3 x the largest grain (" << largest
            << " m): set size_rule.max_diameter or a larger edge";
        throw std::invalid_argument(why.str());
    }
    const DensePlacement placed = place_dense(out.grains.diameters, g.edge, spec.seed ^ 0xA5A5A5A5ull, 1.0e-3);

    ParticleSet particles;
    for (std::size_t i = 0; i < placed.position.size(); ++i)
        particles.add(placed.position[i], placed.radius[i], g.density);
    ContactParams contact;
    contact.effective_modulus = g.reference_modulus;
    contact.stiffness_ratio = g.stiffness_ratio;
    contact.friction = 0.0;
    SimParams sim;
    sim.local_damping = g.damping;
    sim.skin_fraction = 0.3;
    World world(std::move(particles), contact, sim);
    add_vessel(world, {0, 0, 0}, {placed.edge, placed.edge, placed.edge}, g);
    // Approach the target from above: an over-grown, jammed packing unloads smoothly, while
    // loading up from below makes a frictionless packing creep through rearrangements.
    RadiusServo servo(g);
    double growth = 1.0 + kOvergrowth;
    world.scale_radii(growth);

    cycle_to_target(world, servo, g, g.max_steps / 3, growth);
    const std::size_t n = world.particles().size();
    std::vector<std::int32_t> floating = floaters(world, g.min_contacts);
    out.floaters_before = static_cast<double>(floating.size()) / static_cast<double>(n);
    for (int pass = 0; pass < g.floater_passes && !floating.empty(); ++pass) {
        ParticleSet& p = world.edit_particles();
        for (std::int32_t i : floating)
            p.set_radius(static_cast<std::size_t>(i), p.radius[static_cast<std::size_t>(i)] * (1.0 + g.floater_growth));
        cycle_to_target(world, servo, g, g.max_steps / (3 * std::max(1, g.floater_passes)), growth);
        floating = floaters(world, g.min_contacts);
    }
    // Whatever the passes left: bring the stress back and settle, on the rest of the budget.
    cycle_to_target(world, servo, g, std::max<std::int64_t>(0, g.max_steps - world.step_count()), growth);
    out.floaters_after = static_cast<double>(floaters(world, g.min_contacts).size()) / static_cast<double>(n);
    const ParticleSet& p = world.particles();
    out.position = p.position;
    out.radius = p.radius;
    out.density = g.density;
    out.box_lo = {world.walls()[0].point.x, world.walls()[2].point.y, world.walls()[4].point.z};
    out.box_hi = {world.walls()[1].point.x, world.walls()[3].point.y, world.walls()[5].point.z};
    double solid = 0.0;
    for (double r : out.radius) solid += 4.0 / 3.0 * kPi * r * r * r;
    const Vec3 extent = out.box_hi - out.box_lo;
    out.porosity = 1.0 - solid / (extent.x * extent.y * extent.z);
    out.edge_over_d50 = out.edge() / out.grains.d50;
    const std::vector<std::int32_t> count = world.contact_counts();
    double total = 0.0;
    for (std::int32_t c : count) total += c;
    out.mean_coordination = total / static_cast<double>(n);
    out.wall_stress = {0.5 * (wall_stress(world, 0) + wall_stress(world, 1)),
                       0.5 * (wall_stress(world, 2) + wall_stress(world, 3)),
                       0.5 * (wall_stress(world, 4) + wall_stress(world, 5))};
    out.unbalanced_ratio = world.unbalanced_force_ratio();
    out.converged = stresses_ok(world, g) && out.unbalanced_ratio < g.equilibrium_ratio;
    out.radius_growth = growth;
    out.steps = world.step_count();
    out.grains.diameters.clear();
    out.grains.diameters.shrink_to_fit();
    out.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    return out;
}

std::string describe(const Packing& k, const SpecimenSpec& spec) {
    std::ostringstream out;
    out.precision(4);
    const SizeRule& r = spec.size_rule;
    out << "size rule: d_min " << r.min_diameter * 1e3 << " mm (removes " << 100 * k.grains.removed_fine_fraction
        << " % of the mass), d_max " << (r.max_diameter > 0 ? std::to_string(r.max_diameter * 1e3) + " mm" : std::string("none"))
        << " (removes " << 100 * k.grains.removed_coarse_fraction << " %), scale x" << r.scale << "\n";
    out << "specimen: N = " << k.radius.size() << ", edge " << k.edge() * 1e3 << " mm, L/d50 = " << k.edge_over_d50
        << ", porosity " << k.porosity << ", coordination " << k.mean_coordination << "\n";
    out << "sampling: max deviation from the target curve " << 100 * k.grains.max_deviation
        << " percentage points; floaters " << 100 * k.floaters_before << " % -> " << 100 * k.floaters_after << " %\n";
    out << "genesis: locked-in stress x/y/z " << k.wall_stress.x * 1e-6 << " / " << k.wall_stress.y * 1e-6 << " / "
        << k.wall_stress.z * 1e-6 << " MPa, unbalanced-force ratio " << k.unbalanced_ratio << ", radii x" << k.radius_growth << ", " << k.steps
        << " steps, " << k.seconds << " s" << (k.converged ? "" : " (NOT converged: tolerances not met)");
    return out.str();
}

}  // namespace gradem::exp
