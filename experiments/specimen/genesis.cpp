#include "experiments/specimen/genesis.hpp"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cmath>
#include <sstream>
#include <stdexcept>

#include "core/random.hpp"
#include "core/world.hpp"
#include "experiments/specimen/dense_placement.hpp"
#include "experiments/specimen/morton_order.hpp"

namespace gradem::exp {

namespace {
// Linear contacts under isotropic stress p overlap by about 2.5 p/E* of a grain radius
// (F ~ p (2R)^2 on k_n ~ pi R E* / 2); beyond 1e-3 E* that is no longer a seating stress.
constexpr double kMaxStressOverModulus = 1.0e-3;
}  // namespace

std::optional<std::string> GenesisSpec::invalid_reason() const {
    std::ostringstream out;
    auto rule = [&](const char* field, double v, const char* text) { out << "genesis." << field << " = " << v << " violates " << text; };
    if (!(edge > 0.0)) rule("edge", edge, "> 0");
    else if (!(target_solid_fraction > 0.3 && target_solid_fraction < 0.75)) rule("target_solid_fraction", target_solid_fraction, "in (0.3, 0.75)");
    else if (!(locked_in_stress > 0.0)) rule("locked_in_stress", locked_in_stress, "> 0");
    else if (!(reference_modulus > 0.0)) rule("reference_modulus", reference_modulus, "> 0");
    else if (!(locked_in_stress <= kMaxStressOverModulus * reference_modulus))
        out << "genesis.locked_in_stress = " << locked_in_stress << " Pa violates <= " << kMaxStressOverModulus
            << " x reference_modulus (" << kMaxStressOverModulus * reference_modulus
            << " Pa): a locked-in stress is a small seating stress; at this one the rigid-grain packing "
               "would overlap by more than ~0.3 % of a grain radius";
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
constexpr double kJammingPressure = 1.0e-3;  // first minimisation stage, x E* [-]
constexpr double kStageRatio = 1.0e-2;       // loose tolerances of the intermediate stages
constexpr double kStageStress = 0.1;
constexpr double kMargin = 0.5;              // the minimiser aims at this x the tolerances
constexpr double kFillSlack = 1.01;          // final edge may exceed the asked edge by 1 %
constexpr std::int64_t kDemChunk = 20;       // DEM steps between checks
constexpr std::int64_t kDemSteps = 2000;     // DEM check budget (within max_steps)

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

bool stresses_ok(const World& w, const GenesisSpec& g) {
    for (int k = 0; k < 2 * kAxes; ++k)
        if (std::fabs(wall_stress(w, k) - g.locked_in_stress) > g.stress_tolerance * g.locked_in_stress) return false;
    return true;
}

std::vector<std::size_t> floaters(const std::vector<std::int32_t>& count, int min_contacts) {
    std::vector<std::size_t> out;
    for (std::size_t i = 0; i < count.size(); ++i)
        if (count[i] < min_contacts) out.push_back(i);
    return out;
}

std::int64_t remaining(const GenesisSpec& g, const DensePacker& packer) {
    return std::max<std::int64_t>(0, g.max_steps - packer.iterations());
}

// Grains that jam below the target solid fraction need a bigger vessel than asked.
void require_filled(const DensePacker& packer, const GenesisSpec& g) {
    const double edge = std::cbrt(packer.box().x * packer.box().y * packer.box().z);
    if (edge <= kFillSlack * g.edge) return;
    std::ostringstream why;
    why << "genesis.target_solid_fraction = " << g.target_solid_fraction << " cannot be reached: the grains of this gradation jam at a solid fraction of "
        << packer.solid_fraction() << " and need a " << edge * 1e3 << " mm vessel instead of the asked " << g.edge * 1e3
        << " mm; lower genesis.target_solid_fraction (below " << packer.solid_fraction() << ")";
    throw std::invalid_argument(why.str());
}

const auto debug_start = std::chrono::steady_clock::now();

void debug_stage(DensePacker& packer, double p, bool ok) {
    if (!std::getenv("GRADEM_DEBUG_GENESIS")) return;
    const PackingBalance b = packer.balance();
    std::fprintf(stderr, "genesis stage p %.3g Pa: %s after %lld iterations (%lld rebuilds, %.2f s), phi %.4f, ratio %.3g, walls %.4g %.4g %.4g %.4g %.4g %.4g MPa, overlap max %.3g mean %.3g\n",
                 p, ok ? "ok" : "NOT converged", static_cast<long long>(packer.iterations()), static_cast<long long>(packer.rebuilds()),
                 std::chrono::duration<double>(std::chrono::steady_clock::now() - debug_start).count(), packer.solid_fraction(), b.unbalanced_ratio,
                 b.wall_stress_lo.x * 1e-6, b.wall_stress_hi.x * 1e-6, b.wall_stress_lo.y * 1e-6, b.wall_stress_hi.y * 1e-6,
                 b.wall_stress_lo.z * 1e-6, b.wall_stress_hi.z * 1e-6, b.max_overlap, b.mean_overlap);
}

// Step 3: floaters grow by floater_growth per pass and the packing is minimised again after
// each pass, at `pressure`.
void reduce_floaters(DensePacker& packer, const GenesisSpec& g, double pressure, Packing& out) {
    const double n = static_cast<double>(packer.radii().size());
    std::vector<std::size_t> floating = floaters(packer.contact_counts(), g.min_contacts);
    out.floaters_before = static_cast<double>(floating.size()) / n;
    for (int pass = 0; pass < g.floater_passes && !floating.empty() && g.floater_growth > 0.0; ++pass) {
        for (std::size_t i : floating) packer.grow(i, 1.0 + g.floater_growth);
        const bool ok = packer.relax(pressure, kStageRatio, kStageStress, remaining(g, packer));
        debug_stage(packer, pressure, ok);
        floating = floaters(packer.contact_counts(), g.min_contacts);
    }
}

// Steps 2 and 3: jam at a high pressure (where the minimiser converges fast and a floater's
// growth is small against the overlaps), reduce floaters there, unload in decades to the
// locked-in stress. Returns whether the final stage converged.
bool pack(DensePacker& packer, const GenesisSpec& g, Packing& out) {
    const double jamming = std::max(g.locked_in_stress, kJammingPressure * g.reference_modulus);
    const bool jammed = packer.relax(jamming, kStageRatio, kStageStress, remaining(g, packer));
    debug_stage(packer, jamming, jammed);
    if (jammed) require_filled(packer, g);  // decompression only makes the box larger
    reduce_floaters(packer, g, jamming, out);
    for (double p = 0.1 * jamming; p > g.locked_in_stress; p *= 0.1) {
        const bool ok = packer.relax(p, kStageRatio, kStageStress, remaining(g, packer));
        debug_stage(packer, p, ok);
    }
    const bool ok = packer.relax(g.locked_in_stress, kMargin * g.equilibrium_ratio, kMargin * g.stress_tolerance,
                                 remaining(g, packer));
    debug_stage(packer, g.locked_in_stress, ok);
    if (ok) require_filled(packer, g);
    out.floaters_after = static_cast<double>(floaters(packer.contact_counts(), g.min_contacts).size()) /
                         static_cast<double>(packer.radii().size());
    return ok;
}

// Step 5: the World, with real masses and walls, cycles until it measures the tolerances.
World check_with_world(const std::vector<Vec3>& x, const std::vector<double>& r, const Vec3& box, const GenesisSpec& g,
                       std::int64_t budget) {
    ParticleSet particles;
    for (std::size_t i = 0; i < x.size(); ++i) particles.add(x[i], r[i], g.density);
    ContactParams contact;
    contact.effective_modulus = g.reference_modulus;
    contact.stiffness_ratio = g.stiffness_ratio;
    contact.friction = 0.0;
    SimParams sim;
    sim.local_damping = g.damping;
    World world(std::move(particles), contact, sim);
    add_vessel(world, {0, 0, 0}, box, g);
    do {
        world.run(std::min(kDemChunk, std::max<std::int64_t>(1, budget - world.step_count())));
        if (world.status() != RunStatus::running) throw std::runtime_error("genesis diverged: " + world.status_reason());
        if (std::getenv("GRADEM_DEBUG_GENESIS"))
            std::fprintf(stderr, "genesis DEM step %lld: stress %.4g %.4g %.4g %.4g %.4g %.4g MPa, ratio %.3g\n",
                         static_cast<long long>(world.step_count()), wall_stress(world, 0) * 1e-6, wall_stress(world, 1) * 1e-6,
                         wall_stress(world, 2) * 1e-6, wall_stress(world, 3) * 1e-6, wall_stress(world, 4) * 1e-6,
                         wall_stress(world, 5) * 1e-6, world.unbalanced_force_ratio());
    } while (world.step_count() < budget && !(stresses_ok(world, g) && world.unbalanced_force_ratio() <= g.equilibrium_ratio));
    return world;
}

void report(const World& world, const GenesisSpec& g, Packing& out) {
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
    double total = 0.0;
    for (std::int32_t c : world.contact_counts()) total += c;
    out.mean_coordination = total / static_cast<double>(out.radius.size());
    out.wall_stress = {0.5 * (wall_stress(world, 0) + wall_stress(world, 1)),
                       0.5 * (wall_stress(world, 2) + wall_stress(world, 3)),
                       0.5 * (wall_stress(world, 4) + wall_stress(world, 5))};
    out.unbalanced_ratio = world.unbalanced_force_ratio();
    out.steps = world.step_count();
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
    bool relaxed = false;
    Vec3 box;
    std::vector<Vec3> position;
    std::vector<double> radius;
    {  // the packer's arrays are freed before the World is built (peak memory)
        DensePacker packer(out.grains.diameters, g.edge, g.reference_modulus, spec.seed ^ 0xA5A5A5A5ull);
        relaxed = pack(packer, g, out);
        out.relax_iterations = packer.iterations();
        box = packer.box();
        const std::vector<std::int32_t> order = morton_order(packer.positions(), {0, 0, 0}, box);
        position = permuted(packer.positions(), order);
        radius = permuted(packer.radii(), order);
    }
    const std::int64_t dem_budget = std::min(kDemSteps, std::max<std::int64_t>(1, g.max_steps - out.relax_iterations));
    const World world = check_with_world(position, radius, box, g, dem_budget);
    position = {}, radius = {};
    report(world, g, out);
    out.converged = relaxed && stresses_ok(world, g) && out.unbalanced_ratio <= g.equilibrium_ratio;
    out.radius_growth = 1.0;
    out.grains.diameters.clear();
    out.grains.diameters.shrink_to_fit();
    out.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    return out;
}

std::string convergence_failure(const Packing& k, const SpecimenSpec& spec) {
    if (k.converged) return {};
    const GenesisSpec& g = spec.genesis;
    std::ostringstream out;
    out << "genesis did not converge within genesis.max_steps = " << g.max_steps << " (" << k.relax_iterations
        << " minimisation iterations, " << k.steps << " DEM steps): wall stresses x/y/z " << k.wall_stress.x * 1e-6 << " / "
        << k.wall_stress.y * 1e-6 << " / " << k.wall_stress.z * 1e-6 << " MPa (target " << g.locked_in_stress * 1e-6 << " MPa +- "
        << 100 * g.stress_tolerance << " %), unbalanced-force ratio " << k.unbalanced_ratio << " (target <= " << g.equilibrium_ratio
        << "); raise genesis.max_steps";
    return out.str();
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
        << " DEM steps after " << k.relax_iterations << " minimisation iterations, " << k.seconds << " s"
        << (k.converged ? "" : " (NOT converged: tolerances not met)");
    return out.str();
}

}  // namespace gradem::exp
