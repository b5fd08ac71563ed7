// Particle vectors into lanes by transposes (core/lane_load.hpp): every lane holds the bits of
// its particle's vector, whatever they are (signed zeros, subnormals, infinities, NaN payloads),
// for any indices, the last particle of the array included (a page the process may not read
// begins right after it). The fused pair pass's results with
// the transposes are the pinned ones of test_determinism.cpp (recorded with the scalar copy).
#include <catch2/catch.hpp>

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
