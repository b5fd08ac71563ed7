// The one Catch2 main for every gradem test executable. Idle OpenMP threads sleep instead of
// spinning (core/openmp_policy.hpp), as in the gradem and gradem-bench executables.
#define CATCH_CONFIG_RUNNER
#include <catch2/catch.hpp>

#include "core/openmp_policy.hpp"

int main(int argc, char** argv) {
    gradem::use_sleeping_openmp_threads(argv);
    return Catch::Session().run(argc, argv);
}
