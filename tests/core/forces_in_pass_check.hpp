#pragma once
// SimParams::forces_in_pass must be unobservable: what a run reads of its forces (the particles'
// sums, the pair slots as read, the unbalanced-force ratio), as raw bits, is the same whether a
// pass adds the pairs to the particles itself or writes every slot for the gather, on any
// thread count. Shared by the parallel bond's and the flat joint's tests.
#include <catch2/catch.hpp>

#include <cstdint>
#include <cstring>
#include <functional>
#include <vector>

#include "core/world.hpp"

namespace gradem::test {

inline std::uint64_t raw_bits(double x) {
    std::uint64_t u;
    std::memcpy(&u, &x, sizeof u);
    return u;
}

inline void append_bits(std::vector<std::uint64_t>& out, const Vec3& v) {
    out.push_back(raw_bits(v.x));
    out.push_back(raw_bits(v.y));
    out.push_back(raw_bits(v.z));
}

/// What a run reads of its forces, as raw bits, and how many pair-steps went straight into the
/// particles; `other`: anything else the run compares (its crack log, ...).
struct ForcesSeen {
    std::vector<std::uint64_t> particles, slots, other;
    std::uint64_t ratio = 0;
    std::int64_t into_particles = 0;
};

inline ForcesSeen forces_seen(const World& world) {
    ForcesSeen f;
    for (std::size_t i = 0; i < world.particles().size(); ++i) {
        append_bits(f.particles, world.particles().force[i]);
        append_bits(f.particles, world.particles().torque[i]);
    }
    f.ratio = raw_bits(world.unbalanced_force_ratio());
    for (const PairOutput& o : world.pair_outputs()) {
        append_bits(f.slots, o.force_j);
        append_bits(f.slots, o.torque_j);
        append_bits(f.slots, o.torque_i);
    }
    f.into_particles = world.profile().pair_steps_into_particles;
    return f;
}

/// `run(threads, forces_in_pass)` with every slot written on 1 and 2 threads and into the
/// particles on 1, 2 and 3: the same bits throughout; the path under test ran, on 2 and 3
/// threads beside the slots; the slots hold forces, not a zeroed array (more than
/// `nonzero_share` of their components nonzero).
inline void check_forces_in_pass(const std::function<ForcesSeen(int threads, bool forces_in_pass)>& run,
                                 double nonzero_share = 0.5) {
    const ForcesSeen slots_one = run(1, false), slots_two = run(2, false);
    REQUIRE(slots_one.into_particles == 0);
    REQUIRE(slots_two.into_particles == 0);
    const ForcesSeen one = run(1, true);
    REQUIRE(one.into_particles > 0);
    for (int threads : {1, 2, 3}) {
        INFO("threads " << threads);
        const ForcesSeen in_pass = threads == 1 ? one : run(threads, true);
        REQUIRE(in_pass.into_particles > 0);                                        // the path under test ran ...
        if (threads > 1) CHECK(in_pass.into_particles < one.into_particles);        // ... beside the slots
        for (const ForcesSeen* other : {&slots_one, &slots_two}) {
            CHECK(in_pass.particles == other->particles);
            CHECK(in_pass.slots == other->slots);
            CHECK(in_pass.ratio == other->ratio);
            CHECK(in_pass.other == other->other);
        }
    }
    std::size_t nonzero = 0;
    for (std::uint64_t b : one.slots) nonzero += (b << 1) != 0;
    CHECK(static_cast<double>(nonzero) > nonzero_share * static_cast<double>(one.slots.size()));
}

}  // namespace gradem::test
