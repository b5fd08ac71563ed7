// Specimen genesis: grains sampled by mass hit the target curve; the packing reaches the
// requested locked-in stress with few floaters, in force balance, with small overlaps and an
// isotropic contact fabric, in Morton order, bitwise identical for any thread count; bad
// inputs are refused with their reason.
#include "../temp_dir.hpp"
#include <catch2/catch.hpp>
#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <filesystem>

#include "core/parallel.hpp"
#include "experiments/specimen/genesis.hpp"
#include "experiments/specimen/morton_order.hpp"
#include "experiments/specimen/packing_cache.hpp"
#include "../with_threads.hpp"
#include "small_specimen.hpp"

using namespace gradem;
using namespace gradem::exp;
using gradem::test::small_packing;
using gradem::test::small_spec;

TEST_CASE("grains sampled by mass reproduce the sieve curve", "[experiments][genesis]") {
    const lab::GradationCurve curve = test::pre_blended_curve();
    SizeRule rule;
    rule.min_diameter = 0.149e-3;
    rule.max_diameter = 1.18e-3;
    const GrainSample s = sample_grains(curve, rule, 40.0e-9, 3);
    INFO("grains " << s.diameters.size() << ", max deviation " << 100 * s.max_deviation << " pp");
    CHECK(s.diameters.size() > 2000);
    CHECK(s.max_deviation < 0.02);  // within 2 percentage points at every kept sieve
    CHECK(s.removed_fine_fraction == Approx(0.256).epsilon(1e-9));
    CHECK(s.removed_coarse_fraction == Approx(1.0 - 0.981).epsilon(1e-9));
    for (double d : s.diameters) {
        CHECK(d >= rule.min_diameter);
        CHECK(d <= rule.max_diameter);
    }
    double volume = 0.0;
    for (double d : s.diameters) volume += kPi / 6 * d * d * d;
    CHECK(volume == Approx(40.0e-9).epsilon(0.01));
    // Upscaling multiplies every size and keeps the number of grains for the scaled volume.
    rule.scale = 2.0;
    const GrainSample big = sample_grains(curve, rule, 8.0 * 40.0e-9, 3);
    CHECK(big.diameters.size() == s.diameters.size());
    CHECK(big.d50 == Approx(2.0 * s.d50));
}

TEST_CASE("size rules that remove everything are refused", "[experiments][genesis]") {
    SizeRule rule;
    rule.min_diameter = 5.0e-3;  // above the coarsest sieve
    CHECK_THROWS_WITH(sample_grains(test::pre_blended_curve(), rule, 1e-9, 1),
                      Catch::Contains("cannot be sampled"));
    rule = {};
    rule.max_diameter = 0.1e-3;  // below the lower cut-off
    CHECK_THROWS_WITH(sample_grains(test::pre_blended_curve(), rule, 1e-9, 1),
                      Catch::Contains("max_diameter"));
    SpecimenSpec spec;
    spec.size_rule.max_diameter = 1.18e-3;
    spec.genesis.edge = 3.0e-3;  // fewer than 3 largest grains across
    CHECK_THROWS_WITH(generate_packing(test::pre_blended_curve(), spec), Catch::Contains("3 x the largest grain"));
}

namespace {

struct ContactStats {
    double mean_overlap = 0.0, max_overlap = 0.0;  // overlap / smallest diameter of the packing
    std::array<double, 3> fabric_eigenvalues{};    // of (1/Nc) sum n n over grain-grain contacts
    std::size_t contacts = 0;
};

// Eigenvalues of a symmetric 3x3 matrix (trigonometric closed form, Smith 1961).
std::array<double, 3> symmetric_eigenvalues(const double a[3][3]) {
    const double q = (a[0][0] + a[1][1] + a[2][2]) / 3.0;
    const double p1 = a[0][1] * a[0][1] + a[0][2] * a[0][2] + a[1][2] * a[1][2];
    const double p2 = (a[0][0] - q) * (a[0][0] - q) + (a[1][1] - q) * (a[1][1] - q) + (a[2][2] - q) * (a[2][2] - q) + 2.0 * p1;
    const double p = std::sqrt(p2 / 6.0);
    if (p == 0.0) return {q, q, q};
    double b[3][3];
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) b[i][j] = (a[i][j] - (i == j ? q : 0.0)) / p;
    const double det = b[0][0] * (b[1][1] * b[2][2] - b[1][2] * b[2][1]) - b[0][1] * (b[1][0] * b[2][2] - b[1][2] * b[2][0]) +
                       b[0][2] * (b[1][0] * b[2][1] - b[1][1] * b[2][0]);
    const double phi = std::acos(std::clamp(det / 2.0, -1.0, 1.0)) / 3.0;
    const double l1 = q + 2.0 * p * std::cos(phi), l3 = q + 2.0 * p * std::cos(phi + 2.0 * kPi / 3.0);
    return {l1, 3.0 * q - l1 - l3, l3};
}

