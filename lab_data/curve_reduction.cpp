#include "lab_data/curve_reduction.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>

#include "lab_data/popovics.hpp"

namespace gradem::lab {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

struct LineFit {
    double slope = 0, intercept = 0;
};

// Ordinary least squares y = intercept + slope·x over the samples `idx`; needs 3+ samples
// with spread in x.
std::optional<LineFit> fit_line(const std::vector<double>& x, const std::vector<double>& y,
                                const std::vector<std::size_t>& idx) {
    if (idx.size() < 3) return std::nullopt;
    double mx = 0, my = 0;
    for (auto k : idx) { mx += x[k]; my += y[k]; }
    mx /= static_cast<double>(idx.size());
    my /= static_cast<double>(idx.size());
    double sxx = 0, sxy = 0;
    for (auto k : idx) { sxx += (x[k] - mx) * (x[k] - mx); sxy += (x[k] - mx) * (y[k] - my); }
    if (!(sxx > 0)) return std::nullopt;
    return LineFit{sxy / sxx, my - sxy / sxx * mx};
}

// Ascending-branch samples (index <= peak) whose value v lies in [lo, hi].
std::vector<std::size_t> select(const std::vector<double>& v, std::size_t peak, double lo, double hi) {
    std::vector<std::size_t> idx;
    for (std::size_t k = 0; k <= peak; ++k)
        if (v[k] >= lo && v[k] <= hi) idx.push_back(k);
    return idx;
}

// x at the first ascending-branch crossing of y = target, by linear interpolation.
std::optional<double> first_crossing(const std::vector<double>& y, const std::vector<double>& x, std::size_t peak,
                                     double target, std::size_t* where = nullptr) {
    for (std::size_t k = 0; k <= peak; ++k) {
        if (y[k] < target) continue;
        if (where) *where = k;
        if (k == 0 || y[k] == y[k - 1]) return x[k];
        return x[k - 1] + (target - y[k - 1]) / (y[k] - y[k - 1]) * (x[k] - x[k - 1]);
    }
    return std::nullopt;
}

// Strain at the vertex of σ = c0 + c1·x + c2·x² (x = ε − ε_max) fitted to the contiguous samples
// up to the peak within `fraction` below it; nullopt when the vertex is not a maximum within
// the window or just past it (the true peak may lie between the largest sample and the next).
std::optional<double> parabolic_peak_strain(const StressStrainCurve& c, std::size_t peak, double fraction) {
    const double floor = c.stress_pa[peak] * (1.0 - fraction);
    // Ascending side only: mortar cubes often soften abruptly after the peak (a kink), and
    // samples beyond it would pull a two-sided parabola's vertex towards lower strains.
    std::size_t lo = peak;
    const std::size_t hi = peak;
    while (lo > 0 && c.stress_pa[lo - 1] >= floor) --lo;
    if (hi - lo + 1 < 5) return std::nullopt;
    const double e0 = c.strain[peak];
    double s[5] = {0, 0, 0, 0, 0}, t[3] = {0, 0, 0};  // Σx^k and Σx^k·σ
    double xmin = 0, xmax = 0;
    for (std::size_t k = lo; k <= hi; ++k) {
        const double x = c.strain[k] - e0;
        xmin = std::min(xmin, x);
        xmax = std::max(xmax, x);
        double p = 1;
        for (int j = 0; j < 5; ++j) { s[j] += p; if (j < 3) t[j] += p * c.stress_pa[k]; p *= x; }
    }
    // Normal equations of the 3x3 system, solved by Cramer's rule.
    const double a[3][3] = {{s[0], s[1], s[2]}, {s[1], s[2], s[3]}, {s[2], s[3], s[4]}};
    auto det3 = [](const double m[3][3]) {
        return m[0][0] * (m[1][1] * m[2][2] - m[1][2] * m[2][1]) - m[0][1] * (m[1][0] * m[2][2] - m[1][2] * m[2][0]) +
               m[0][2] * (m[1][0] * m[2][1] - m[1][1] * m[2][0]);
    };
    const double d = det3(a);
    if (!(std::abs(d) > 0)) return std::nullopt;
    double coef[3];
    for (int col = 0; col < 3; ++col) {
        double m[3][3];
        for (int r = 0; r < 3; ++r)
            for (int k = 0; k < 3; ++k) m[r][k] = (k == col) ? t[r] : a[r][k];
        coef[col] = det3(m) / d;
    }
    if (!(coef[2] < 0)) return std::nullopt;
    const double x_star = -coef[1] / (2 * coef[2]);
    if (!(x_star >= xmin && x_star <= xmax + 0.25 * (xmax - xmin))) return std::nullopt;
    return e0 + x_star;
}

std::string fmt(double v) {
    std::ostringstream os;
    os.precision(4);
    os << v;
    return os.str();
}

bool validate(const StressStrainCurve& c, CurveReduction& r) {
    const std::size_t n = c.strain.size();
    auto fail = [&](const std::string& why, std::size_t at) {
        r.status = ReductionStatus::invalid_curve;
        r.message = why;
        r.problem_index = at;
        return false;
    };
    if (c.stress_pa.size() != n) return fail("strain and stress have different lengths", 0);
    if (n < 5) return fail("a curve needs at least 5 samples, got " + std::to_string(n), 0);
    for (const auto* opt : {&c.crosshead_strain, &c.lateral_strain, &c.time_s})
        if (!opt->empty() && opt->size() != n) return fail("an optional channel has a different length", 0);
    for (std::size_t k = 0; k < n; ++k)
        if (!std::isfinite(c.strain[k]) || !std::isfinite(c.stress_pa[k])) return fail("non-finite strain or stress", k);
    return true;
}

// ASTM C469 chord modulus; sets status/message when the window is not reached.
void chord_modulus(const StressStrainCurve& c, const ReductionOptions& o, CurveReduction& r) {
    const std::size_t pk = r.peak_index;
    const double peak = r.peak_stress_pa, e1 = o.chord_lower_strain;
    r.chord_s2_pa = o.chord_upper_fraction * peak;
    std::size_t s2_index = 0;
    const auto crossing2 = first_crossing(c.stress_pa, c.strain, pk, r.chord_s2_pa, &s2_index);
    const auto fit2 = fit_line(c.stress_pa, c.strain,
                               select(c.stress_pa, pk, r.chord_s2_pa - o.window_fraction * peak, r.chord_s2_pa + o.window_fraction * peak));
    r.chord_strain2 = fit2 ? fit2->intercept + fit2->slope * r.chord_s2_pa : crossing2.value_or(kNaN);
    const double max_strain = *std::max_element(c.strain.begin(), c.strain.begin() + static_cast<std::ptrdiff_t>(pk) + 1);
    r.status = ReductionStatus::modulus_window_not_reached;
    r.problem_index = s2_index;
    if (max_strain < e1) {
        r.problem_index = pk;
        r.message = "the ascending branch never reaches the lower chord strain ε1 = " + fmt(e1) +
                    " (largest strain before the peak is " + fmt(max_strain) + "; ASTM C469 chord window not reached)";
        return;
    }
    if (!(r.chord_strain2 > e1)) {
        r.message = "S2 = " + fmt(o.chord_upper_fraction * 100) + " % of peak (" + fmt(r.chord_s2_pa / 1e6) +
                    " MPa) is reached at strain " + fmt(r.chord_strain2) + ", not above ε1 = " + fmt(e1) +
                    ": the ASTM C469 chord window is empty";
        return;
    }
    const auto fit1 = fit_line(c.strain, c.stress_pa, select(c.strain, pk, e1 - o.strain_window, e1 + o.strain_window));
    r.chord_s1_pa = fit1 ? fit1->intercept + fit1->slope * e1 : first_crossing(c.strain, c.stress_pa, pk, e1).value_or(kNaN);
    r.chord_modulus_pa = (r.chord_s2_pa - r.chord_s1_pa) / (r.chord_strain2 - e1);
    if (!(r.chord_modulus_pa > 0) || !std::isfinite(r.chord_modulus_pa)) {
        r.message = "chord modulus is not positive (S1 = " + fmt(r.chord_s1_pa / 1e6) + " MPa, S2 = " + fmt(r.chord_s2_pa / 1e6) + " MPa)";
        r.chord_modulus_pa = kNaN;
        return;
    }
    r.status = ReductionStatus::ok;
}

void secondary_quantities(const StressStrainCurve& c, const ReductionOptions& o, CurveReduction& r) {
    const std::size_t pk = r.peak_index;
    const double peak = r.peak_stress_pa;
    const double t = o.tangent_fraction * peak, w = o.window_fraction * peak;
    const auto tangent = fit_line(c.strain, c.stress_pa, select(c.stress_pa, pk, t - w, t + w));
    r.tangent_modulus_pa = tangent ? tangent->slope : kNaN;
    r.strain_at_peak_crosshead = c.crosshead_strain.empty() ? kNaN : c.crosshead_strain[pk];
    r.stress_rate_pa_per_s = kNaN;
    if (!c.time_s.empty()) {
        const auto rate = fit_line(c.time_s, c.stress_pa, select(c.stress_pa, pk, 0.1 * peak, 0.5 * peak));
        if (rate) r.stress_rate_pa_per_s = rate->slope;
    }
    r.poisson_ratio = kNaN;
    if (!c.lateral_strain.empty() && r.status == ReductionStatus::ok) {
        const auto nu = fit_line(c.strain, c.lateral_strain, select(c.strain, pk, o.chord_lower_strain, r.chord_strain2));
        if (nu) r.poisson_ratio = std::abs(nu->slope);
    }
}

}  // namespace

