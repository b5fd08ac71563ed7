// The direct-tension test's config and result files: the optional [tension] table (defaults,
// unknown keys and out-of-range values rejected with file, line, key and rule), the compression
// reference check (same material and specimen, a compression macro.json only) and macro.json
// (tension headline keys, σc/σt, null for NaN).
#include "../input_files.hpp"
#include "../temp_dir.hpp"
#include <catch2/catch.hpp>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>

#include "common/input_error.hpp"
#include "experiments/config/cube_config.hpp"
#include "core/bond_models.hpp"
#include "experiments/config/tension_config.hpp"
#include "reports/cube_output.hpp"
#include "reports/tension_output.hpp"

using namespace gradem;
using namespace gradem::exp;
using namespace gradem::report;
namespace fs = std::filesystem;
using Catch::Matchers::Contains;

namespace {

using test::TempDir;
using test::write_file;

const std::string kSieve = "sieve,opening_mm,percent_passing\n#16,1.18,100\n#50,0.3,50\n#100,0.149,0\n";
const std::string kHead = "[specimen]\nsieve_csv = \"sand.csv\"\n[test]\nmax_strain = 0.02\n";

void require_rejected(const fs::path& file, int line, std::initializer_list<std::string> parts) {
    test::require_input_error([&] { (void)load_tension_config(load_cube_config(file)); }, file, line, parts);
}

// A tension result with a three-point curve, σt = 5 MPa.
TensionTestResult small_result() {
    TensionTestResult t;
    for (int s = 0; s < 3; ++s) {
        CurvePoint p;
        p.step = 100 + 50 * s;
        p.platen_strain = 1e-4 * s;
        p.gauge_strain = 0.8e-4 * s;
        p.stress = 2.5e6 * s;
        t.cube.test.curve.push_back(p);
    }
    t.cube.macro.peak_stress_pa = 5e6;
    t.cube.macro.chord_modulus_pa = 20e9;
    t.cube.macro.poisson_ratio = std::nan("");
    BreakEvent e;
    e.mode = BondState::broken_tension;
    t.cube.cracks = {e, e};
    t.grip_grains_bottom = 7;
    t.grip_grains_top = 9;
    return t;
}

Packing tiny_packing() {
    Packing k;
    k.box_hi = {1e-3, 1e-3, 1e-3};
    k.position = {{5e-4, 5e-4, 5e-4}};
    k.radius = {2e-4};
    return k;
}

/// An empty 3 mm box of sand density: what the automatic rate reads of a packing.
Packing three_mm_packing() {
    Packing k;
    k.box_hi = {3e-3, 3e-3, 3e-3};
    k.density = 2640.0;
    return k;
}

}  // namespace

TEST_CASE("[tension] is optional, read with the cube config, and takes the test's loading", "[tension_config]") {
    const TempDir dir("tension-config");
    write_file(dir.path / "sand.csv", kSieve);
    const CubeConfig plain = load_cube_config(write_file(dir.path / "plain.toml", kHead));
    const TensionConfig defaults = load_tension_config(plain);
    CHECK(defaults.spec.grip_depth_fraction == TensionTestSpec{}.grip_depth_fraction);
    CHECK(defaults.auto_peak_strain == TensionConfig{}.auto_peak_strain);
    CHECK(defaults.auto_transits == 100.0);
    CHECK(defaults.spec.test.loading.max_strain == 0.02);

    const CubeConfig with = load_cube_config(write_file(dir.path / "with.toml", kHead +
                                                   "[tension]\ngrip_depth_fraction = 0.05\nauto_peak_strain = 5e-4\nauto_transits = 250\n"));
    const TensionConfig t = load_tension_config(with);
    CHECK(t.spec.grip_depth_fraction == 0.05);
    CHECK(t.auto_peak_strain == 5e-4);
    CHECK(t.auto_transits == 250.0);
    CHECK(with.test.loading.max_strain == 0.02);  // the compression reader accepts (and ignores) [tension]

    SECTION("the auto strain rate: compression's rule at the expected tensile peak strain, with its own transits") {
        const Packing k = three_mm_packing();
        CubeConfig automatic = with;
        automatic.auto_strain_rate = true;
        const double rate = tension_strain_rate(automatic, t, k);
        CHECK(rate == Approx(quasi_static_strain_rate(k, with.material, 5e-4, 250.0)));
        // compression expects a peak at 0.003 after 200 transits; this pull 5e-4 after 250
        CHECK(rate / strain_rate_for(automatic, k) == Approx(5e-4 / 0.003 * 200.0 / 250.0));
        TensionConfig fewer = t;
        fewer.auto_transits = 125.0;  // half the transits: twice the rate
        CHECK(tension_strain_rate(automatic, fewer, k) == Approx(2.0 * rate));
        CHECK(tension_strain_rate(with, t, k) == with.test.loading.strain_rate);
    }
    SECTION("without auto_peak_strain the expected tensile peak strain comes from the material") {
        const Packing k = three_mm_packing();
        CubeConfig automatic = plain;
        automatic.auto_strain_rate = true;
        automatic.material.bond.tensile_strength_mean = 16.0e6;
        automatic.material.bond.effective_modulus = 8.0e9;
        const double expected = 0.5 * 16.0e6 / 8.0e9;  // 0.5 σ̄_c/Ē = 1e-3
        CHECK(expected_tensile_peak_strain(automatic.material) == Approx(expected));
        // the default: 100 transits, twice compression's rate for the same expected peak
        const double rule = quasi_static_strain_rate(k, automatic.material, expected);
        CHECK(tension_strain_rate(automatic, defaults, k) == Approx(2.0 * rule));
        automatic.material.bond.tensile_strength_mean *= 2.0;  // stronger bonds: a later peak, a faster pull
        CHECK(tension_strain_rate(automatic, defaults, k) == Approx(4.0 * rule));
    }
    SECTION("the expected tensile peak strain is the bond law's: flat joints peak later than parallel bonds") {
        MaterialParams m = plain.material;
        m.bond.tensile_strength_mean = 16.0e6;
        m.bond.effective_modulus = 8.0e9;
        m.bond.model = BondModel::parallel_bond;
        const double parallel = expected_tensile_peak_strain(m);
        m.bond.model = BondModel::flat_joint;
        const double joint = expected_tensile_peak_strain(m);
        CHECK(joint == Approx(FlatJointLaw::kPlatenTestCost.tension_peak_over_bond_strain * 2e-3));
        CHECK(joint / parallel == Approx(0.75 / 0.5));  // the laws' measured rows
        m.bond.model = BondModel::soft_bond;  // a law without a row: 0.5 σ̄_c/Ē
        CHECK(expected_tensile_peak_strain(m) == Approx(0.5 * 2e-3));
    }
}

