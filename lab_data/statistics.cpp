#include "lab_data/statistics.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace gradem::lab {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

std::vector<double> finite(const std::vector<double>& v) {
    std::vector<double> out;
    for (double x : v)
        if (std::isfinite(x)) out.push_back(x);
    return out;
}

// Continued fraction for I_x(a, b) (modified Lentz; Press et al., Numerical Recipes §6.4).
double beta_continued_fraction(double a, double b, double x) {
    constexpr int kMaxIterations = 500;
    constexpr double kEps = 1e-15, kTiny = 1e-300;
    const double qab = a + b, qap = a + 1, qam = a - 1;
    double c = 1, d = 1 - qab * x / qap;
    if (std::abs(d) < kTiny) d = kTiny;
    d = 1 / d;
    double h = d;
    for (int m = 1; m <= kMaxIterations; ++m) {
        const int m2 = 2 * m;
        double aa = m * (b - m) * x / ((qam + m2) * (a + m2));
        d = 1 + aa * d;
        if (std::abs(d) < kTiny) d = kTiny;
        c = 1 + aa / c;
        if (std::abs(c) < kTiny) c = kTiny;
        d = 1 / d;
        h *= d * c;
        aa = -(a + m) * (qab + m) * x / ((a + m2) * (qap + m2));
        d = 1 + aa * d;
        if (std::abs(d) < kTiny) d = kTiny;
        c = 1 + aa / c;
        if (std::abs(c) < kTiny) c = kTiny;
        d = 1 / d;
        const double delta = d * c;
        h *= delta;
        if (std::abs(delta - 1) < kEps) break;
    }
    return h;
}

}  // namespace

SampleSummary summarize(const std::vector<double>& values) {
    const std::vector<double> v = finite(values);
    SampleSummary s;
    s.n = v.size();
    if (v.empty()) {
        s.mean = s.std = s.cv = s.min = s.max = kNaN;
        return s;
    }
    double sum = 0;
    for (double x : v) sum += x;
    s.mean = sum / static_cast<double>(s.n);
    double ss = 0;
    for (double x : v) ss += (x - s.mean) * (x - s.mean);
    s.std = s.n > 1 ? std::sqrt(ss / static_cast<double>(s.n - 1)) : kNaN;
    s.cv = s.std / s.mean;
    s.min = *std::min_element(v.begin(), v.end());
    s.max = *std::max_element(v.begin(), v.end());
    return s;
}

double regularized_incomplete_beta(double a, double b, double x) {
    if (!(a > 0 && b > 0) || std::isnan(x)) return kNaN;
    if (x <= 0) return 0.0;
    if (x >= 1) return 1.0;
    const double front = std::exp(std::lgamma(a + b) - std::lgamma(a) - std::lgamma(b) + a * std::log(x) + b * std::log1p(-x));
    if (x < (a + 1) / (a + b + 2)) return front * beta_continued_fraction(a, b, x) / a;
    return 1.0 - front * beta_continued_fraction(b, a, 1 - x) / b;
}

double student_t_two_sided_p(double t, double dof) {
    if (!std::isfinite(t) || !(dof > 0)) return kNaN;
    return regularized_incomplete_beta(dof / 2, 0.5, dof / (dof + t * t));
}

WelchTest welch_t_test(const std::vector<double>& a, const std::vector<double>& b) {
    return welch_t_test_of_summaries(summarize(a), summarize(b));
}

WelchTest welch_t_test_of_summaries(const SampleSummary& s1, const SampleSummary& s2) {
    WelchTest w;
    w.n1 = s1.n;
    w.n2 = s2.n;
    w.mean_difference = s1.mean - s2.mean;
    w.std_error = w.t = w.dof = w.p_value = w.cohens_d = w.hedges_g = kNaN;
    if (s1.n < 2 || s2.n < 2) return w;
    const double n1 = static_cast<double>(s1.n), n2 = static_cast<double>(s2.n);
    const double v1 = s1.std * s1.std / n1, v2 = s2.std * s2.std / n2;
    w.std_error = std::sqrt(v1 + v2);
    if (!(v1 + v2 > 0)) return w;
    w.dof = (v1 + v2) * (v1 + v2) / (v1 * v1 / (n1 - 1) + v2 * v2 / (n2 - 1));
    w.t = w.mean_difference / w.std_error;
    w.p_value = student_t_two_sided_p(w.t, w.dof);
    const double pooled = std::sqrt(((n1 - 1) * s1.std * s1.std + (n2 - 1) * s2.std * s2.std) / (n1 + n2 - 2));
    w.cohens_d = w.mean_difference / pooled;
    w.hedges_g = w.cohens_d * (1 - 3 / (4 * (n1 + n2) - 9));
    return w;
}

double c109_permissible_range(std::size_t cubes) {
    if (cubes == 3) return 0.087;
    if (cubes == 2) return 0.076;
    return kNaN;
}

std::vector<RangeCheck> c109_range_checks(const std::vector<double>& x, std::size_t group_size) {
    std::vector<RangeCheck> checks;
    if (group_size < 2) return checks;
    for (std::size_t start = 0; start + 1 < x.size(); start += group_size) {
        RangeCheck g;
        for (std::size_t k = start; k < std::min(start + group_size, x.size()); ++k) g.members.push_back(k);
        auto range_of = [&](const std::vector<std::size_t>& m, double& mean) {
            double lo = x[m.front()], hi = lo, sum = 0;
            for (auto k : m) { lo = std::min(lo, x[k]); hi = std::max(hi, x[k]); sum += x[k]; }
            mean = sum / static_cast<double>(m.size());
            return (hi - lo) / mean;
        };
        g.range_fraction = range_of(g.members, g.mean);
        g.permissible_fraction = c109_permissible_range(std::min<std::size_t>(g.members.size(), 3));
        g.ok = !(g.range_fraction > g.permissible_fraction);  // groups larger than 3 (NaN limit) pass
        if (!g.ok && g.members.size() == 3) {
            std::size_t worst = g.members.front();
            for (auto k : g.members)
                if (std::abs(x[k] - g.mean) > std::abs(x[worst] - g.mean)) worst = k;
            g.discarded = static_cast<long>(worst);
            std::vector<std::size_t> rest;
            for (auto k : g.members)
                if (k != worst) rest.push_back(k);
            double mean2 = 0;
            g.retest_required = range_of(rest, mean2) > c109_permissible_range(2);
        } else if (!g.ok) {
            g.retest_required = true;
        }
        checks.push_back(g);
    }
    return checks;
}

}  // namespace gradem::lab
