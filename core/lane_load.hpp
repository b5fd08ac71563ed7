#pragma once
// Particle vectors copied into structure-of-arrays lanes, four lanes at a time with AVX2: each
// lane's Vec3 (24 bytes, at base[index[l]]) read by one masked 256-bit load (the fourth double
// masked out: nothing is read past the Vec3), the four rows transposed into the x, y and z lanes
// by two unpacks and two 128-bit permutes. A copy of bits, so the lanes hold exactly what the
// scalar copy (one double at a time) gives; it issues a third of that copy's loads and a quarter
// of its stores (bench/README.md "Each side's moment in its pair's slot, particles into lanes by
// transposes"). Other processors and compilers keep the scalar copy:
// `lane_transpose_available()` says which one runs. The same transposes copy fixed records
// (a bond's side state, its constants) into lanes and back (rows_to_lanes4, lanes_to_rows4).
#include <cstdint>
#include <cstdlib>
#include <string_view>

#include "core/vec3.hpp"

#if defined(__x86_64__) && defined(__GNUC__) && !defined(__clang__) && !defined(GRADEM_NO_CLONES)
#define GRADEM_LANE_TRANSPOSE 1
#include <immintrin.h>
#endif

namespace gradem {

/// True if this processor runs the transposes (AVX2), checked once. GRADEM_NO_LANE_TRANSPOSE=1 in
/// the environment makes it false, so that the scalar copies that processors without AVX2 run
/// are tested here too (tests/core/CMakeLists.txt: the pinned hashes with them).
inline bool lane_transpose_available() {
#ifdef GRADEM_LANE_TRANSPOSE
    static const bool available = [] {
        if (const char* off = std::getenv("GRADEM_NO_LANE_TRANSPOSE"); off != nullptr && std::string_view(off) == "1")
            return false;
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

/// The 4x4 transpose of four rows of four doubles: on return a holds every row's first double,
/// b the second, c the third, d the fourth (two unpacks and two 128-bit permutes per pair).
__attribute__((target("avx2"), always_inline)) inline void transpose4(__m256d& a, __m256d& b, __m256d& c, __m256d& d) {
    const __m256d t0 = _mm256_unpacklo_pd(a, b);  // a0 b0 a2 b2
    const __m256d t1 = _mm256_unpackhi_pd(a, b);  // a1 b1 a3 b3
    const __m256d t2 = _mm256_unpacklo_pd(c, d);  // c0 d0 c2 d2
    const __m256d t3 = _mm256_unpackhi_pd(c, d);  // c1 d1 c3 d3
    a = _mm256_permute2f128_pd(t0, t2, 0x20);     // a0 b0 c0 d0
    b = _mm256_permute2f128_pd(t1, t3, 0x20);     // a1 b1 c1 d1
    c = _mm256_permute2f128_pd(t0, t2, 0x31);     // a2 b2 c2 d2
    d = _mm256_permute2f128_pd(t1, t3, 0x31);     // a3 b3 c3 d3
}

/// Four doubles at each of four records (row[r] + 0..3) into lanes 0..3 of four fields:
/// field[c][r] = row[r][c]. `count` < 4 loads only the first `count` doubles of each record (a
/// masked load: nothing past them is read) and writes only fields [0, count).
__attribute__((target("avx2"), always_inline)) inline void rows_to_lanes4(const double* const row[4], double* const field[4],
                                                                          int count = 4) {
    const __m256i mask = _mm256_cmpgt_epi64(_mm256_set1_epi64x(count), _mm256_setr_epi64x(0, 1, 2, 3));
    __m256d a = _mm256_maskload_pd(row[0], mask), b = _mm256_maskload_pd(row[1], mask);
    __m256d c = _mm256_maskload_pd(row[2], mask), d = _mm256_maskload_pd(row[3], mask);
    transpose4(a, b, c, d);
    const __m256d out[4] = {a, b, c, d};
    for (int f = 0; f < count; ++f) _mm256_storeu_pd(field[f], out[f]);
}

/// The inverse: lanes 0..3 of four fields into four doubles at each of four records,
/// row[r][c] = field[c][r].
__attribute__((target("avx2"), always_inline)) inline void lanes_to_rows4(const double* const field[4], double* const row[4]) {
    __m256d a = _mm256_loadu_pd(field[0]), b = _mm256_loadu_pd(field[1]);
    __m256d c = _mm256_loadu_pd(field[2]), d = _mm256_loadu_pd(field[3]);
    transpose4(a, b, c, d);
    _mm256_storeu_pd(row[0], a);
    _mm256_storeu_pd(row[1], b);
    _mm256_storeu_pd(row[2], c);
    _mm256_storeu_pd(row[3], d);
}

/// Lanes 0..3 of two fields into two doubles at each of four records: row[r][0] = x[r],
/// row[r][1] = y[r].
__attribute__((target("avx2"), always_inline)) inline void lane_pairs_to_rows4(const double* x, const double* y,
                                                                               double* const row[4]) {
    const __m256d a = _mm256_loadu_pd(x), b = _mm256_loadu_pd(y);
    const __m256d lo = _mm256_unpacklo_pd(a, b);  // x0 y0 x2 y2
    const __m256d hi = _mm256_unpackhi_pd(a, b);  // x1 y1 x3 y3
    _mm_storeu_pd(row[0], _mm256_castpd256_pd128(lo));
    _mm_storeu_pd(row[1], _mm256_castpd256_pd128(hi));
    _mm_storeu_pd(row[2], _mm256_extractf128_pd(lo, 1));
    _mm_storeu_pd(row[3], _mm256_extractf128_pd(hi, 1));
}
#endif

}  // namespace gradem
