// Explicit paste: the mix design's volume fractions against hand computation and
// Powers' numbers (docs/genesis.md "Mix design"); bad mixes name the key; a paste fill of a sand lattice
// matches the mix design's fractions within a stated tolerance, leaves no paste particle
// overlapping a sand grain beyond the tolerance, and refuses a size that would not fit memory.
#include <catch2/catch.hpp>

#include <cmath>

#include "core/neighbor_search.hpp"
#include "experiments/paste/paste_fill.hpp"
#include "experiments/paste/paste_mix.hpp"

using namespace gradem;
using namespace gradem::exp;

namespace {

MixDesign study_mix() {
    MixDesign m;  // 1 : 2.6 by loose volume, w/c 0.53, SG 3.15 / 2.64 (the study)
    m.sand_specific_gravity = 2.64;
    return m;
}

// A BCC lattice of equal sand grains (radius R): cell a = (2 · 4/3 π R³ / 0.67)^(1/3) = 2.321 R,
// nearest centres √3/2 a = 2.010 R apart (no overlaps), 2 n³ grains; the box touches the outer
// grains (solid fraction 0.67 n³ / (n + 0.362)³: 0.517 for n = 4).
Packing bcc_sand(int n, double radius) {
    const double a = std::cbrt(2.0 * 4.0 / 3.0 * M_PI * radius * radius * radius / 0.67);
    Packing k;
    for (int i = 0; i < n; ++i)
        for (int j = 0; j < n; ++j)
            for (int l = 0; l < n; ++l) {
                k.position.push_back({(i + 0.25) * a, (j + 0.25) * a, (l + 0.25) * a});
                k.position.push_back({(i + 0.75) * a, (j + 0.75) * a, (l + 0.75) * a});
                k.radius.insert(k.radius.end(), 2, radius);
            }
    k.density = 2640.0;
    const double lo = 0.25 * a - radius, hi = (n - 0.25) * a + radius;
    k.box_lo = {lo, lo, lo};
    k.box_hi = {hi, hi, hi};
    k.converged = true;
    return k;
}

}  // namespace

TEST_CASE("mix design: absolute volume fractions of the study's mortar by hand", "[paste]") {
    // Per unit bulk volume of cement: m_c = 1506, m_s = 1280 x 2.6 = 3328, m_w = 0.53 x 1506 = 798.18 kg;
    // V_c = 1506/3150 = 0.478095, V_s = 3328/2640 = 1.260606, V_w = 0.79818 m³; sum 2.536881.
    const MixFractions f = mix_fractions(study_mix());
    CHECK(f.sand == Approx(1.260606 / 2.536881).epsilon(1e-5));
    CHECK(f.cement == Approx(0.478095 / 2.536881).epsilon(1e-5));
    CHECK(f.water == Approx(0.79818 / 2.536881).epsilon(1e-5));
    CHECK(f.sand + f.paste + f.air == Approx(1.0).epsilon(1e-14));
    CHECK(f.sand_to_cement_mass == Approx(3328.0 / 1506.0));
    CHECK(f.paste_density == Approx((1506.0 + 798.18) / (0.478095 + 0.79818)).epsilon(1e-5));
    // A mortar's ranges (docs/genesis.md "Mix design"): sand 0.50-0.55, cement 0.17-0.19, water 0.28-0.32 (absolute volumes).
    CHECK(f.cement > 0.17);
    CHECK(f.cement < 0.19);

    MixDesign with_air = study_mix();
    with_air.air_content = 0.05;
    const MixFractions g = mix_fractions(with_air);
    CHECK(g.sand == Approx(0.95 * f.sand));
    CHECK(g.paste == Approx(0.95 * f.paste));
    CHECK(g.air == 0.05);
    CHECK(g.sand + g.paste + g.air == Approx(1.0).epsilon(1e-14));
}

TEST_CASE("mix design: Powers' split reproduces the hand computation (α 0.8, SG 3.2)", "[paste]") {
    MixDesign m = study_mix();
    m.cement_specific_gravity = 3.2;
    m.hydration_degree = 0.8;
    const MixFractions f = mix_fractions(m);
    // φ_cap = (0.53 - 0.359 x 0.8)/(0.53 + 0.3125) = 0.2884; unhydrated 0.2/(1 + 3.2 x 0.53) = 0.0742.
    CHECK(f.paste_capillary == Approx(0.2428 / 0.8425).epsilon(1e-4));
    CHECK(f.paste_unhydrated == Approx(0.2 / 2.696).epsilon(1e-4));
    CHECK(f.paste_hydrates == Approx(1.0 - f.paste_capillary - f.paste_unhydrated));
    m.hydration_degree = 0.0;  // fresh paste: all water is capillary space
    CHECK(mix_fractions(m).paste_capillary == Approx(0.53 / 0.8425));
}

