#pragma once
// gradem-bench --full-cube: what one full-size cube test costs (issue 10 item 5); see
// bench/full_cube_bench.cpp.
#include <cstdint>

#include "experiments/quick_packing.hpp"

namespace gradem::bench {

/// One timed bonded run (gradem_bench.cpp): wall seconds of `steps` steps after a 20-step
/// warm-up with `threads` threads, the automatic time step [s] and the peak RSS [bytes].
struct TimedRun {
    double seconds = 0.0, time_step = 0.0;
    std::int64_t particles = 0, bonds = 0;
    std::size_t peak_rss = 0;
};
TimedRun time_bonded_run(const exp::QuickPacking& packing, int threads, std::int64_t steps);

/// Peak resident set size of this process [bytes] (VmHWM of /proc/self/status; 0 if unknown).
std::size_t peak_rss_bytes();

/// Samples the study's 50 mm cube (pre-blended sand, No. 100 sieve cut, no upper cut,
/// solid fraction 0.60), times `steps` bonded steps on an O(N) packing of that many spheres
/// with the same smallest grain (so the same time step), and prints N, memory, seconds per
/// 1000 steps and the estimated steps and wall time of a whole compression test.
void run_full_cube_bench(int threads, std::int64_t steps, double transits_to_stop, bool json);

}  // namespace gradem::bench
