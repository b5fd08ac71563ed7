#pragma once
// Particle vectors copied into structure-of-arrays lanes, four lanes at a time with AVX2: each
// lane's Vec3 (24 bytes, at base[index[l]]) read by one masked 256-bit load (the fourth double
// masked out: nothing is read past the Vec3), the four rows transposed into the x, y and z lanes
// by two unpacks and two 128-bit permutes. A copy of bits, so the lanes hold exactly what the
// scalar copy (one double at a time) gives; it issues a third of that copy's loads and a quarter
// of its stores (bench/README.md "Each side's moment in its pair's slot, particles into lanes by
// transposes"). Other processors and compilers keep the scalar copy:
// `lane_transpose_available()` says which one runs.
#include <cstdint>

#include "core/vec3.hpp"

#if defined(__x86_64__) && defined(__GNUC__) && !defined(__clang__) && !defined(GRADEM_NO_CLONES)
#define GRADEM_LANE_TRANSPOSE 1
#include <immintrin.h>
#endif

namespace gradem {

/// True if this processor runs transposed_lanes4() (AVX2), checked once.
inline bool lane_transpose_available() {
#ifdef GRADEM_LANE_TRANSPOSE
    static const bool available = [] {
        __builtin_cpu_init();
        return __builtin_cpu_supports("avx2") != 0;
    }();
    return available;
#else
    return false;
#endif
}

#ifdef GRADEM_LANE_TRANSPOSE
/// Lanes [0, 4) of x, y and z (each an array of at least 4 doubles) from base[index[0..3]].
/// Call only where lane_transpose_available().
__attribute__((target("avx2"), always_inline)) inline void transposed_lanes4(double* x, double* y, double* z,
                                                                             const Vec3* base, const std::int32_t* index) {
    const __m256i first_three = _mm256_setr_epi64x(-1, -1, -1, 0);
    const __m256d r0 = _mm256_maskload_pd(&base[index[0]].x, first_three);  // x0 y0 z0 0
    const __m256d r1 = _mm256_maskload_pd(&base[index[1]].x, first_three);
    const __m256d r2 = _mm256_maskload_pd(&base[index[2]].x, first_three);
    const __m256d r3 = _mm256_maskload_pd(&base[index[3]].x, first_three);
    const __m256d xz01 = _mm256_unpacklo_pd(r0, r1);  // x0 x1 z0 z1
    const __m256d y01 = _mm256_unpackhi_pd(r0, r1);   // y0 y1 0 0
    const __m256d xz23 = _mm256_unpacklo_pd(r2, r3);  // x2 x3 z2 z3
    const __m256d y23 = _mm256_unpackhi_pd(r2, r3);   // y2 y3 0 0
    _mm256_storeu_pd(x, _mm256_permute2f128_pd(xz01, xz23, 0x20));  // low halves: x0 x1 x2 x3
    _mm256_storeu_pd(y, _mm256_permute2f128_pd(y01, y23, 0x20));
    _mm256_storeu_pd(z, _mm256_permute2f128_pd(xz01, xz23, 0x31));  // high halves: z0 z1 z2 z3
}
#endif

}  // namespace gradem
