#pragma once
// The statistics of the studies' answers: seed samples, the 95 % Student-t quantile and the
// Welch interval of a difference of means (the test itself is lab::welch_t_test, the lab
// statistics' own, so lab and simulation are compared by one definition).
#include <vector>

namespace gradem::cal {

/// 95 % two-sided Student-t quantile t_{0.975, dof} (bisection on the exact CDF).
double student_t_975(double dof);

/// Mean, sample standard deviation and count of the finite values.
struct Sample {
    double mean = 0.0, std = 0.0;
    int n = 0;
};
Sample sample_of(const std::vector<double>& values);

/// Welch interval of mean(a) - mean(b): estimate and 95 % bounds (NaN when n < 2 on a side).
struct Interval {
    double estimate = 0.0, low = 0.0, high = 0.0;
};
Interval welch_interval(const Sample& a, const Sample& b);

/// σc/σt: a mean peak compressive stress over the mean of the successful tensile strengths
/// (NaN when either is missing or not positive).
double compressive_to_tensile_ratio(double peak_compression_pa, const Sample& tensile_strength_pa);

}  // namespace gradem::cal
