// Linear contact: stiffness from the deformability rule and the collision time of two spheres.
#include <catch2/catch.hpp>

#include "core/contact_law.hpp"
#include "core_fixtures.hpp"

using namespace gradem;
using namespace gradem::test;

TEST_CASE("normal stiffness follows k_n = pi min(R)^2 E* / (R_A + R_B)", "[core][contact]") {
    const double ra = 1.0e-3, rb = 0.6e-3, overlap = 2.0e-6, modulus = 2.0e9;
    World world(sphere_pair(ra, rb, -overlap), frictionless(modulus), undamped());
    world.set_time_step(1e-9);
    world.step();
    const ParticleSet& p = world.particles();
    const double now_overlap = ra + rb - norm(p.position[1] - p.position[0]);
    const double kn = kPi * rb * rb * modulus / (ra + rb);
    CHECK(contact_normal_stiffness(modulus, ra, rb) == Approx(kn).epsilon(1e-15));
    CHECK(p.force[1].x == Approx(kn * now_overlap).epsilon(1e-9));
    CHECK(p.force[0].x == Approx(-kn * now_overlap).epsilon(1e-9));
    CHECK(wall_normal_stiffness(modulus, ra) == Approx(kPi * ra * modulus));
}

TEST_CASE("head-on collision lasts half the period 2 pi sqrt(m_eff / k_n)", "[core][contact]") {
    const double ra = 1.0e-3, rb = 0.7e-3, modulus = 1.0e9, speed = 0.01;
    World world(sphere_pair(ra, rb, 1.0e-7), frictionless(modulus), undamped());
    const ParticleSet& p0 = world.particles();
    const double m_eff = p0.mass[0] * p0.mass[1] / (p0.mass[0] + p0.mass[1]);
    const double kn = contact_normal_stiffness(modulus, ra, rb);
    const double period = 2.0 * kPi * std::sqrt(m_eff / kn);
    const double dt = period / 2000.0;
    world.set_time_step(dt);
    world.set_particle_motion(0, {speed, 0, 0}, {});
    world.set_particle_motion(1, {-speed, 0, 0}, {});
    int in_contact = 0;
    for (int s = 0; s < 4000; ++s) {
        world.step();
        const ParticleSet& p = world.particles();
        if (norm(p.position[1] - p.position[0]) < ra + rb) ++in_contact;
    }
    CHECK(in_contact * dt == Approx(0.5 * period).epsilon(0.01));
    // Elastic and undamped: the spheres leave with the relative speed they came with.
    const ParticleSet& p = world.particles();
    CHECK((p.velocity[1].x - p.velocity[0].x) == Approx(2.0 * speed).epsilon(1e-3));
}

TEST_CASE("Coulomb slip caps the shear force at mu F_n", "[core][contact]") {
    LinearContactResult r = linear_contact(1.0e4, 0.5e4, 0.5, -1.0e-5, {}, {0, 1.0e-4, 0});
    CHECK(r.sliding);
    CHECK(norm(r.shear_force) == Approx(0.5 * r.normal_force).epsilon(1e-12));
    CHECK(r.shear_force.y < 0.0);  // opposes the motion of B
    CHECK(r.slip_energy > 0.0);
    const LinearContactResult stick = linear_contact(1.0e4, 0.5e4, 0.5, -1.0e-5, {}, {0, 1.0e-7, 0});
    CHECK_FALSE(stick.sliding);
    CHECK(stick.shear_force.y == Approx(-0.5e4 * 1.0e-7));
    const LinearContactResult open = linear_contact(1.0e4, 0.5e4, 0.5, 1.0e-9, {0, 3, 0}, {});
    CHECK(open.normal_force == 0.0);
    CHECK(norm(open.shear_force) == 0.0);
}
