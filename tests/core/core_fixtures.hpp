#pragma once
// Small hand-built particle sets for the core tests.
#include <cmath>
#include <memory>

#include "core/random.hpp"
#include "core/world.hpp"

namespace gradem::test {

inline constexpr double kDensity = 2650.0;  // quartz [kg/m^3]

/// Two spheres: A at the origin, B on +x at centre distance ra + rb + gap.
inline ParticleSet sphere_pair(double ra, double rb, double gap) {
    ParticleSet p;
    p.add({0, 0, 0}, ra, kDensity);
    p.add({ra + rb + gap, 0, 0}, rb, kDensity);
    return p;
}

/// n x n x n simple-cubic lattice of spheres of radius r, centre spacing 2r + gap.
inline ParticleSet simple_cubic(int n, double r, double gap) {
    ParticleSet p;
    const double a = 2.0 * r + gap;
    for (int k = 0; k < n; ++k)
        for (int j = 0; j < n; ++j)
            for (int i = 0; i < n; ++i) p.add({i * a, j * a, k * a}, r, kDensity);
    return p;
}

/// A compact polydisperse cluster: simple-cubic sites 2 r_max apart jittered by up to
/// 0.02 r_max, radii in [0.8, 0.96] r_max: nobody overlaps, lattice neighbours are within
/// 0.44 r_max. Deterministic in `seed`.
inline ParticleSet jittered_cluster(int n, double r_max, std::uint64_t seed) {
    ParticleSet p;
    SplitMix64 rng(seed);
    const double a = 2.0 * r_max;
    for (int k = 0; k < n; ++k)
        for (int j = 0; j < n; ++j)
            for (int i = 0; i < n; ++i) {
                const Vec3 jitter{rng.uniform(-0.02, 0.02), rng.uniform(-0.02, 0.02),
                                  rng.uniform(-0.02, 0.02)};
                p.add(Vec3{i * a, j * a, k * a} + r_max * jitter, r_max * rng.uniform(0.8, 0.96),
                      kDensity);
            }
    return p;
}

inline SimParams undamped() {
    SimParams s;
    s.local_damping = 0.0;
    return s;
}

inline ContactParams frictionless(double modulus) {
    ContactParams c;
    c.effective_modulus = modulus;
    c.friction = 0.0;
    return c;
}

}  // namespace gradem::test