// Brute force over all pairs (the packing is small): an oracle independent of the packer.
ContactStats contact_stats(const Packing& k) {
    ContactStats s;
    const double d_min = 2.0 * *std::min_element(k.radius.begin(), k.radius.end());
    double fabric[3][3] = {};
    for (std::size_t i = 0; i < k.radius.size(); ++i)
        for (std::size_t j = i + 1; j < k.radius.size(); ++j) {
            const Vec3 d = k.position[j] - k.position[i];
            const double overlap = k.radius[i] + k.radius[j] - norm(d);
            if (overlap <= 0.0) continue;
            ++s.contacts;
            s.mean_overlap += overlap / d_min;
            s.max_overlap = std::max(s.max_overlap, overlap / d_min);
            const Vec3 n = (1.0 / norm(d)) * d;
            for (int a = 0; a < 3; ++a)
                for (int b = 0; b < 3; ++b) fabric[a][b] += n[a] * n[b];
        }
    if (s.contacts == 0) return s;
    s.mean_overlap /= static_cast<double>(s.contacts);
    for (auto& row : fabric)
        for (double& v : row) v /= static_cast<double>(s.contacts);
    s.fabric_eigenvalues = symmetric_eigenvalues(fabric);
    return s;
}

}  // namespace

TEST_CASE("genesis reaches the locked-in stress with few floaters", "[experiments][genesis]") {
    const SpecimenSpec spec = small_spec();
    const Packing& k = small_packing();
    INFO(describe(k, spec));
    const double target = spec.genesis.locked_in_stress, tol = spec.genesis.stress_tolerance;
    CHECK(k.converged);
    CHECK(std::fabs(k.wall_stress.x - target) <= tol * target);
    CHECK(std::fabs(k.wall_stress.y - target) <= tol * target);
    CHECK(std::fabs(k.wall_stress.z - target) <= tol * target);
    CHECK(k.unbalanced_ratio < spec.genesis.equilibrium_ratio);
    // Floaters are enlarged at the jamming pressure (1e-3 E*); unloading to the locked-in
    // stress opens some contacts again, so the final count (rattlers of a frictionless packing)
    // may exceed the count before the passes.
    CHECK(k.floaters_before < 0.10);
    CHECK(k.floaters_after < 0.12);
    CHECK(k.porosity > 0.3);
    CHECK(k.porosity < 0.45);
    CHECK(k.edge() == Approx(spec.genesis.edge).epsilon(0.1));
}

TEST_CASE("a genesis packing is in force balance with small overlaps and an isotropic fabric", "[experiments][genesis]") {
    const SpecimenSpec spec = small_spec();
    const Packing& k = small_packing();
    INFO(describe(k, spec));
    REQUIRE(k.converged);
    CHECK(k.unbalanced_ratio <= spec.genesis.equilibrium_ratio);
    const ContactStats s = contact_stats(k);
    INFO("contacts " << s.contacts << ", overlap / d_min mean " << s.mean_overlap << " max " << s.max_overlap
                     << ", fabric eigenvalues " << s.fabric_eigenvalues[0] << " " << s.fabric_eigenvalues[1] << " "
                     << s.fabric_eigenvalues[2]);
    REQUIRE(s.contacts > k.radius.size());  // a connected contact network, ~ z/2 per grain
    // Linear contacts at sigma_0/E* = 1e-5 overlap by ~1e-5 of a diameter (~2.5 sigma/E* of a radius).
    CHECK(s.mean_overlap < 1.0e-3);
    CHECK(s.max_overlap < 1.0e-2);
    // Isotropic compression: every eigenvalue of the fabric tensor near 1/3. With Nc ~ 1000
    // contacts the sampling spread of a diagonal entry is ~0.3/sqrt(Nc) ~ 0.01: allow 0.04 (12 %).
    for (double lambda : s.fabric_eigenvalues) CHECK(std::fabs(lambda - 1.0 / 3.0) < 0.04);
    // The grains are stored in Morton order of their centres.
    std::uint64_t previous = 0;
    bool ordered = true;
    for (const Vec3& p : k.position) {
        const std::uint64_t code = morton_code(p, k.box_lo, k.box_hi);
        ordered = ordered && code >= previous;
        previous = code;
    }
    CHECK(ordered);
}

TEST_CASE("genesis is bitwise identical for any thread count", "[experiments][genesis]") {
    SpecimenSpec spec;
    spec.size_rule.min_diameter = 0.4e-3;  // ~200 grains
    spec.size_rule.max_diameter = 1.18e-3;
    spec.genesis.edge = 3.6e-3;
    spec.genesis.target_solid_fraction = 0.5;  // walls loosen a box only ~6 grains wide
    spec.seed = 11;
    auto generate = [&] { return generate_packing(test::van_buren_curve(), spec); };
    const Packing one = test::with_threads(1, generate);
    const Packing three = test::with_threads(3, generate);
    REQUIRE(one.position.size() == three.position.size());
    CHECK(std::memcmp(one.position.data(), three.position.data(), one.position.size() * sizeof(Vec3)) == 0);
    CHECK(std::memcmp(one.radius.data(), three.radius.data(), one.radius.size() * sizeof(double)) == 0);
    CHECK(one.relax_iterations == three.relax_iterations);
    CHECK(one.steps == three.steps);
    CHECK(std::memcmp(&one.unbalanced_ratio, &three.unbalanced_ratio, sizeof(double)) == 0);
}

