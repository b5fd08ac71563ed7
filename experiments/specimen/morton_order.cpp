#include "experiments/specimen/morton_order.hpp"

#include <algorithm>
#include <cmath>
#include <utility>

namespace gradem::exp {
namespace {

constexpr int kBits = 21;
constexpr double kCells = static_cast<double>(1u << kBits);

// Spreads the low 21 bits of v so that bit k lands on bit 3k.
std::uint64_t spread3(std::uint64_t v) {
    v &= 0x1fffffull;
    v = (v | v << 32) & 0x1f00000000ffffull;
    v = (v | v << 16) & 0x1f0000ff0000ffull;
    v = (v | v << 8) & 0x100f00f00f00f00full;
    v = (v | v << 4) & 0x10c30c30c30c30c3ull;
    v = (v | v << 2) & 0x1249249249249249ull;
    return v;
}

std::uint64_t quantise(double x, double lo, double hi) {
    const double t = hi > lo ? (x - lo) / (hi - lo) : 0.0;
    const double cell = std::floor(std::clamp(t, 0.0, 1.0) * kCells);
    return static_cast<std::uint64_t>(std::min(cell, kCells - 1.0));
}

}  // namespace

std::uint64_t morton_code(const Vec3& p, const Vec3& lo, const Vec3& hi) {
    return spread3(quantise(p.x, lo.x, hi.x)) | spread3(quantise(p.y, lo.y, hi.y)) << 1 |
           spread3(quantise(p.z, lo.z, hi.z)) << 2;
}

std::vector<std::int32_t> morton_order(const std::vector<Vec3>& points, const Vec3& lo, const Vec3& hi) {
    std::vector<std::pair<std::uint64_t, std::int32_t>> keyed(points.size());
    for (std::size_t i = 0; i < points.size(); ++i) keyed[i] = {morton_code(points[i], lo, hi), static_cast<std::int32_t>(i)};
    std::sort(keyed.begin(), keyed.end());  // (code, index): unique keys, a total order
    std::vector<std::int32_t> order(points.size());
    for (std::size_t k = 0; k < keyed.size(); ++k) order[k] = keyed[k].second;
    return order;
}

}  // namespace gradem::exp
