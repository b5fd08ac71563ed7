// The branch-free forms the flat joint's pass runs across lanes (core/disc_elements_branchless.hpp,
// portable_atan2_branchless in core/portable_math.hpp) against the branching code they stand
// for: the same bits for every argument, on random gap fields over several disc layouts (every
// case the closed form distinguishes: compressed, open, cut once or twice, kinks on one or both
// arcs, a level gap field), so the pass's results do not depend on which form ran.
#include <catch2/catch.hpp>

#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>
#include <random>
#include <vector>

#include "core/disc_elements_branchless.hpp"

using namespace gradem;

namespace {

std::uint64_t bits(double x) { return std::bit_cast<std::uint64_t>(x); }

/// compressed_part as the flat joint's scalar kernel calls it (its ZeroLineCache's gap field and
/// arc crossings).
CompressedPart branching(const DiscElement& g, double gamma, double wy, double wz) {
    const GapField f = gap_field(gamma, wy, wz);
    return compressed_part(g, f, arc_crossing(f, g.r0), arc_crossing(f, g.r1));
}

CompressedPart branchless(const DiscElement& g, bool inner_kinks, double gamma, double wy, double wz) {
    return inner_kinks ? compressed_part_branchless<true>(sector_bounds(g), gamma, wy, wz)
                       : compressed_part_branchless<false>(sector_bounds(g), gamma, wy, wz);
}

bool same_bits(const CompressedPart& a, const CompressedPart& b) {
    return bits(a.force) == bits(b.force) && bits(a.py) == bits(b.py) && bits(a.pz) == bits(b.pz) &&
           bits(a.energy) == bits(b.energy);
}

}  // namespace

TEST_CASE("portable_atan2_branchless: the bits of portable_atan2 for every argument", "[core][math]") {
    std::mt19937_64 rng(7);
    std::uniform_real_distribution<double> unit(-1.0, 1.0);
    std::uniform_int_distribution<int> exponent(-1060, 1020);
    int mismatches = 0, checked = 0;
    for (int n = 0; n < 400000; ++n) {
        const double y = std::ldexp(unit(rng), n % 4 == 0 ? exponent(rng) : 0);
        const double x = std::ldexp(unit(rng), n % 4 == 1 ? exponent(rng) : 0);
        mismatches += bits(portable_atan2_branchless(y, x)) != bits(portable_atan2(y, x));
        ++checked;
    }
    const double inf = std::numeric_limits<double>::infinity(), nan = std::numeric_limits<double>::quiet_NaN();
    const double specials[] = {0.0, -0.0, 1.0, -1.0, inf, -inf, nan, 0x1p-1074, -0x1p-1074, 0x1.fffffffffffffp1023, 3.0, -7.5};
    for (double y : specials)
        for (double x : specials) {
            const double a = portable_atan2_branchless(y, x), b = portable_atan2(y, x);
            mismatches += std::isnan(b) ? !std::isnan(a) : bits(a) != bits(b);
            ++checked;
        }
    CHECK(checked == 400144);
    CHECK(mismatches == 0);
}

TEST_CASE("compressed_part_branchless: the bits of compressed_part on every layout and gap field", "[core][flat_joint]") {
    std::mt19937_64 rng(11);
    std::uniform_real_distribution<double> unit(-1.0, 1.0);
    struct Layout {
        std::int32_t nr, na;
    };
    for (const Layout layout : {Layout{1, 4}, Layout{1, 1}, Layout{1, 3}, Layout{2, 4}, Layout{3, 6}, Layout{1, 8}}) {
        const std::vector<DiscElement> elements = disc_elements(layout.nr, layout.na);
        const bool inner_kinks = layout.nr > 1;
        int mismatches = 0, cut = 0, loaded = 0, cases = 0;
        for (int n = 0; n < 20000; ++n) {
            // |w| about 1e-6 m with γ within ±1.2 |w|: the zero line crosses the disc in most cases,
            // often one element twice; every 16th field level (w = 0), every 8th without a gap at
            // the centre
            const double wy = n % 16 == 0 ? 0.0 : 1e-6 * unit(rng), wz = n % 16 == 0 ? 0.0 : 1e-6 * unit(rng);
            const double slope = std::hypot(wy, wz);
            const double gamma = n % 8 == 3 ? 0.0 : (slope > 0.0 ? 1.2 * slope * unit(rng) : 1e-6 * unit(rng));
            for (const DiscElement& g : elements) {
                const CompressedPart want = branching(g, gamma, wy, wz);
                const CompressedPart got = branchless(g, inner_kinks, gamma, wy, wz);
                mismatches += !same_bits(want, got);
                const double spread = slope * g.reach, centroid_gap = gamma + wy * g.y + wz * g.z;
                cut += centroid_gap - spread < 0.0 && centroid_gap + spread > 0.0;
                loaded += want.force != 0.0;
                ++cases;
            }
        }
        INFO("layout " << layout.nr << " x " << layout.na);
        CHECK(mismatches == 0);
        CHECK(cut > cases / 4);     // the closed form's cases were reached: cut elements,
        CHECK(loaded > cases / 4);  // compressed ones
        CHECK(loaded < cases);      // and open ones
    }
}