TEST_CASE("mix design: bad input names the key and the rule", "[paste]") {
    MixDesign m = study_mix();
    m.sand_specific_gravity = 0.0;
    REQUIRE(m.invalid_reason());
    CHECK(m.invalid_reason()->find("sand_specific_gravity") == 0);
    CHECK_THROWS_WITH(mix_fractions(m), Catch::Contains("sand_specific_gravity"));
    m = study_mix();
    m.hydration_degree = 1.0;
    m.water_cement_ratio = 0.3;  // Powers: full hydration needs w/c >= 0.359
    CHECK_THROWS_WITH(mix_fractions(m), Catch::Contains("hydration_degree"));
    m = study_mix();
    m.sand_bulk_density = 3000.0;
    CHECK_THROWS_WITH(mix_fractions(m), Catch::Contains("sand_bulk_density"));
}

TEST_CASE("paste fill: volume fractions match the mix design, no paste inside sand", "[paste]") {
    const Packing sand = bcc_sand(4, 0.2e-3);  // 128 grains, box 2.0 mm
    const MixFractions mix = mix_fractions(study_mix());
    PasteSpec spec;
    spec.min_diameter = spec.max_diameter = 0.12e-3;
    PasteReport report;
    const Packing k = fill_paste(sand, mix, spec, 7, report);
    INFO(describe(report));
    REQUIRE(report.growth_reached == 1.0);
    // Sand: dilated exactly to the mix's fraction. Paste: the particle count is rounded from the
    // target volume, so the represented paste fraction is within half a particle of the mix's:
    // stated tolerance 2 % relative.
    CHECK(report.sand_fraction == Approx(mix.sand).epsilon(1e-12));
    CHECK(report.paste_fraction == Approx(mix.paste).epsilon(0.02));
    CHECK(report.void_fraction == Approx(mix.air).margin(0.02));
    CHECK(k.position.size() == k.family.size());
    CHECK(report.paste_count + report.sand_count == k.position.size());
    // Independent overlap check: every paste-sand pair overlaps less than the tolerance.
    std::vector<ParticlePair> pairs;
    make_neighbor_search()->find_pairs(k.position, k.radius, 0.0, pairs);
    double worst = 0.0;
    for (const ParticlePair& p : pairs) {
        const auto i = static_cast<std::size_t>(p.i), j = static_cast<std::size_t>(p.j);
        if (k.family[i] == k.family[j]) continue;
        const double ov = k.radius[i] + k.radius[j] - norm(k.position[j] - k.position[i]);
        worst = std::max(worst, ov / std::min(k.radius[i], k.radius[j]));
    }
    CHECK(worst < spec.overlap_tolerance);
    CHECK(report.max_overlap < spec.overlap_tolerance);
    // Every particle inside the box.
    for (std::size_t i = 0; i < k.position.size(); ++i) {
        CHECK(k.position[i].x - k.radius[i] >= k.box_lo.x - 1e-15);
        CHECK(k.position[i].z + k.radius[i] <= k.box_hi.z + 1e-15);
    }
    // The same seed gives the same specimen.
    PasteReport again;
    const Packing k2 = fill_paste(sand, mix, spec, 7, again);
    REQUIRE(k2.position.size() == k.position.size());
    for (std::size_t i = 0; i < k.position.size(); ++i) CHECK(norm2(k2.position[i] - k.position[i]) == 0.0);
}

TEST_CASE("paste fill: a cement size distribution truncated at the smallest size", "[paste]") {
    PasteSpec spec;
    spec.min_diameter = 0.04e-3;
    spec.max_diameter = 0.3e-3;
    // Expected count by mass sampling matches the integral of the Rosin-Rammler curve.
    const double n = expected_paste_count(spec, 1e-9);
    CHECK(n > 1e-9 / (M_PI / 6 * std::pow(0.3e-3, 3)));
    CHECK(n < 1e-9 / (M_PI / 6 * std::pow(0.04e-3, 3)));
    const lab::GradationCurve c = cement_size_curve();
    CHECK(c.passing_fraction(75e-6) > 0.95);  // a cement: >= 95 % below 75 µm (docs/genesis.md "Paste fill")
    CHECK(c.passing_fraction(1e-6) == Approx(0.089).margin(0.01));  // SRM 114p
}

TEST_CASE("paste fill: bad input is refused before anything is allocated", "[paste]") {
    const Packing sand = bcc_sand(4, 0.2e-3);
    PasteSpec spec;
    PasteReport report;
    SECTION("a lean mix whose paste cannot fill the sand's pore space") {
        MixDesign lean = study_mix();
        lean.sand_to_cementitious_volume = 8.0;  // sand fraction 0.73 > packed 0.6
        CHECK_THROWS_WITH(fill_paste(sand, mix_fractions(lean), spec, 1, report),
                          Catch::Contains("cannot fill the sand's pore space"));
    }
    SECTION("a smallest size that would exceed the machine's memory") {
        spec.min_diameter = spec.max_diameter = 0.05e-6;  // ~1e10 particles in a 1.2 mm box
        CHECK_THROWS_AS(fill_paste(sand, mix_fractions(study_mix()), spec, 1, report), PasteMemoryError);
        CHECK_THROWS_WITH(fill_paste(sand, mix_fractions(study_mix()), spec, 1, report),
                          Catch::Contains("GB") && Catch::Contains("paste.min_diameter_mm"));
    }
}
