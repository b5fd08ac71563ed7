#include "lab_data/gradation.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>
#include <sstream>
#include <stdexcept>

namespace gradem::lab {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr double kNo4 = 4.75e-3;    // m, sand/gravel boundary (ASTM D2487)
constexpr double kNo200 = 75e-6;    // m, fines boundary (ASTM D2487)
// ASTM C125 fineness-modulus sieves [m].
constexpr double kFinenessSieves[] = {150e-6, 300e-6, 600e-6, 1.18e-3, 2.36e-3, 4.75e-3,
                                      9.5e-3, 19e-3,  37.5e-3, 75e-3,  150e-3};

std::string mm(double size_m) {
    std::ostringstream os;
    os << size_m * 1e3 << " mm";
    return os.str();
}

std::string uscs_coarse(const GradationIndices& g, std::string& name) {
    const bool sand = g.sand_fraction >= g.gravel_fraction;
    const char* letter = sand ? "S" : "G";
    const double cu_min = sand ? 6.0 : 4.0;
    const bool well = g.cu >= cu_min && g.cc >= 1.0 && g.cc <= 3.0;
    const std::string base = std::string(letter) + (well ? "W" : "P");
    const std::string kind = sand ? "sand" : "gravel";
    if (g.fines_fraction < 0.05) {
        name = std::string(well ? "well" : "poorly") + " graded " + kind;
        return base;
    }
    if (g.fines_fraction <= 0.12) {
        name = std::string(well ? "well" : "poorly") + " graded " + kind + " with silt or clay (plasticity needed)";
        return base + "-" + letter + "M or " + base + "-" + letter + "C";
    }
    name = "silty or clayey " + kind + " (plasticity needed)";
    return std::string(letter) + "M or " + letter + "C";
}

}  // namespace

GradationCurve GradationCurve::from_points(std::vector<double> size_m, std::vector<double> passing,
                                           std::vector<std::string> designation) {
    if (designation.empty()) designation.assign(size_m.size(), "");
    if (passing.size() != size_m.size() || designation.size() != size_m.size())
        throw std::invalid_argument("GradationCurve: sizes, passing and designations differ in length");
    std::vector<std::size_t> order(size_m.size());
    std::iota(order.begin(), order.end(), 0);
    std::sort(order.begin(), order.end(), [&](auto a, auto b) { return size_m[a] < size_m[b]; });
    GradationCurve c;
    for (auto k : order) {
        c.size_m.push_back(size_m[k]);
        c.passing.push_back(passing[k]);
        c.designation.push_back(designation[k]);
    }
    if (auto why = c.invalid_reason()) throw std::invalid_argument(*why);
    return c;
}

std::optional<std::string> GradationCurve::invalid_reason() const {
    if (size_m.size() < 2) return "GradationCurve needs at least 2 sieves, has " + std::to_string(size_m.size());
    if (passing.size() != size_m.size()) return std::string("GradationCurve::passing has a different length than size_m");
    for (std::size_t i = 0; i < size_m.size(); ++i) {
        if (!(size_m[i] > 0) || !std::isfinite(size_m[i])) return "GradationCurve::size_m[" + std::to_string(i) + "] violates > 0";
        if (!(passing[i] >= 0 && passing[i] <= 1)) return "GradationCurve::passing[" + std::to_string(i) + "] violates 0 <= p <= 1";
        if (i == 0) continue;
        if (!(size_m[i] > size_m[i - 1])) return "GradationCurve::size_m must be strictly ascending (repeated sieve " + mm(size_m[i]) + ")";
        if (passing[i] < passing[i - 1]) return "GradationCurve::passing must not decrease with size (at " + mm(size_m[i]) + ")";
    }
    return std::nullopt;
}

double GradationCurve::passing_fraction(double d) const {
    if (!(d > 0)) return 0.0;
    if (d <= size_m.front()) return passing.front();
    if (d >= size_m.back()) return passing.back();
    const auto hi = static_cast<std::size_t>(std::upper_bound(size_m.begin(), size_m.end(), d) - size_m.begin());
    const std::size_t lo = hi - 1;
    const double t = std::log(d / size_m[lo]) / std::log(size_m[hi] / size_m[lo]);
    return passing[lo] + t * (passing[hi] - passing[lo]);
}

double GradationCurve::size_at_passing(double fraction) const {
    if (!(fraction >= 0 && fraction <= 1)) return kNaN;
    const auto it = std::lower_bound(passing.begin(), passing.end(), fraction);
    if (it == passing.end()) return kNaN;
    const auto i = static_cast<std::size_t>(it - passing.begin());
    if (i == 0) return passing.front() == fraction ? size_m.front() : kNaN;
    const double t = (fraction - passing[i - 1]) / (passing[i] - passing[i - 1]);
    return size_m[i - 1] * std::pow(size_m[i] / size_m[i - 1], t);
}

std::optional<std::size_t> GradationCurve::find_sieve(double d, double tol) const {
    for (std::size_t i = 0; i < size_m.size(); ++i)
        if (std::abs(size_m[i] - d) <= tol * d) return i;
    return std::nullopt;
}

GradationIndices analyse_gradation(const GradationCurve& c) {
    GradationIndices g;
    g.d10_m = c.size_at_passing(0.10);
    g.d30_m = c.size_at_passing(0.30);
    g.d50_m = c.size_at_passing(0.50);
    g.d60_m = c.size_at_passing(0.60);
    if (std::isnan(g.d10_m)) g.notes.push_back("D10 lies below the finest sieve: Cu and Cc undetermined");
    g.cu = g.d60_m / g.d10_m;
    g.cc = g.d30_m * g.d30_m / (g.d10_m * g.d60_m);

    auto passing_at = [&](double d, const char* what) {
        if (c.find_sieve(d)) return c.passing[*c.find_sieve(d)];
        if (d < c.size_m.front() && c.passing.front() > 0)
            g.notes.push_back(std::string(what) + ": " + mm(d) + " is below the finest sieve; its passing taken as the finest sieve's");
        else if (d > c.size_m.front() && d < c.size_m.back())
            g.notes.push_back(std::string(what) + ": no " + mm(d) + " sieve; passing interpolated on the log-size curve");
        return c.passing_fraction(d);
    };
    g.fines_fraction = passing_at(kNo200, "fines");
    g.gravel_fraction = 1.0 - passing_at(kNo4, "gravel");
    g.sand_fraction = 1.0 - g.gravel_fraction - g.fines_fraction;

    double retained_sum = 0;
    for (double d : kFinenessSieves) retained_sum += 100.0 * (1.0 - passing_at(d, "fineness modulus"));
    g.fineness_modulus = retained_sum / 100.0;

    if (g.fines_fraction >= 0.5) {
        g.uscs = "fine-grained";
        g.uscs_name = "fine-grained soil (50 % or more passing 75 µm): needs Atterberg limits";
    } else if (std::isnan(g.cu) || std::isnan(g.cc)) {
        g.uscs = "undetermined";
        g.uscs_name = "Cu/Cc undetermined";
    } else {
        g.uscs = uscs_coarse(g, g.uscs_name);
    }
    return g;
}

}  // namespace gradem::lab
