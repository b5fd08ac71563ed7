// Specimen genesis: grains sampled by mass hit the target curve; the packing reaches the
// requested locked-in stress with few floaters.
#include <catch2/catch.hpp>
#include <cmath>

#include "experiments/genesis.hpp"
#include "study_curves.hpp"

using namespace gradem;
using namespace gradem::exp;

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

TEST_CASE("genesis reaches the locked-in stress with few floaters", "[experiments][genesis]") {
    SpecimenSpec spec;
    spec.size_rule.min_diameter = 0.3e-3;  // small and fast: ~500 grains
    spec.size_rule.max_diameter = 1.18e-3;
    spec.genesis.edge = 3.6e-3;
    spec.genesis.max_steps = 60000;
    spec.seed = 5;
    const Packing k = generate_packing(test::van_buren_curve(), spec);
    INFO(describe(k, spec));
    INFO("(an unbonded frictionless packing creeps; genesis stops at a ratio of "
         << spec.genesis.equilibrium_ratio << ")");
    const double target = spec.genesis.locked_in_stress, tol = spec.genesis.stress_tolerance;
    CHECK(std::fabs(k.wall_stress.x - target) <= tol * target);
    CHECK(std::fabs(k.wall_stress.y - target) <= tol * target);
    CHECK(std::fabs(k.wall_stress.z - target) <= tol * target);
    CHECK(k.unbalanced_ratio < spec.genesis.equilibrium_ratio);
    CHECK(k.floaters_after < 0.10);
    CHECK(k.floaters_after <= k.floaters_before);
    CHECK(k.porosity > 0.3);
    CHECK(k.porosity < 0.45);
    CHECK(k.edge() == Approx(spec.genesis.edge).epsilon(0.1));
}
