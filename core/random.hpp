#pragma once
// Counter-based random numbers: a value depends only on (seed, key, counter), never on the
// order of calls or on the thread that asks, so bond strengths are the same whatever order
// bonds are installed in and whatever the thread count. SplitMix64 finaliser (Steele et al.
// 2014) as the mixing function.
#include <cmath>
#include <cstdint>

namespace gradem {

inline std::uint64_t mix64(std::uint64_t z) {
    z += 0x9e3779b97f4a7c15ull;
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
    return z ^ (z >> 31);
}

/// Uniform double in (0, 1) for (seed, key, counter).
inline double hashed_uniform(std::uint64_t seed, std::uint64_t key, std::uint64_t counter) {
    const std::uint64_t h = mix64(mix64(seed ^ mix64(key)) + counter);
    return (static_cast<double>(h >> 11) + 0.5) * (1.0 / 9007199254740992.0);
}

/// Normal(mean, std) truncated to values > 0, by rejection (Box-Muller pairs).
inline double truncated_normal_positive(double mean, double std, std::uint64_t seed,
                                        std::uint64_t key) {
    if (std == 0.0) return mean;
    for (std::uint64_t c = 0; c < 2000; c += 2) {
        const double u1 = hashed_uniform(seed, key, c);
        const double u2 = hashed_uniform(seed, key, c + 1);
        const double z = std::sqrt(-2.0 * std::log(u1)) * std::cos(6.283185307179586 * u2);
        const double v = mean + std * z;
        if (v > 0.0) return v;
    }
    return mean > 0.0 ? mean : std;  // unreachable for any sane (mean, std)
}

/// Stateful SplitMix64 stream for sequential use (genesis, benchmarks).
class SplitMix64 {
public:
    explicit SplitMix64(std::uint64_t seed) : state_(seed) {}
    std::uint64_t next() { return mix64(state_ += 0x9e3779b97f4a7c15ull); }
    /// Uniform in [0, 1).
    double uniform() { return static_cast<double>(next() >> 11) * (1.0 / 9007199254740992.0); }
    double uniform(double lo, double hi) { return lo + (hi - lo) * uniform(); }

private:
    std::uint64_t state_;
};

}  // namespace gradem
