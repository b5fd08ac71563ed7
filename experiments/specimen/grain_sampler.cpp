#include "experiments/specimen/grain_sampler.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <stdexcept>

#include "core/random.hpp"
#include "core/vec3.hpp"

namespace gradem::exp {

std::optional<std::string> SizeRule::invalid_reason() const {
    std::ostringstream out;
    if (!(min_diameter >= 0.0 && std::isfinite(min_diameter)))
        out << "size_rule.min_diameter = " << min_diameter << " violates >= 0";
    else if (!(max_diameter >= 0.0 && std::isfinite(max_diameter)))
        out << "size_rule.max_diameter = " << max_diameter << " violates >= 0";
    else if (max_diameter > 0.0 && max_diameter <= min_diameter)
        out << "size_rule.max_diameter = " << max_diameter << " violates > min_diameter ("
            << min_diameter << ")";
    else if (!(scale > 0.0 && std::isfinite(scale)))
        out << "size_rule.scale = " << scale << " violates > 0";
    if (out.str().empty()) return std::nullopt;
    return out.str();
}

namespace {

double sphere_volume(double d) { return kPi / 6.0 * d * d * d; }

// Draws d in [a, b] with number density ∝ d^-4 (uniform mass per log size), by inversion.
double draw_diameter(double a, double b, SplitMix64& rng) {
    const double ia = 1.0 / (a * a * a), ib = 1.0 / (b * b * b);
    return 1.0 / std::cbrt(ia - rng.uniform() * (ia - ib));
}

// Kept size range [lo, hi] (unscaled) and the interval boundaries inside it.
std::vector<double> interval_bounds(const lab::GradationCurve& curve, double lo, double hi) {
    std::vector<double> b{lo};
    for (double s : curve.size_m)
        if (s > lo && s < hi) b.push_back(s);
    b.push_back(hi);
    return b;
}

void fill_interval(double a, double b, double volume, SplitMix64& rng, std::vector<double>& out) {
    double filled = 0.0;
    while (filled < volume) {
        const double d = draw_diameter(a, b, rng);
        const double v = sphere_volume(d);
        if (filled + 0.5 * v > volume) break;  // stop nearest to the target volume
        out.push_back(d);
        filled += v;
    }
}

void compare_with_curve(const lab::GradationCurve& curve, double lo, double hi, GrainSample& s,
                        const std::vector<double>& unscaled) {
    const double p_lo = curve.passing_fraction(lo), kept = curve.passing_fraction(hi) - p_lo;
    double total = 0.0;
    for (double d : unscaled) total += sphere_volume(d);
    for (double sieve : curve.size_m) {
        if (sieve <= lo || sieve >= hi) continue;
        double finer = 0.0;
        for (double d : unscaled)
            if (d <= sieve) finer += sphere_volume(d);
        s.sieve_sizes.push_back(sieve);
        s.target_passing.push_back((curve.passing_fraction(sieve) - p_lo) / kept);
        s.achieved_passing.push_back(total > 0 ? finer / total : 0.0);
        s.max_deviation = std::max(s.max_deviation, std::fabs(s.achieved_passing.back() - s.target_passing.back()));
    }
    std::vector<double> sorted = unscaled;
    std::sort(sorted.begin(), sorted.end());
    double acc = 0.0;
    for (double d : sorted) {
        acc += sphere_volume(d);
        if (acc >= 0.5 * total) {
            s.d50 = d;
            break;
        }
    }
}

}  // namespace

GrainSample sample_grains(const lab::GradationCurve& curve, const SizeRule& rule,
                          double solid_volume, std::uint64_t seed) {
    if (auto why = rule.invalid_reason()) throw std::invalid_argument(*why);
    if (auto why = curve.invalid_reason()) throw std::invalid_argument("gradation: " + *why);
    if (!(solid_volume > 0.0)) throw std::invalid_argument("sample_grains: solid volume must be > 0");
    const double finest = curve.size_m.front(), coarsest = curve.size_m.back();
    const double lo = std::max(rule.min_diameter, finest);
    double hi = rule.max_diameter > 0.0 ? std::min(rule.max_diameter, coarsest) : coarsest;
    // The curve is 100 % passing from some sieve up: nothing to keep above it.
    for (std::size_t k = 0; k < curve.size_m.size(); ++k)
        if (curve.passing[k] >= 1.0) {
            hi = std::min(hi, curve.size_m[k]);
            break;
        }
    const double kept = curve.passing_fraction(hi) - curve.passing_fraction(lo);
    if (!(hi > lo) || !(kept > 1e-9)) {
        std::ostringstream out;
        out << "gradation cannot be sampled: the size rule keeps " << lo * 1e3 << " mm .. "
            << hi * 1e3 << " mm, which holds " << 100.0 * std::max(0.0, kept) << " % of the mass";
        throw std::invalid_argument(out.str());
    }
    GrainSample s;
    s.removed_fine_fraction = curve.passing_fraction(lo);
    s.removed_coarse_fraction = 1.0 - curve.passing_fraction(hi);
    SplitMix64 rng(seed);
    const double unscaled_volume = solid_volume / (rule.scale * rule.scale * rule.scale);
    std::vector<double> unscaled;
    const std::vector<double> b = interval_bounds(curve, lo, hi);
    for (std::size_t k = 0; k + 1 < b.size(); ++k) {
        const double fraction = (curve.passing_fraction(b[k + 1]) - curve.passing_fraction(b[k])) / kept;
        if (fraction > 0.0) fill_interval(b[k], b[k + 1], fraction * unscaled_volume, rng, unscaled);
    }
    if (unscaled.empty()) throw std::invalid_argument("gradation cannot be sampled: the volume holds no grain");
    compare_with_curve(curve, lo, hi, s, unscaled);
    for (std::size_t i = unscaled.size(); i > 1; --i)
        std::swap(unscaled[i - 1], unscaled[static_cast<std::size_t>(rng.next() % i)]);
    s.diameters.reserve(unscaled.size());
    for (double d : unscaled) {
        s.diameters.push_back(d * rule.scale);
        s.solid_volume += sphere_volume(d * rule.scale);
    }
    s.d50 *= rule.scale;
    return s;
}

}  // namespace gradem::exp