TEST_CASE("genesis of a packing large enough for parallel minimisation is bitwise identical for 1 and 2 threads",
          "[experiments][genesis][.slow]") {
    SpecimenSpec spec;  // ~17 000 grains: >= 8 blocks of 2048, so the minimiser's loops run in parallel
    spec.size_rule.min_diameter = 0.3e-3;
    spec.size_rule.max_diameter = 1.18e-3;
    spec.genesis.edge = 9.9e-3;
    spec.seed = 3;
    auto generate = [&] { return generate_packing(test::van_buren_curve(), spec); };
    const Packing one = test::with_threads(1, generate);
    const Packing two = test::with_threads(2, generate);
    INFO(describe(one, spec));
    REQUIRE(one.position.size() > 16384);
    REQUIRE(one.position.size() == two.position.size());
    CHECK(std::memcmp(one.position.data(), two.position.data(), one.position.size() * sizeof(Vec3)) == 0);
    CHECK(one.relax_iterations == two.relax_iterations);
}

TEST_CASE("genesis refuses inputs it cannot honour", "[experiments][genesis]") {
    SpecimenSpec spec;
    spec.size_rule.min_diameter = 0.4e-3;
    spec.size_rule.max_diameter = 1.18e-3;
    spec.genesis.edge = 3.6e-3;
    SECTION("a locked-in stress that is not small against the packing modulus") {
        spec.genesis.locked_in_stress = 50.0e6;  // 5e-3 E*
        CHECK_THROWS_WITH(generate_packing(test::van_buren_curve(), spec),
                          Catch::Contains("genesis.locked_in_stress") && Catch::Contains("reference_modulus"));
    }
    SECTION("a gradation that jams before it fills the vessel at the asked solid fraction") {
        spec.genesis.target_solid_fraction = 0.74;  // above random close packing of this narrow sand
        CHECK_THROWS_WITH(generate_packing(test::van_buren_curve(), spec),
                          Catch::Contains("target_solid_fraction") && Catch::Contains("cannot be reached"));
    }
    SECTION("a budget too small to converge: flagged, and never cached") {
        spec.genesis.max_steps = 200;
        const Packing k = generate_packing(test::van_buren_curve(), spec);
        CHECK_FALSE(k.converged);
        CHECK_THAT(describe(k, spec), Catch::Contains("NOT converged"));
        CHECK_THAT(convergence_failure(k, spec), Catch::Contains("genesis.max_steps = 200"));
        const test::TempDir dir("genesis-budget");
        CHECK_THROWS_AS(load_or_generate(test::van_buren_curve(), spec, dir.path), GenesisError);
        CHECK_FALSE(std::filesystem::exists(packing_cache_path(dir.path, packing_key(test::van_buren_curve(), spec))));
    }
}

TEST_CASE("the Morton order follows the Z curve and keeps neighbours together", "[experiments][genesis]") {
    const Vec3 lo{0, 0, 0}, hi{1, 1, 1};
    CHECK(morton_code({0, 0, 0}, lo, hi) == 0);
    CHECK(morton_code({0.6, 0.1, 0.1}, lo, hi) > morton_code({0.4, 0.4, 0.4}, lo, hi));  // x bit is the lowest
    CHECK(morton_code({0.1, 0.1, 0.6}, lo, hi) > morton_code({0.6, 0.6, 0.4}, lo, hi));  // z bit is the highest
    CHECK(morton_code({2, 2, 2}, lo, hi) == morton_code({1, 1, 1}, lo, hi));             // clamped
    // An 8^3 lattice, listed in a scrambled order: sorted, consecutive points are lattice
    // neighbours most of the time (mean step < 1.5 spacings; a random order gives ~4).
    std::vector<Vec3> points;
    for (int k = 0; k < 512; ++k) {
        const int m = (k * 389) % 512;  // 389 is odd: a permutation of 0..511
        points.push_back({(m % 8 + 0.5) / 8.0, (m / 8 % 8 + 0.5) / 8.0, (m / 64 + 0.5) / 8.0});
    }
    const std::vector<std::int32_t> order = morton_order(points, lo, hi);
    std::vector<std::int32_t> sorted = order;
    std::sort(sorted.begin(), sorted.end());
    for (std::int32_t k = 0; k < 512; ++k) REQUIRE(sorted[static_cast<std::size_t>(k)] == k);  // a permutation
    const std::vector<Vec3> along = permuted(points, order);
    double step = 0.0;
    for (std::size_t k = 1; k < along.size(); ++k) step += norm(along[k] - along[k - 1]) * 8.0;
    CHECK(step / 511.0 < 1.5);
    // Ties (equal codes) keep the index order.
    const std::vector<std::int32_t> tied = morton_order({{0.5, 0.5, 0.5}, {0.5, 0.5, 0.5}, {0.1, 0.1, 0.1}}, lo, hi);
    CHECK(tied == std::vector<std::int32_t>{2, 0, 1});
}
