// The bonding gap (experiments/virtual_tests/cube_test.hpp MaterialParams::bond_gap): bonds are installed
// between grains closer than the gap. A gap given as a fraction of the mean grain radius
// (bond_gap_fraction) is a shape: a packing and its copy at half the size get the same bonds.
// A gap given as a length (bond_gap_um, "the paste-bridge length, the same for every sand")
// is not: the finer copy gets more bonds per grain, exactly as many as the original with twice
// the gap. This is what lets one parameter set give a fine and a coarse sand different
// moduli and strengths (calibrate/README.md, the main job).
#include <catch2/catch.hpp>

#include "experiments/virtual_tests/cube_specimen.hpp"
#include "small_specimen.hpp"

using namespace gradem;
using namespace gradem::exp;
using gradem::test::small_material;
using gradem::test::small_packing;

namespace {

// The packing with every length × 0.5 (a power of two, so every distance halves exactly).
Packing half_size(const Packing& k) {
    Packing h = k;
    for (Vec3& x : h.position) x = 0.5 * x;
    for (double& r : h.radius) r *= 0.5;
    h.box_lo = 0.5 * h.box_lo;
    h.box_hi = 0.5 * h.box_hi;
    return h;
}

std::size_t bonds_installed(const Packing& k, const MaterialParams& m) {
    CubeTestSpec spec;
    spec.max_settle_steps = 0;  // the bond set is fixed at installation: no cycling needed
    CubeTestResult r;
    (void)settled_cube_specimen(k, m, spec, r);
    return r.bonds;
}

}  // namespace

TEST_CASE("a relative bonding gap bonds a packing and its half-size copy alike", "[experiments][bond_gap]") {
    MaterialParams m = small_material();
    m.bond_gap_fraction = 0.1;
    m.bond_gap_absolute = 0.0;
    const std::size_t original = bonds_installed(small_packing(), m);
    CHECK(original > small_packing().radius.size());  // a bonded specimen, not a handful of pairs
    CHECK(bonds_installed(half_size(small_packing()), m) == original);
}

TEST_CASE("an absolute bonding gap gives the finer copy more bonds, as twice the gap on the original",
          "[experiments][bond_gap]") {
    const double gap = 30e-6;  // [m]
    MaterialParams m = small_material();
    m.bond_gap_absolute = gap;
    const std::size_t original = bonds_installed(small_packing(), m);
    const std::size_t finer = bonds_installed(half_size(small_packing()), m);
    CHECK(finer > original);

    MaterialParams doubled = m;
    doubled.bond_gap_absolute = 2.0 * gap;
    CHECK(bonds_installed(small_packing(), doubled) == finer);
}
