#pragma once
// gradem-bench --genesis N1,N2,...: genesis rows (see genesis_bench.cpp).
#include <cstdint>
#include <vector>

#include "lab_data/gradation.hpp"

namespace gradem::bench {

/// The study's Table 2 gradation of the pre-blended sand (as lab_data/datasets/study).
lab::GradationCurve pre_blended_curve();

/// Runs genesis of the study's pre-blended sand at about each grain count and prints a table
/// row (or a JSON row {"kind": "genesis", ...} with `json`) per size.
void run_genesis_bench(const std::vector<std::int64_t>& sizes, bool json);

}  // namespace gradem::bench
