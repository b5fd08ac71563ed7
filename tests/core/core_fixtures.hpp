#pragma once
// Small hand-built particle sets and the shared "bonded cluster between platens" scene pieces
// for the core tests.
#include <algorithm>
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

// The "bonded cluster between platens" scenes (bond families, energy ledger, flat joints, pair
// pass, soft bonds, neighbour search, determinism): grains with E* = 1 GPa and the default
// grain-grain friction 0.5; the cluster, its bonds, the platen speed and friction, and the run
// length are each scene's own.
inline ContactParams platen_scene_contact() {
    ContactParams contact;
    contact.effective_modulus = 1.0e9;
    contact.friction = 0.5;
    return contact;
}

// The platens of those scenes: a fixed bottom platen 1 mm below
// the lowest particle centre (normal +z) and a top platen 1 mm above the highest (normal -z)
// moving down at `top_speed` [m/s]; both with E*_w = 1 GPa and friction `wall_friction`.
// Added in that order (bottom, top), as every scene's pinned numbers assume.
inline void add_platens(World& world, double top_speed, double wall_friction = 0.0) {
    double lo = 1e9, hi = -1e9;
    for (const Vec3& x : world.particles().position) lo = std::min(lo, x.z), hi = std::max(hi, x.z);
    Wall bottom{"bottom", {0, 0, 1}, {0, 0, lo - 1.0e-3}, {0, 0, 0}, {}, {}, {}};
    Wall top{"top", {0, 0, -1}, {0, 0, hi + 1.0e-3}, {0, 0, -top_speed}, {}, {}, {}};
    bottom.contact.effective_modulus = top.contact.effective_modulus = 1.0e9;
    bottom.contact.friction = top.contact.friction = wall_friction;
    world.add_wall(bottom);
    world.add_wall(top);
}

}  // namespace gradem::test
