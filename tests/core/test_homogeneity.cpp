// Homogeneity of the bonded-particle model (docs/model.md "Homogeneity"; docs/calibration.md "Homogeneity"),
// on a small bonded packing pulled apart by its top layer (bottom layer held):
// (a) moduli x 4 with density x 4 (so the dynamics are unchanged) -> every force x 4;
// (b) strengths x 2, pulled twice as far in the same steps -> break loads x 2, same break step.
#include <catch2/catch.hpp>
#include <algorithm>
#include <cmath>

#include "core_fixtures.hpp"

using namespace gradem;
using namespace gradem::test;

namespace {

struct Response {
    std::vector<double> pull_force;  // force the top layer needs [N]
    double first_break_force = 0.0;
    std::int64_t first_break_step = -1;
    std::size_t breaks = 0;
};

Response pull(double modulus_scale, double strength_scale, double speed_scale) {
    const int n = 5;
    ParticleSet p = jittered_cluster(n, 1.0e-3, 21);
    p.scale_density(modulus_scale);
    ContactParams contact;
    contact.effective_modulus = 1.0e9 * modulus_scale;
    contact.friction = 0.5;
    World world(std::move(p), contact, SimParams{});
    BondParams bp;
    bp.effective_modulus = 1.0e9 * modulus_scale;
    bp.tensile_strength_mean = 1.5e6 * strength_scale;
    bp.cohesion_mean = 3.0e6 * strength_scale;
    bp.tensile_strength_std = 0.3e6 * strength_scale;
    bp.cohesion_std = 0.6e6 * strength_scale;
    world.install_bonds(bp, 0.5e-3);
    std::vector<std::int32_t> top;
    ParticleSet& q = world.edit_particles();
    for (std::int32_t i = 0; i < static_cast<std::int32_t>(q.size()); ++i) {
        const double z = q.position[static_cast<std::size_t>(i)].z;
        if (z < 0.5e-3) q.flags[static_cast<std::size_t>(i)] = kFixedVelocity | kFixedSpin;
        if (z > (2 * n - 2.5) * 1.0e-3) {
            q.flags[static_cast<std::size_t>(i)] = kFixedVelocity | kFixedSpin;
            top.push_back(i);
        }
    }
    world.set_time_step(2.0e-7);  // fixed: the same steps in every variant
    for (std::int32_t i : top) world.set_particle_motion(i, {0, 0, 0.02 * speed_scale}, {});
    Response r;
    for (int s = 0; s < 5000; ++s) {
        world.step();
        double f = 0.0;
        for (std::int32_t i : top) f -= world.particles().force[static_cast<std::size_t>(i)].z;
        r.pull_force.push_back(f);
        if (r.first_break_step < 0 && !world.break_events().empty()) {
            r.first_break_step = world.step_count();
            r.first_break_force = f;
        }
    }
    r.breaks = world.break_events().size();
    return r;
}

double peak(const std::vector<double>& v) { return *std::max_element(v.begin(), v.end()); }

}  // namespace

TEST_CASE("moduli x 4 (density and strengths x 4): forces x 4, same breaks",
          "[core][homogeneity]") {
    const Response base = pull(1.0, 1.0, 1.0);
    const Response stiff = pull(4.0, 4.0, 1.0);
    REQUIRE(base.breaks > 10);
    CHECK(stiff.breaks == base.breaks);
    CHECK(stiff.first_break_step == base.first_break_step);
    for (std::size_t s = 0; s < base.pull_force.size(); s += 250)
        CHECK(stiff.pull_force[s] == Approx(4.0 * base.pull_force[s]).epsilon(1e-9).margin(1e-12));
}

TEST_CASE("strengths x 2, pulled twice as far: break loads x 2", "[core][homogeneity]") {
    const Response base = pull(1.0, 1.0, 1.0);
    const Response strong = pull(1.0, 2.0, 2.0);
    REQUIRE(base.first_break_step > 0);
    // Same strain history scaled by 2: the first bond breaks on the same step at twice the load;
    // geometric non-linearity of the ~1e-3 strains is the only difference.
    CHECK(strong.first_break_step == base.first_break_step);
    CHECK(strong.first_break_force == Approx(2.0 * base.first_break_force).epsilon(0.01));
    CHECK(peak(strong.pull_force) == Approx(2.0 * peak(base.pull_force)).epsilon(0.02));
}
