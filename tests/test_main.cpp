// The one Catch2 main for every gradem test executable.
#define CATCH_CONFIG_MAIN
#include <catch2/catch.hpp>
