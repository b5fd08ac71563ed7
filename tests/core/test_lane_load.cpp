// Particle vectors into lanes by transposes (core/lane_load.hpp): every lane holds the bits of
// its particle's vector, whatever they are (signed zeros, subnormals, infinities, NaN payloads),
// for any indices, the last particle of the array included (a page the process may not read
// begins right after it). The same for fixed records into lanes and back (a joint's side state):
// every double lands where the scalar copy puts it, and nothing past a record's copied part is
// read or written. The fused pair pass's results with
// the transposes are the pinned ones of test_determinism.cpp (recorded with the scalar copy).
#include <catch2/catch.hpp>

#include <algorithm>
#include <cstdint>
#include <cstring>
#include <limits>
#include <random>
#include <vector>

#include <sys/mman.h>
#include <unistd.h>

#include "core/lane_load.hpp"

using namespace gradem;

namespace {

std::uint64_t bits(double x) {
    std::uint64_t u;
    std::memcpy(&u, &x, sizeof u);
    return u;
}

double from_bits(std::uint64_t u) {
    double x;
    std::memcpy(&x, &u, sizeof x);
    return x;
}

/// Doubles that a copy through arithmetic could change: -0, subnormals, infinities, NaNs with payloads.
std::vector<double> awkward_values() {
    return {0.0,
            -0.0,
            std::numeric_limits<double>::denorm_min(),
            -std::numeric_limits<double>::denorm_min(),
            std::numeric_limits<double>::infinity(),
            -std::numeric_limits<double>::infinity(),
            from_bits(0x7ff8000000000123ULL),  // quiet NaN, payload 0x123
            from_bits(0xfff4000000000001ULL),  // signalling NaN, sign bit set
            std::numeric_limits<double>::max(),
            1.0e-300,
            -3.5e-3};
}

/// n vectors that end exactly where a page the process may not read begins: a read past the
/// last one faults.
class VectorsBeforeGuardPage {
public:
    explicit VectorsBeforeGuardPage(std::size_t n) {
        page_ = static_cast<std::size_t>(sysconf(_SC_PAGESIZE));
        const std::size_t pages = (n * sizeof(Vec3) + page_ - 1) / page_ + 1;
        bytes_ = pages * page_;
        void* m = mmap(nullptr, bytes_, PROT_READ | PROT_WRITE, MAP_PRIVATE | MAP_ANONYMOUS, -1, 0);
        REQUIRE(m != MAP_FAILED);
        base_ = static_cast<char*>(m);
        REQUIRE(mprotect(base_ + bytes_ - page_, page_, PROT_NONE) == 0);
        data_ = reinterpret_cast<Vec3*>(base_ + bytes_ - page_ - n * sizeof(Vec3));
        size_ = n;
    }
    ~VectorsBeforeGuardPage() { munmap(base_, bytes_); }
    VectorsBeforeGuardPage(const VectorsBeforeGuardPage&) = delete;
    VectorsBeforeGuardPage& operator=(const VectorsBeforeGuardPage&) = delete;
    Vec3* data() { return data_; }
    std::size_t size() const { return size_; }

private:
    std::size_t page_ = 0, bytes_ = 0, size_ = 0;
    char* base_ = nullptr;
    Vec3* data_ = nullptr;
};

#ifdef GRADEM_LANE_TRANSPOSE
/// transposed_lanes4 from a function compiled for AVX2, as the pass calls it.
__attribute__((target("avx2"), noinline)) void transpose4(double* x, double* y, double* z, const Vec3* v,
                                                          const std::int32_t* index) {
    transposed_lanes4(x, y, z, v, index);
}

/// The record transposes from functions compiled for AVX2, as the flat joint's pass calls them.
__attribute__((target("avx2"), noinline)) void rows_to_lanes(const double* const row[4], double* const field[4], int count) {
    rows_to_lanes4(row, field, count);
}
__attribute__((target("avx2"), noinline)) void lanes_to_rows(const double* const field[4], double* const row[4]) {
    lanes_to_rows4(field, row);
}
__attribute__((target("avx2"), noinline)) void lane_pairs_to_rows(const double* x, const double* y, double* const row[4]) {
    lane_pairs_to_rows4(x, y, row);
}
#endif

}  // namespace

TEST_CASE("lane transposes: four lanes hold their particles' vectors bit for bit", "[core][lanes]") {
    if (!lane_transpose_available()) {
        SUCCEED("no AVX2 on this processor: the scalar copy runs, and this test has nothing to check");
        return;
    }
#ifdef GRADEM_LANE_TRANSPOSE
    const std::vector<double> awkward = awkward_values();
    std::mt19937_64 rng(7);
    VectorsBeforeGuardPage guarded(1001);
    Vec3* const v = guarded.data();
    for (std::size_t p = 0; p < guarded.size(); ++p) {
        const auto pick = [&](std::size_t k) {
            return (rng() % 3 == 0) ? awkward[(p + k) % awkward.size()] : from_bits(rng());
        };
        v[p] = {pick(0), pick(1), pick(2)};
    }
    const auto last = static_cast<std::int32_t>(guarded.size() - 1);
    std::uniform_int_distribution<std::int32_t> any_index(0, last);
    for (int trial = 0; trial < 2000; ++trial) {
        std::int32_t index[4];
        for (auto& i : index) i = any_index(rng);
        if (trial % 7 == 0) index[trial % 4] = last;  // the array's end, before the guard page: a read past it faults
        if (trial % 11 == 0) index[1] = index[2] = index[0];  // repeated particles (pairs sorted by i)
        double x[4], y[4], z[4];
        transpose4(x, y, z, v, index);
        for (int l = 0; l < 4; ++l) {
            const Vec3& p = v[index[l]];
            INFO("trial " << trial << ", lane " << l << ", particle " << index[l]);
            REQUIRE(bits(x[l]) == bits(p.x));
            REQUIRE(bits(y[l]) == bits(p.y));
            REQUIRE(bits(z[l]) == bits(p.z));
        }
    }
#endif
}

