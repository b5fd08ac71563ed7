#pragma once
// Helpers for deterministic OpenMP: work is cut into blocks whose boundaries depend only on
// the problem size, never on the thread count, and per-block partial results are combined in
// block order. Floating-point sums therefore come out bitwise identical for any thread count.
#include <algorithm>
#include <chrono>
#include <cstdint>
#include <utility>
#include <vector>

#ifdef _OPENMP
#include <omp.h>
#endif

namespace gradem {

inline constexpr std::int64_t kBlockSize = 2048;

inline std::int64_t block_count(std::int64_t n) { return (n + kBlockSize - 1) / kBlockSize; }

inline int thread_count() {
#ifdef _OPENMP
    return omp_get_max_threads();
#else
    return 1;
#endif
}

/// Size of the current team (inside a parallel region).
inline int team_size() {
#ifdef _OPENMP
    return omp_get_num_threads();
#else
    return 1;
#endif
}

inline int thread_index() {
#ifdef _OPENMP
    return omp_get_thread_num();
#else
    return 0;
#endif
}

/// Calls body(begin, end, block) for every fixed block of [0, n), in parallel.
template <class Body>
void for_each_block(std::int64_t n, Body&& body) {
    const std::int64_t blocks = block_count(n);
#pragma omp parallel for schedule(static)
    for (std::int64_t b = 0; b < blocks; ++b) {
        const std::int64_t begin = b * kBlockSize;
        body(begin, std::min(n, begin + kBlockSize), b);
    }
}

/// Thread t's share [first, last) of n items cut at the given bounds (team + 1 of them, from 0 to
/// n), or into equal parts where `bounds` is not for this team and these items.
inline std::pair<std::int64_t, std::int64_t> item_share(const std::vector<std::int64_t>& bounds, std::int64_t n, int team,
                                                        int t) {
    if (static_cast<int>(bounds.size()) == team + 1 && bounds.back() == n)
        return {bounds[static_cast<std::size_t>(t)], bounds[static_cast<std::size_t>(t) + 1]};
    return {n * t / team, n * (t + 1) / team};
}

/// The part of a thread's share that lies in one fixed block: items [begin, end) of block
/// `block`. A part that starts at its block's first item is the block's head, whose sums start
/// the block's chain of additions; a share that starts inside a block begins with that block's
/// tail (at most one per thread), whose terms are kept in order and added to the head's sums
/// afterwards, so a block's sums have the same bits however the shares cut it.
struct BlockPart {
    std::int64_t begin = 0, end = 0, block = 0;
    [[nodiscard]] bool head() const { return begin == block * kBlockSize; }
};

/// Calls body(part) for the block parts of items [first, last), in order.
template <class Body>
void for_each_block_part(std::int64_t first, std::int64_t last, Body&& body) {
    for (std::int64_t b = first / kBlockSize; b * kBlockSize < last; ++b)
        body(BlockPart{std::max(first, b * kBlockSize), std::min(last, (b + 1) * kBlockSize), b});
}

/// Thread t's share of n items cut at `bounds` (item_share), part by part in order (body(part)),
/// its time in it added to seconds[t] [s] (World::balance_pass_shares weighs the shares by it).
template <class Body>
void run_timed_share(const std::vector<std::int64_t>& bounds, std::int64_t n, int team, int t, std::vector<double>& seconds,
                     Body&& body) {
    const auto [first, last] = item_share(bounds, n, team, t);
    const auto start = std::chrono::steady_clock::now();
    for_each_block_part(first, last, body);
    seconds[static_cast<std::size_t>(t)] += std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

/// Sums `partials` in block order (deterministic).
template <class T>
T ordered_sum(const std::vector<T>& partials) {
    T total{};
    for (const T& p : partials) total += p;
    return total;
}

}  // namespace gradem