std::optional<std::string> ReductionOptions::invalid_reason() const {
    auto bad = [](const char* field, double v, const char* rule) {
        return std::string("ReductionOptions::") + field + " = " + fmt(v) + " violates " + rule;
    };
    if (!(chord_upper_fraction > 0 && chord_upper_fraction < 1)) return bad("chord_upper_fraction", chord_upper_fraction, "0 < x < 1");
    if (!(chord_lower_strain >= 0)) return bad("chord_lower_strain", chord_lower_strain, ">= 0");
    if (!(tangent_fraction > 0 && tangent_fraction < 1)) return bad("tangent_fraction", tangent_fraction, "0 < x < 1");
    if (!(window_fraction > 0 && window_fraction < 0.5)) return bad("window_fraction", window_fraction, "0 < x < 0.5");
    if (!(strain_window > 0)) return bad("strain_window", strain_window, "> 0");
    if (!(peak_window_fraction > 0 && peak_window_fraction < 0.5)) return bad("peak_window_fraction", peak_window_fraction, "0 < x < 0.5");
    return std::nullopt;
}

CurveReduction reduce_curve(const StressStrainCurve& c, const ReductionOptions& o) {
    CurveReduction r;
    r.chord_modulus_pa = r.tangent_modulus_pa = r.poisson_ratio = r.strain_at_peak_crosshead = kNaN;
    if (auto why = o.invalid_reason()) { r.message = *why; return r; }
    if (!validate(c, r)) return r;
    r.peak_index = static_cast<std::size_t>(std::max_element(c.stress_pa.begin(), c.stress_pa.end()) - c.stress_pa.begin());
    r.peak_stress_pa = c.stress_pa[r.peak_index];
    if (!(r.peak_stress_pa > 0)) {
        r.message = "no compressive stress (largest stress is " + fmt(r.peak_stress_pa) + " Pa)";
        r.problem_index = r.peak_index;
        return r;
    }
    r.strain_at_peak = parabolic_peak_strain(c, r.peak_index, o.peak_window_fraction).value_or(c.strain[r.peak_index]);
    chord_modulus(c, o, r);
    secondary_quantities(c, o, r);
    if (o.fit_popovics) r.popovics = fit_popovics(c, r.peak_index, r.strain_at_peak, r.chord_modulus_pa);
    return r;
}

}  // namespace gradem::lab