TEST_CASE("record transposes: records into lanes and back bit for bit, nothing read or written past them",
          "[core][lanes]") {
    if (!lane_transpose_available()) {
        SUCCEED("no AVX2 on this processor: the scalar copy runs, and this test has nothing to check");
        return;
    }
#ifdef GRADEM_LANE_TRANSPOSE
    const std::vector<double> awkward = awkward_values();
    std::mt19937_64 rng(11);
    const auto any_double = [&](std::size_t k) { return (rng() % 3 == 0) ? awkward[k % awkward.size()] : from_bits(rng()); };
    // Records of 3 doubles (an element: bonded flag, two shear forces) that end at a guard page.
    VectorsBeforeGuardPage guarded(257);
    Vec3* const records = guarded.data();
    for (std::size_t p = 0; p < guarded.size(); ++p) records[p] = {any_double(p), any_double(p + 1), any_double(p + 2)};
    const auto last = static_cast<std::int32_t>(guarded.size() - 1);
    std::uniform_int_distribution<std::int32_t> any_record(0, last);
    for (int trial = 0; trial < 500; ++trial) {
        std::int32_t index[4];
        for (auto& i : index) i = any_record(rng);
        if (trial % 5 == 0) index[trial % 4] = last;  // a masked load must not read past the last record
        const double* const row[4] = {&records[index[0]].x, &records[index[1]].x, &records[index[2]].x, &records[index[3]].x};
        double a[4], b[4], c[4], untouched[4];
        for (double& u : untouched) u = 42.0;
        double* const field[4] = {a, b, c, untouched};
        rows_to_lanes(row, field, 3);
        for (int l = 0; l < 4; ++l) {
            INFO("trial " << trial << ", lane " << l << ", record " << index[l]);
            REQUIRE(bits(a[l]) == bits(row[l][0]));
            REQUIRE(bits(b[l]) == bits(row[l][1]));
            REQUIRE(bits(c[l]) == bits(row[l][2]));
            REQUIRE(untouched[l] == 42.0);  // a fourth field is not written for three-double records
        }
    }
    // Records of 8 doubles: four into lanes, four lanes back into other records, pairs into the middle of a record.
    std::vector<double> source(8 * 64), target(8 * 64, 0.0);
    for (std::size_t n = 0; n < source.size(); ++n) source[n] = any_double(n);
    for (int trial = 0; trial < 500; ++trial) {
        const std::size_t r[4] = {rng() % 64, rng() % 64, rng() % 64, rng() % 64};
        const std::size_t offset = rng() % 5;  // the four doubles copied: [offset, offset + 4) of each record
        const double* const row[4] = {&source[8 * r[0] + offset], &source[8 * r[1] + offset], &source[8 * r[2] + offset],
                                      &source[8 * r[3] + offset]};
        double lanes[4][4];
        double* const field[4] = {lanes[0], lanes[1], lanes[2], lanes[3]};
        rows_to_lanes(row, field, 4);
        for (int f = 0; f < 4; ++f)
            for (int l = 0; l < 4; ++l) REQUIRE(bits(lanes[f][l]) == bits(row[l][f]));
        // back into four distinct records of the target, the doubles around them left alone
        std::fill(target.begin(), target.end(), -1.0);
        const std::size_t t[4] = {3, 17, 40, 63};
        double* const out[4] = {&target[8 * t[0] + offset], &target[8 * t[1] + offset], &target[8 * t[2] + offset],
                                &target[8 * t[3] + offset]};
        const double* const from[4] = {lanes[0], lanes[1], lanes[2], lanes[3]};
        lanes_to_rows(from, out);
        for (int l = 0; l < 4; ++l)
            for (std::size_t n = 0; n < 8; ++n) {
                const double got = target[8 * t[l] + n];
                if (n >= offset && n < offset + 4) REQUIRE(bits(got) == bits(row[l][n - offset]));
                else REQUIRE(got == -1.0);
            }
        // two lanes' fields as pairs into the records, at [offset, offset + 2)
        std::fill(target.begin(), target.end(), -1.0);
        lane_pairs_to_rows(lanes[1], lanes[2], out);
        for (int l = 0; l < 4; ++l)
            for (std::size_t n = 0; n < 8; ++n) {
                const double got = target[8 * t[l] + n];
                if (n == offset) REQUIRE(bits(got) == bits(lanes[1][l]));
                else if (n == offset + 1) REQUIRE(bits(got) == bits(lanes[2][l]));
                else REQUIRE(got == -1.0);
            }
    }
#endif
}
