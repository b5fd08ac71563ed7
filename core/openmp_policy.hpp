#pragma once
// Idle OpenMP threads that sleep instead of spinning. libgomp's default lets a thread that
// waits at a barrier spin (GOMP_SPINCOUNT, 3e5 pause iterations, milliseconds) before it
// sleeps; when another process holds the other core (a calibration runs two cube tests at a
// time), the spinning thread burns the time slice the straggler needs, and a 2-thread run
// became ~4x slower. A short spin (GOMP_SPINCOUNT=3000, a few microseconds) keeps the quick
// hand-over between the phases of a step on a quiet machine and then sleeps. Measured on 2
// cores (gradem-bench 2e4, 2 threads, quiet / with `yes` on the other core, M particle-steps/s):
// default spin 9.4-10 / 3.7, passive 8.2 / 5.1, spin 3000 9.3 / 4.5; the default cube test
// 15.6 s (spin), 25.0 s (passive), 15.9 s (spin 3000).
// libgomp reads its environment when it is loaded, before main(), so setting the variable
// in main() is too late: the process re-executes itself once (/proc/self/exe, same argv) with
// the variable set. A user's own OMP_WAIT_POLICY or GOMP_SPINCOUNT is always respected.
#include <cstdlib>

#include <unistd.h>

namespace gradem {

/// First statement of every main(): re-executes the program with GOMP_SPINCOUNT=3000
/// unless the user set OMP_WAIT_POLICY or GOMP_SPINCOUNT. Returns only when no re-execution
/// happened (policy already set, or exec failed: the run then keeps the runtime's default).
inline void use_sleeping_openmp_threads(char** argv) {
#ifdef _OPENMP
    if (std::getenv("OMP_WAIT_POLICY") != nullptr || std::getenv("GOMP_SPINCOUNT") != nullptr) return;
    if (setenv("GOMP_SPINCOUNT", "3000", 1) != 0) return;
    execv("/proc/self/exe", argv);  // returns only on failure
#else
    (void)argv;
#endif
}

}  // namespace gradem
