#pragma once
// gradem-bench --full-cube: what one full-size cube test costs; see
// bench/full_cube_bench.cpp.
#include <cstdint>

#include "experiments/specimen/quick_packing.hpp"

namespace gradem::bench {

/// One timed bonded run (gradem_bench.cpp): wall seconds of `steps` steps after a 20-step
/// warm-up with `threads` threads, the automatic time step [s] and the peak RSS [bytes].
struct TimedRun {
    double seconds = 0.0, time_step = 0.0;
    std::int64_t particles = 0, bonds = 0;
    std::size_t peak_rss = 0, world_bytes = 0;  ///< process peak; the World's arrays
};
TimedRun time_bonded_run(const exp::QuickPacking& packing, int threads, std::int64_t steps);

/// Peak resident set size of this process [bytes] (VmHWM of /proc/self/status; 0 if unknown).
std::size_t peak_rss_bytes();

struct FullCubeOptions {
    double min_diameter = 0.149e-3;   ///< lower cut of the gradation [m] (No. 100 sieve)
    std::int64_t timed = 200000;      ///< spheres of the timed packing (the cost is extrapolated to N)
    std::int64_t steps = 100;         ///< timed steps
    int threads = 2;
    double transits_to_stop = 160.0;  ///< wave transits from the start of a cube test to its stop
    double time_step = 0.0;           ///< [s] of the real specimen; 0: the timed World's
    bool json = false;
};

/// Samples the study's 50 mm cube (pre-blended sand cut at `min_diameter`, no upper cut,
/// solid fraction 0.60) for its grain count N, times bonded steps on an O(N) packing of
/// `timed` spheres with the same smallest grain (so the same time step), and prints N, the
/// memory and seconds per 1000 steps scaled to N (both linear in N: bench/README.md), and the
/// estimated steps and wall time of a whole compression test.
void run_full_cube_bench(const FullCubeOptions& o);

}  // namespace gradem::bench
