#include "calibrate/study/study_statistics.hpp"

#include <algorithm>
#include <cmath>

#include "lab_data/statistics.hpp"

namespace gradem::cal {

double student_t_975(double dof) {
    if (!(dof > 0.0)) return std::nan("");
    double lo = 0.0, hi = 1000.0;  // p(t) = two-sided tail; find p = 0.05
    for (int k = 0; k < 200; ++k) {
        const double mid = 0.5 * (lo + hi);
        (lab::student_t_two_sided_p(mid, dof) > 0.05 ? lo : hi) = mid;
    }
    return 0.5 * (lo + hi);
}

Sample sample_of(const std::vector<double>& values) {
    const lab::SampleSummary s = lab::summarize(values);
    return {s.mean, s.std, static_cast<int>(s.n)};
}

// The interval is the estimate ± t_{0.975, dof} × the standard error of Welch's test (its
// Welch-Satterthwaite degrees of freedom); a difference without spread is its own interval.
Interval welch_interval(const Sample& a, const Sample& b) {
    lab::SampleSummary sa, sb;
    sa.n = static_cast<std::size_t>(std::max(a.n, 0)), sa.mean = a.mean, sa.std = a.std;
    sb.n = static_cast<std::size_t>(std::max(b.n, 0)), sb.mean = b.mean, sb.std = b.std;
    const lab::WelchTest w = lab::welch_t_test_of_summaries(sa, sb);
    Interval out{w.mean_difference, std::nan(""), std::nan("")};
    if (a.n < 2 || b.n < 2) return out;
    if (!(w.std_error > 0.0)) {
        out.low = out.high = out.estimate;
        return out;
    }
    const double t = student_t_975(w.dof);
    out.low = out.estimate - t * w.std_error;
    out.high = out.estimate + t * w.std_error;
    return out;
}

double compressive_to_tensile_ratio(double peak_compression_pa, const Sample& tensile_strength_pa) {
    if (!(peak_compression_pa > 0.0) || tensile_strength_pa.n < 1 || !(tensile_strength_pa.mean > 0.0)) return std::nan("");
    return peak_compression_pa / tensile_strength_pa.mean;
}

}  // namespace gradem::cal
