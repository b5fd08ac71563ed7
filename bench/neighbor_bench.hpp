#pragma once
// Neighbour-search benchmark (gradem-bench --neighbors N): see bench/neighbor_bench.cpp.
#include <cstdint>
#include <vector>

namespace gradem::bench {

/// Times the cell grid and the multi-level grid at size ratios 1, 10 and 50 on N particles
/// for each thread count; prints a table, or JSON rows {"kind": "neighbors", ...} with `json`.
void run_neighbor_bench(std::int64_t n, const std::vector<int>& threads, int repeat, bool json);

}  // namespace gradem::bench