TEST_CASE("bad [tension] tables are rejected with file, line, key and rule", "[tension_config]") {
    const TempDir dir("tension-config-bad");
    write_file(dir.path / "sand.csv", kSieve);
    const fs::path file = dir.path / "bad.toml";
    write_file(file, kHead + "[tension]\ngrip_depth = 0.1\n");
    require_rejected(file, 6, {"unknown key 'tension.grip_depth'", "grip_depth_fraction"});
    write_file(file, kHead + "[tension]\ngrip_depth_fraction = 0.3\n");
    require_rejected(file, 6, {"key 'tension.grip_depth_fraction' = 0.3 violates in [0, 0.25)"});
    write_file(file, kHead + "[tension]\ngrip_depth_fraction = \"deep\"\n");
    require_rejected(file, 6, {"key 'tension.grip_depth_fraction' = \"deep\"", "expected a number"});
    write_file(file, kHead + "[tension]\nauto_peak_strain = 0\n");
    require_rejected(file, 6, {"key 'tension.auto_peak_strain' = 0", "violates in (0, 0.01)"});
    write_file(file, kHead + "[tension]\ngrip_depth_fraction = 0.1\nauto_transits = 5\n");
    require_rejected(file, 7, {"key 'tension.auto_transits' = 5", "violates in [10, 10000]"});
    write_file(file, "tension = 3\n" + kHead);
    require_rejected(file, 1, {"'tension' must be a table"});
}

TEST_CASE("tension macro.json: tension keys, σc/σt from a matching compression macro.json", "[tension_output]") {
    const TempDir dir("tension-output");
    CubeConfig c;
    const Packing k = tiny_packing();
    const TensionTestResult t = small_result();
    const TensionTestSpec spec;

    CubeTestResult compression;
    compression.macro.peak_stress_pa = 40e6;
    compression.macro.chord_modulus_pa = 25e9;
    const fs::path compression_file = write_file(dir.path / "macro.json", macro_json(compression, c, k, 1.0));
    const CompressionReference ref = read_compression_reference(compression_file, c, k);
    CHECK(ref.peak_stress == Approx(40e6));
    CHECK(ref.chord_modulus == Approx(25e9));

    const auto j = nlohmann::json::parse(tension_macro_json(t, c, spec, k, 2.0, std::nullopt, ref));
    CHECK(j["test"] == "direct tension");
    CHECK(j["tensile_strength_mpa"].get<double>() == Approx(5.0));
    CHECK(j["tensile_modulus_mpa"].get<double>() == Approx(20e3));
    CHECK(j["strength_ratio_c_over_t"].get<double>() == Approx(8.0));
    CHECK(j["compression"]["modulus_ratio_t_over_c"].get<double>() == Approx(0.8));
    CHECK(j["poisson_ratio"].is_null());
    CHECK(j["broken_bonds"]["tension"] == 2);
    CHECK(j["grips"]["grains_top"] == 9);
    CHECK(j["run"]["strain_rate_per_s"].get<double>() == 2.0);
    CHECK(j["material"]["display"].contains("tensile_strength_mpa"));

    const auto alone = nlohmann::json::parse(tension_macro_json(t, c, spec, k, 2.0));
    CHECK(alone["strength_ratio_c_over_t"].is_null());
    CHECK(alone["compression"].is_null());

    SECTION("another material is refused") {
        CubeConfig other = c;
        other.material.bond.tensile_strength_mean *= 2.0;
        CHECK_THROWS_WITH(read_compression_reference(compression_file, other, k),
                          Contains(compression_file.string()) && Contains("another material"));
    }
    SECTION("a tension macro.json is not a compression reference") {
        const fs::path tension_file = write_file(dir.path / "t.json", tension_macro_json(t, c, spec, k, 2.0));
        CHECK_THROWS_WITH(read_compression_reference(tension_file, c, k), Contains("not the macro.json of a compression test"));
    }
    SECTION("files are written atomically into the folder") {
        write_tension_outputs(dir.path / "tension", t, c, spec, k, 2.0, std::nullopt, ref);
        for (const char* name : {"load_curve.csv", "cracks.csv", "macro.json"}) CHECK(fs::exists(dir.path / "tension" / name));
    }
}
