#include "experiments/virtual_tests/cube_specimen.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <stdexcept>

#include "core/world.hpp"
#include "experiments/paste/paste_spec.hpp"

namespace gradem::exp {
namespace {

double mean_radius(const Packing& k) {
    double sum = 0.0;
    for (double r : k.radius) sum += r;
    return sum / static_cast<double>(k.radius.size());
}

// Explicit paste: paste-paste bonds are m.bond, paste-sand (ITZ) bonds m.bond scaled
// by the ITZ factors, sand-sand pairs bonded with m.bond or frictional only.
BondFamilyTable family_bonds(const MaterialParams& m) {
    BondFamilyTable t = BondFamilyTable::empty(2);
    BondParams itz = m.bond;
    const double f = m.families.itz_strength_factor;
    itz.tensile_strength_mean *= f;
    itz.tensile_strength_std *= f;
    itz.cohesion_mean *= f;
    itz.cohesion_std *= f;
    itz.effective_modulus *= m.families.itz_modulus_factor;
    t.set(kPasteFamily, kPasteFamily, m.bond);
    t.set(kSandFamily, kPasteFamily, itz);
    if (m.families.sand_sand_bonded) t.set(kSandFamily, kSandFamily, m.bond);
    return t;
}

}  // namespace

World bonded_cube_specimen(const Packing& k, const MaterialParams& m) {
    const bool paste = !k.family.empty();
    ParticleSet particles;
    for (std::size_t i = 0; i < k.position.size(); ++i) {
        const std::uint8_t family = paste ? k.family[i] : kSandFamily;
        particles.add(k.position[i], k.radius[i], family == kPasteFamily ? k.paste_density : k.density, family);
    }
    SimParams sim;
    sim.local_damping = m.damping;
    // A stress-free start (explicit paste) supplies ~1e-29 J: kinetic energies below the cube's
    // elastic energy at a strain of 1e-9 (½ E* L³ ε²) are round-off, not an instability.
    const double edge = k.edge(), strain = 1e-9;
    sim.divergence_energy_floor = 0.5 * m.contact.effective_modulus * edge * edge * edge * strain * strain;
    World world(std::move(particles), m.contact, sim);
    if (paste) world.install_bonds(family_bonds(m), m.bond_gap(mean_radius(k)));
    else world.install_bonds(m.bond, m.bond_gap(mean_radius(k)));
    WallContactParams platen;
    platen.effective_modulus = m.contact.effective_modulus;
    platen.stiffness_ratio = m.contact.stiffness_ratio;
    platen.friction = m.platen_friction;
    world.add_wall({"bottom", {0, 0, 1}, {0, 0, k.box_lo.z}, {}, platen, {}, {}});
    world.add_wall({"top", {0, 0, -1}, {0, 0, k.box_hi.z}, {}, platen, {}, {}});
    return world;
}

namespace {

// Cycles the released specimen (platens fixed) until the unbalanced-force ratio is small.
std::int64_t settle(World& world, const CubeTestSpec& spec, double& ratio) {
    const std::int64_t start = world.step_count();
    ratio = 1.0;
    while (world.step_count() - start < spec.max_settle_steps) {
        world.run(100);
        if (world.status() != RunStatus::running) break;
        ratio = world.unbalanced_force_ratio();
        if (ratio < spec.settle_ratio) break;
    }
    return world.step_count() - start;
}

// Largest relative difference of the two end stresses on the loading branch: from 20 % of the
// peak to the first point at 95 % of it. Past that point the cracks that make the peak run
// through the specimen and their stress waves set the two ends apart at any loading rate (a
// flat-joint tension cube: 3.0, 3.3 and 3.2 % up to its peak at 1, 1.5 and 2 × the automatic
// rate, 1.6, 1.5 and 1.4 % up to 95 %), which lowering the rate does not cure. Below it, cracks
// can still do it (a tension cube microcracks from about 70 % of its peak), so the warning names
// both causes, and `--check-rate` tells them apart (report::imbalance_verdict).
double platen_imbalance(const PlatenTestResult& t) {
    double worst = 0.0;
    for (const CurvePoint& p : t.curve) {
        if (p.platen_strain > t.strain_at_peak) break;
        if (p.stress < 0.2 * t.peak_stress) continue;
        if (p.stress >= kImbalanceBranchEnd * t.peak_stress) break;
        worst = std::max(worst, std::fabs(p.stress_top - p.stress_bottom) / p.stress);
    }
    return worst;
}

void count_family_bonds(const World& world, const Packing& packing, CubeTestResult& r) {
    for (const ParallelBond& b : world.bonds()) {
        const int paste_ends = (packing.family[static_cast<std::size_t>(b.i)] == kPasteFamily) +
                               (packing.family[static_cast<std::size_t>(b.j)] == kPasteFamily);
        ++(paste_ends == 0 ? r.bonds_sand_sand : paste_ends == 1 ? r.bonds_itz : r.bonds_paste_paste);
    }
}

}  // namespace

World settled_cube_specimen(const Packing& packing, const MaterialParams& material, const CubeTestSpec& spec,
                            CubeTestResult& r) {
    if (auto why = material.invalid_reason()) throw std::invalid_argument(*why);
    if (auto why = spec.invalid_reason()) throw std::invalid_argument(*why);
    if (packing.position.empty()) throw std::invalid_argument("cube test: empty packing");
    World world = bonded_cube_specimen(packing, material);
    r.particles = world.particles().size();
    r.bonds = world.bonds().size();
    if (!packing.family.empty()) count_family_bonds(world, packing, r);
    r.settle_steps = settle(world, spec, r.settle_ratio);
    if (r.settle_ratio >= spec.settle_ratio)
        r.warnings.push_back("settling stopped at unbalanced-force ratio " + std::to_string(r.settle_ratio) +
                             " (target " + std::to_string(spec.settle_ratio) + ")");
    return world;
}

Gauges cube_gauges(const World& world, const Packing& packing, const CubeTestSpec& spec) {
    return Gauges(world.particles(), {packing.box_lo, packing.box_hi, spec.gauge_length_fraction, spec.slab_fraction,
                                      spec.core_fraction});
}

lab::StressStrainCurve to_stress_strain_curve(const PlatenTestResult& t) {
    lab::StressStrainCurve c;
    for (const CurvePoint& p : t.curve) {
        c.strain.push_back(p.gauge_strain);
        c.stress_pa.push_back(p.stress);
        c.crosshead_strain.push_back(p.platen_strain);
        c.lateral_strain.push_back(p.lateral_strain);
        c.time_s.push_back(p.time);
    }
    return c;
}

void reduce_cube_result(CubeTestResult& r, const CubeTestSpec& spec, const lab::ReductionOptions& options) {
    r.strain_at_peak_platen = r.test.strain_at_peak;
    r.macro = lab::reduce_curve(to_stress_strain_curve(r.test), options);
    r.platen_imbalance = platen_imbalance(r.test);
    if (r.platen_imbalance > spec.imbalance_warning) {
        std::ostringstream w;
        w.precision(3);
        w << "unequal end stresses: top and bottom differ by up to " << 100.0 * r.platen_imbalance
          << " % before the peak (limit " << 100.0 * spec.imbalance_warning
          << " %): a test too fast to be quasi-static, or cracks ahead of the peak; --check-rate tells which";
        r.warnings.push_back(w.str());
    }
}

}  // namespace gradem::exp
