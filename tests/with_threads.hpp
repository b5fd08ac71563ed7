#pragma once
// The determinism tests run the same thing with several OpenMP thread counts.
#include "core/parallel.hpp"

namespace gradem::test {

/// `run()` on `threads` OpenMP threads (no-op without OpenMP); the previous count is restored
/// afterwards, also when `run` throws.
template <typename Run>
auto with_threads(int threads, Run&& run) {
#ifdef _OPENMP
    struct Restore {
        int before = thread_count();
        ~Restore() { omp_set_num_threads(before); }
    } restore;
    omp_set_num_threads(threads);
#else
    (void)threads;
#endif
    return run();
}

}  // namespace gradem::test
