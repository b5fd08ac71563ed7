#pragma once
// Space-filling-curve order of the grains of a packing: grains sorted along the Morton
// (Z-order) curve of their centres, so grains close in space are close in memory and the
// engine's neighbour and force loops touch nearby cache lines (Morton 1966; the usual
// locality sort of particle codes). Codes interleave 21 bits per axis of the centre quantised
// over the box; equal codes keep their original order (ties broken by index): the order is a
// pure function of the positions.
#include <cstdint>
#include <vector>

#include "core/vec3.hpp"

namespace gradem::exp {

/// 63-bit Morton code of `p` in the box [lo, hi] (coordinates clamped into it).
std::uint64_t morton_code(const Vec3& p, const Vec3& lo, const Vec3& hi);

/// Permutation that sorts the points along the Morton curve: order[k] is the index of the
/// k-th point. Ties (same code) are ordered by index.
std::vector<std::int32_t> morton_order(const std::vector<Vec3>& points, const Vec3& lo, const Vec3& hi);

/// out[k] = in[order[k]].
template <class T>
std::vector<T> permuted(const std::vector<T>& in, const std::vector<std::int32_t>& order) {
    std::vector<T> out;
    out.reserve(order.size());
    for (std::int32_t k : order) out.push_back(in[static_cast<std::size_t>(k)]);
    return out;
}

}  // namespace gradem::exp
