#pragma once
// parallel_for over independent jobs on `workers` std::threads, each with one OpenMP thread
// (two multi-threaded DEM runs on two cores would oversubscribe them; one run per core does
// not). Jobs are taken in index order; results must not depend on which thread ran a job.
// The first exception thrown by a job is rethrown after every started job has finished.
#ifdef _OPENMP
#include <omp.h>
#endif

#include <algorithm>
#include <atomic>
#include <cstddef>
#include <exception>
#include <functional>
#include <mutex>
#include <thread>
#include <vector>

namespace gradem::cal {

inline void parallel_for(std::size_t jobs, int workers, const std::function<void(std::size_t)>& job) {
    std::atomic<std::size_t> next{0};
    std::exception_ptr error;
    std::mutex mutex;
    auto work = [&] {
#ifdef _OPENMP
        omp_set_num_threads(1);
#endif
        for (std::size_t k; (k = next++) < jobs;) {
            {
                const std::lock_guard lock(mutex);
                if (error) return;
            }
            try {
                job(k);
            } catch (...) {
                const std::lock_guard lock(mutex);
                if (!error) error = std::current_exception();
            }
        }
    };
    const std::size_t n = std::min<std::size_t>(jobs, static_cast<std::size_t>(std::max(1, workers)));
    std::vector<std::thread> threads;
    for (std::size_t t = 0; t < n; ++t) threads.emplace_back(work);
    for (auto& t : threads) t.join();
    if (error) std::rethrow_exception(error);
}

}  // namespace gradem::cal
