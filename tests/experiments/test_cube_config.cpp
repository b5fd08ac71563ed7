// Cube-test config files: display units converted to SI once, defaults from the structs,
// relative paths, and each kind of bad input (unknown table or key, wrong type, out-of-range
// value) rejected with the file, line, key, value and rule. Also the shipped configs and the
// result writers (CSV columns, crack strain interpolation, null for NaN in macro.json).
#include "../input_files.hpp"
#include "../temp_dir.hpp"
#include <catch2/catch.hpp>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <set>
#include <string>
#include <vector>

#include <unistd.h>

#include "common/input_error.hpp"
#include "experiments/config/cube_config.hpp"
#include "experiments/config/material_table.hpp"
#include "experiments/virtual_tests/cube_specimen.hpp"
#include "reports/cube_output.hpp"

using namespace gradem;
using namespace gradem::exp;
using namespace gradem::report;
namespace fs = std::filesystem;
using Catch::Matchers::Contains;

namespace {

using test::TempDir;
using test::write_file;

const std::string kSieve =
    "sieve,opening_mm,percent_passing\n#4,4.75,100\n#16,1.18,98\n#50,0.3,70\n#100,0.149,25\n#200,0.075,0\n";

// A config whose key on line 3 (after two header lines) is `line3`.
std::string config_with(const std::string& table, const std::string& line3) {
    return "[specimen]\nsieve_csv = \"sand.csv\"\n" + std::string(table == "specimen" ? "" : "[" + table + "]\n") + line3 + "\n";
}

/// load_cube_config must throw an InputError at `line` whose message contains every `parts`.
void require_rejected(const fs::path& file, int line, std::initializer_list<std::string> parts) {
    test::require_input_error([&] { (void)load_cube_config(file); }, file, line, parts);
}

}  // namespace

TEST_CASE("a config converts display units to SI and resolves paths from its folder", "[cube_config]") {
    const TempDir dir("config-good");
    write_file(dir.path / "sand.csv", kSieve);
    const fs::path file = write_file(dir.path / "runs" / "c.toml", R"(
[specimen]
sieve_csv = "../sand.csv"
[size_rule]
min_diameter_mm = 0.3
max_diameter_mm = 2.0
scale = 1.5
[genesis]
edge_mm = 10.0
locked_in_stress_mpa = 0.2
reference_modulus_gpa = 5
density_kg_m3 = 2650
min_contacts = 4
max_steps = 5000
seed = 9
[material]
effective_modulus_gpa = 2.5
tensile_strength_mpa = 8
tensile_strength_cv = 0.25
cohesion_mpa = 16
friction_angle_deg = 30
platen_friction = 0.3
bond_seed = 11
[test]
strain_rate_per_s = 0.5
record_interval = 20
[output]
dir = "results"
cache_dir = "/tmp/somewhere/cache"
vtk = true
vtk_every = 5
)");
    const CubeConfig c = load_cube_config(file);
    CHECK(c.sieve_csv == (dir.path / "sand.csv").lexically_normal());
    CHECK(c.dataset.empty());
    CHECK(c.specimen.size_rule.min_diameter == Approx(0.3e-3));
    CHECK(c.specimen.size_rule.max_diameter == Approx(2.0e-3));
    CHECK(c.specimen.size_rule.scale == 1.5);
    CHECK(c.specimen.genesis.edge == Approx(10.0e-3));
    CHECK(c.specimen.genesis.locked_in_stress == Approx(0.2e6));
    CHECK(c.specimen.genesis.reference_modulus == Approx(5e9));
    CHECK(c.specimen.genesis.density == 2650);
    CHECK(c.specimen.genesis.min_contacts == 4);
    CHECK(c.specimen.genesis.max_steps == 5000);
    CHECK(c.specimen.seed == 9);
    CHECK(c.specimen.genesis.target_solid_fraction == GenesisSpec{}.target_solid_fraction);  // default
    CHECK(c.material.contact.effective_modulus == Approx(2.5e9));
    CHECK(c.material.bond.effective_modulus == Approx(2.5e9));  // defaults to the contact's
    CHECK(c.material.bond.stiffness_ratio == c.material.contact.stiffness_ratio);
    CHECK(c.material.bond.tensile_strength_mean == Approx(8e6));
    CHECK(c.material.bond.tensile_strength_std == Approx(2e6));  // cv x mean
    CHECK(c.material.bond.cohesion_mean == Approx(16e6));
    CHECK(c.material.bond.cohesion_std == 0.0);
    CHECK(c.material.bond.friction_angle_deg == 30);
    CHECK(c.material.bond.seed == 11);
    CHECK(c.material.platen_friction == 0.3);
    CHECK(c.test.loading.platen_friction == 0.3);
    CHECK(c.test.loading.strain_rate == 0.5);
    CHECK_FALSE(c.auto_strain_rate);
    CHECK(c.test.loading.record_interval == 20);
    CHECK(c.test.slab_fraction == CubeTestSpec{}.slab_fraction);
    CHECK(c.out_dir == (dir.path / "runs" / "results").lexically_normal());
    CHECK(c.cache_dir == fs::path("/tmp/somewhere/cache"));
    CHECK(c.vtk);
    CHECK(c.vtk_every == 5);
    CHECK(load_gradation(c).size_m.size() == 5);
}

TEST_CASE("a minimal config takes the struct defaults", "[cube_config]") {
    const TempDir dir("config-minimal");
    write_file(dir.path / "sand.csv", kSieve);
    const CubeConfig c = load_cube_config(write_file(dir.path / "m.toml", "[specimen]\nsieve_csv = \"sand.csv\"\n[test]\nstrain_rate_per_s = \"auto\"\n"));
    CHECK(c.auto_strain_rate);
    CHECK(c.material.contact.effective_modulus == ContactParams{}.effective_modulus);
    CHECK(c.material.bond.tensile_strength_mean == BondParams{}.tensile_strength_mean);
    CHECK(c.specimen.genesis.edge == GenesisSpec{}.edge);
    CHECK(c.test.loading.max_strain == PlatenTestSpec{}.max_strain);
    CHECK(c.out_dir == (dir.path / "out" / "m").lexically_normal());
    CHECK(c.cache_dir == (dir.path / "out" / "packing-cache").lexically_normal());
    CHECK_FALSE(c.vtk);
}

TEST_CASE("bad configs are rejected with file, line, key, value and rule", "[cube_config]") {
    const TempDir dir("config-bad");
    const fs::path file = dir.path / "bad.toml";
    write_file(dir.path / "sand.csv", kSieve);

    SECTION("unknown key") {
        write_file(file, config_with("material", "youngs = 3"));
        require_rejected(file, 4, {"unknown key 'material.youngs'", "known:", "effective_modulus_gpa"});
    }
    SECTION("unknown table") {
        write_file(file, config_with("materials", "friction = 3"));
        require_rejected(file, 3, {"unknown table '[materials]'", "known tables"});
    }
    SECTION("wrong type") {
        write_file(file, config_with("material", "friction = \"high\""));
        require_rejected(file, 4, {"key 'material.friction' = \"high\"", "expected a number"});
        write_file(file, config_with("genesis", "max_steps = 1.5"));
        require_rejected(file, 4, {"key 'genesis.max_steps'", "expected an integer"});
        write_file(file, config_with("test", "strain_rate_per_s = \"fast\""));
        require_rejected(file, 4, {"key 'test.strain_rate_per_s' = \"fast\"", "\"auto\""});
        write_file(file, config_with("output", "vtk = 1"));
        require_rejected(file, 4, {"key 'output.vtk' = 1", "true or false"});
        // Non-finite numbers never reach a validator (an infinite edge would exhaust memory in genesis).
        write_file(file, config_with("genesis", "edge_mm = inf"));
        require_rejected(file, 4, {"key 'genesis.edge_mm' = inf", "expected a finite number"});
        write_file(file, config_with("material", "friction = nan"));
        require_rejected(file, 4, {"key 'material.friction' = nan", "expected a finite number"});
    }
    SECTION("out of range, rule from the struct's validator") {
        write_file(file, config_with("material", "radius_multiplier = 1.5"));
        require_rejected(file, 4, {"key 'material.radius_multiplier' = 1.5 violates in (0, 1]"});
        write_file(file, config_with("genesis", "edge_mm = -2"));
        require_rejected(file, 4, {"key 'genesis.edge_mm' = -2 violates > 0", "genesis.edge = -0.002"});
        write_file(file, config_with("material", "tensile_strength_cv = -0.1"));
        require_rejected(file, 4, {"key 'material.tensile_strength_cv' = -0.1 violates >= 0"});
        write_file(file, config_with("material", "bond_modulus_gpa = 0"));
        require_rejected(file, 4, {"key 'material.bond_modulus_gpa' = 0 violates > 0"});
        write_file(file, config_with("material", "damping = 1.0"));
        require_rejected(file, 4, {"key 'material.damping' = 1.0 violates in [0, 1)"});
        write_file(file, config_with("test", "stop_fraction = 2"));
        require_rejected(file, 4, {"key 'test.stop_fraction' = 2 violates in (0, 1)"});
        write_file(file, config_with("test", "slab_fraction = 0.7"));
        require_rejected(file, 4, {"key 'test.slab_fraction' = 0.7 violates in (0, 0.5)"});
        write_file(file, config_with("genesis", "seed = -1"));
        require_rejected(file, 4, {"key 'genesis.seed' = -1 violates in [0,"});
        write_file(file, config_with("output", "vtk_every = -3"));
        require_rejected(file, 4, {"key 'output.vtk_every' = -3 violates in [0,"});
    }
    SECTION("specimen source") {
        write_file(file, "[specimen]\nsand = \"x\"\n");
        require_rejected(file, 0, {"either dataset"});
        write_file(file, "[specimen]\ndataset = \"d\"\n");
        require_rejected(file, 2, {"'specimen.sand' is required"});
    }
    SECTION("TOML syntax") {
        write_file(file, "[specimen]\nsieve_csv = \"sand.csv\"\n[test]\nmax_strain = = 3\n");
        require_rejected(file, 4, {});
    }
}

TEST_CASE("the shipped configs load and name a sand of the study", "[cube_config]") {
    const fs::path configs = fs::path(GRADEM_SOURCE_DIR) / "experiments" / "configs";
    for (const char* name : {"default_cube.toml", "verification_cube.toml"}) {
        INFO(name);
        const CubeConfig c = load_cube_config(configs / name);
        CHECK(c.sand == "pre-blended");
        CHECK(load_gradation(c).passing.back() == 1.0);
    }
    CubeConfig c = load_cube_config(configs / "default_cube.toml");
    c.sand = "no such sand";
    CHECK_THROWS_WITH(load_gradation(c), Contains("'no such sand' is not a sand") && Contains("Van Buren"));
}

TEST_CASE("result writers: curve and crack CSVs, macro.json with null for NaN", "[cube_output]") {
    CubeTestResult r;
    for (int s = 0; s < 3; ++s) {
        CurvePoint p;
        p.step = 100 + 50 * s;
        p.platen_strain = 0.001 * s;
        p.gauge_strain = 0.0008 * s;
        p.lateral_strain = std::nan("");
        p.stress = 1e6 * s;
        r.test.curve.push_back(p);
    }
    BreakEvent e;
    e.step = 125;  // halfway between the first two points
    e.mode = BondState::broken_shear;
    r.cracks.push_back(e);
    r.macro.poisson_ratio = std::nan("");
    r.test.stop_reason = "post-peak";
    const std::string curve = load_curve_csv(r);
    CHECK_THAT(curve, Contains("step,time_s,platen_strain,gauge_strain,lateral_strain,stress_mpa"));
    const std::string cracks = cracks_csv(r);
    CHECK_THAT(cracks, Contains("\n125,0,0.0005,"));
    CHECK_THAT(cracks, Contains(",shear,"));

    CubeConfig c;
    Packing k;
    k.box_hi = {1e-3, 1e-3, 1e-3};
    CubeTestResult half = r;
    half.macro.peak_stress_pa = 2e6;
    r.macro.peak_stress_pa = 2.1e6;
    const RateCheck check = compare_rates(r, half, 1.0);
    const auto j = nlohmann::json::parse(macro_json(r, c, k, 1.0, check));
    CHECK(j["poisson_ratio"].is_null());
    CHECK(j["peak_stress_mpa"].get<double>() == Approx(2.1));
    CHECK(j["broken_bonds"]["shear"] == 1);
    CHECK(j["rate_check"]["peak_change"].get<double>() == Approx(-0.1 / 2.1));
    CHECK(j["rate_check"]["half_rate_per_s"].get<double>() == 0.5);
    CHECK(j.contains("chord_modulus_mpa"));
    CHECK(j.contains("strain_at_peak"));
    CHECK(j["material"]["display"].contains("tensile_strength_mpa"));
}

namespace {

/// A cube test whose two ends differ by `gap` (relative) over its whole rise to a 20 MPa peak
/// at platen strain 1e-3, reduced as a run's result is (platen_imbalance, warnings).
CubeTestResult uneven_ends(double gap) {
    CubeTestResult r;
    for (int k = 1; k <= 130; ++k) {
        CurvePoint p;
        p.platen_strain = p.gauge_strain = 1e-5 * k;
        p.stress = k <= 100 ? 20e6 * k / 100.0 : 20e6 * (1.0 - 0.01 * (k - 100));
        p.stress_top = p.stress * (1.0 + 0.5 * gap);
        p.stress_bottom = p.stress * (1.0 - 0.5 * gap);
        p.lateral_strain = 0.2 * p.gauge_strain;
        p.time = 1e-3 * k;
        r.test.curve.push_back(p);
    }
    r.test.peak_stress = 20e6;
    r.test.strain_at_peak = 1e-3;
    reduce_cube_result(r, CubeTestSpec{});  // imbalance_warning 0.02
    return r;
}

}  // namespace

TEST_CASE("rate check: an end-stress imbalance that halves with the rate is inertia, one that stays is not",
          "[cube_output]") {
    const double limit = CubeTestSpec{}.imbalance_warning;
    const CubeTestResult at_rate = uneven_ends(0.03);
    REQUIRE(at_rate.platen_imbalance == Approx(0.03).epsilon(1e-9));
    REQUIRE(at_rate.warnings.size() == 1);
    CHECK_THAT(at_rate.warnings[0], Contains("unequal end stresses") && Contains("3 %") && Contains("--check-rate"));
    SECTION("inertia: 3 % at the rate, 1.5 % at half of it") {
        const RateCheck check = compare_rates(at_rate, uneven_ends(0.015), 1.0);
        CHECK(check.imbalance == Approx(0.03).epsilon(1e-9));
        CHECK(check.imbalance_half == Approx(0.015).epsilon(1e-9));
        CHECK(check.imbalance_falls());
        CHECK_THAT(imbalance_verdict(check, limit), Contains("3.00 %") && Contains("1.50 %") && Contains("inertia (it falls") &&
                                                         Contains("lower the strain rate"));
        const auto j = nlohmann::json::parse(macro_json(at_rate, CubeConfig{}, Packing{}, 1.0, check));
        CHECK(j["rate_check"]["platen_imbalance"].get<double>() == Approx(0.03));
        CHECK(j["rate_check"]["platen_imbalance_half_rate"].get<double>() == Approx(0.015));
        CHECK(j["rate_check"]["imbalance_falls_with_rate"] == true);
    }
    SECTION("cracks: 3 % at the rate, 2.8 % at half of it") {
        const RateCheck check = compare_rates(at_rate, uneven_ends(0.028), 1.0);
        CHECK_FALSE(check.imbalance_falls());
        const std::string verdict = imbalance_verdict(check, limit);
        CHECK_THAT(verdict, Contains("2.80 %") && Contains("not inertia") && Contains("cracks ahead of the peak"));
        CHECK_THAT(verdict, !Contains("lower the strain rate"));
        const auto j = nlohmann::json::parse(macro_json(at_rate, CubeConfig{}, Packing{}, 1.0, check));
        CHECK(j["rate_check"]["imbalance_falls_with_rate"] == false);
    }
    SECTION("under the limit at the rate: nothing to say") {
        const CubeTestResult even = uneven_ends(0.01);
        CHECK(even.warnings.empty());
        CHECK(imbalance_verdict(compare_rates(even, uneven_ends(0.01), 1.0), limit).empty());
    }
}

TEST_CASE("bond model keys: each model reads its own parameters, in SI, and macro.json shows them", "[cube_config]") {
    const TempDir dir("config-models");
    write_file(dir.path / "sand.csv", kSieve);
    SECTION("soft bond") {
        const CubeConfig c = load_cube_config(write_file(dir.path / "s.toml", "[specimen]\nsieve_csv = \"sand.csv\"\n[material]\n"
                                                                       "model = \"soft_bond\"\nsoftening_factor = 0.4\ncut_fraction = 0.1\n"));
        CHECK(c.material.bond.model == BondModel::soft_bond);
        CHECK(c.material.bond.law<SoftBondLaw>().softening_factor == 0.4);
        CHECK(c.material.bond.law<SoftBondLaw>().cut_fraction == 0.1);
        CHECK(c.material.bond.replaces_contact);  // the default: one spring set (PFC softbond)
        const auto j = nlohmann::json::parse(macro_json(CubeTestResult{}, c, Packing{}, 1.0))["material"];
        CHECK(j["display"]["model"] == "soft_bond");
        CHECK(j["display"]["softening_factor"] == 0.4);
        CHECK(j["si"]["soft_bond"]["cut_fraction"] == 0.1);
        CHECK_FALSE(j["display"].contains("radial_elements"));
    }
    SECTION("flat joint") {
        const CubeConfig c = load_cube_config(write_file(dir.path / "f.toml", "[specimen]\nsieve_csv = \"sand.csv\"\n[material]\n"
                                                                       "model = \"flat_joint\"\nradial_elements = 2\n"
                                                                       "angular_elements = 3\nresidual_friction = 0.6\n"
                                                                       "unbonded_stiffness_ratio = 0.35\n"
                                                                       "bond_replaces_contact = false\n"));
        CHECK(c.material.bond.model == BondModel::flat_joint);
        CHECK_FALSE(c.material.bond.replaces_contact);
        CHECK(c.material.bond.law<FlatJointLaw>().radial_elements == 2);
        CHECK(c.material.bond.law<FlatJointLaw>().angular_elements == 3);
        CHECK(c.material.bond.law<FlatJointLaw>().residual_friction == 0.6);
        CHECK(c.material.bond.law<FlatJointLaw>().unbonded_stiffness_ratio == 0.35);
        const auto j = nlohmann::json::parse(macro_json(CubeTestResult{}, c, Packing{}, 1.0))["material"];
        CHECK(j["si"]["flat_joint"]["angular_elements"] == 3);
        CHECK_FALSE(j["display"].contains("softening_factor"));
    }
    SECTION("parallel bond by default, and without the other models' keys in macro.json") {
        const CubeConfig c = load_cube_config(write_file(dir.path / "p.toml", "[specimen]\nsieve_csv = \"sand.csv\"\n"));
        CHECK(c.material.bond.model == BondModel::parallel_bond);
        const auto j = nlohmann::json::parse(macro_json(CubeTestResult{}, c, Packing{}, 1.0))["material"];
        CHECK(j["display"]["model"] == "parallel_bond");
        CHECK_FALSE(j["si"].contains("soft_bond"));
        CHECK_FALSE(j["si"].contains("flat_joint"));
    }
}

TEST_CASE("bad bond model keys name the file, line, key and what is allowed", "[cube_config]") {
    const TempDir dir("config-bad-models");
    const fs::path file = dir.path / "bad.toml";
    write_file(dir.path / "sand.csv", kSieve);
    SECTION("unknown model: the known ones are listed") {
        write_file(file, config_with("material", "model = \"damage\""));
        require_rejected(file, 4, {"key 'material.model' = \"damage\"", "unknown bond model", "parallel_bond, soft_bond, flat_joint"});
        write_file(file, config_with("material", "model = 3"));
        require_rejected(file, 4, {"key 'material.model' = 3", "expected a string"});
    }
    SECTION("a parameter of another model") {
        write_file(file, config_with("material", "model = \"flat_joint\"\nsoftening_factor = 0.3"));
        require_rejected(file, 5, {"key 'material.softening_factor' belongs to bond model soft_bond", "material.model = \"flat_joint\" (line 4)"});
        write_file(file, config_with("material", "radial_elements = 2"));
        require_rejected(file, 4, {"key 'material.radial_elements' belongs to bond model flat_joint", "\"parallel_bond\" (the default)",
                                   "set model = \"flat_joint\""});
        write_file(file, config_with("material", "model = \"soft_bond\"\nresidual_friction = 0.5"));
        require_rejected(file, 5, {"'material.residual_friction' belongs to bond model flat_joint"});
        write_file(file, config_with("material", "bond_replaces_contact = true"));
        require_rejected(file, 4, {"'material.bond_replaces_contact' belongs to bond model soft_bond, flat_joint"});
        write_file(file, config_with("material", "model = \"soft_bond\"\nbond_replaces_contact = 1"));
        require_rejected(file, 5, {"key 'material.bond_replaces_contact' = 1: expected true or false"});
    }
    SECTION("shape parameters out of range") {
        for (const auto& [line, expected] : std::vector<std::pair<std::string, std::string>>{
                 {"softening_factor = 0", "key 'material.softening_factor' = 0 violates > 0"},
                 {"softening_factor = -0.5", "key 'material.softening_factor' = -0.5 violates > 0"},
                 {"cut_fraction = 1.0", "key 'material.cut_fraction' = 1.0 violates in [0, 1)"},
                 {"cut_fraction = -0.1", "key 'material.cut_fraction' = -0.1 violates in [0, 1)"}}) {
            write_file(file, config_with("material", "model = \"soft_bond\"\n" + line));
            require_rejected(file, 5, {expected});
        }
        for (const auto& [line, expected] : std::vector<std::pair<std::string, std::string>>{
                 {"radial_elements = 0", "key 'material.radial_elements' = 0 violates in [1, 64]"},
                 {"angular_elements = -3", "key 'material.angular_elements' = -3 violates in [1, 64]"},
                 {"angular_elements = 10000000000", "key 'material.angular_elements' = 10000000000 violates in [1, 64]"},
                 {"radial_elements = 1.5", "key 'material.radial_elements' = 1.5: expected an integer"},
                 {"residual_friction = -0.2", "key 'material.residual_friction' = -0.2 violates >= 0"},
                 {"bonded_fraction = 1.2", "key 'material.bonded_fraction' = 1.2 violates in [0, 1]"},
                 {"gapped_fraction = -0.1", "key 'material.gapped_fraction' = -0.1 violates in [0, 1]"},
                 {"gap_ratio = -0.01", "key 'material.gap_ratio' = -0.01 violates >= 0"},
                 {"unbonded_stiffness_ratio = 0", "key 'material.unbonded_stiffness_ratio' = 0 violates in (0, 1]"},
                 {"unbonded_stiffness_ratio = 1.5", "key 'material.unbonded_stiffness_ratio' = 1.5 violates in (0, 1]"},
                 {"friction_angle_deg = 90", "key 'material.friction_angle_deg' = 90 violates in [0, 90)"},
                 {"stiffness_over_gap = 1", "key 'material.stiffness_over_gap' = 1: expected true or false"}}) {
            write_file(file, config_with("material", "model = \"flat_joint\"\n" + line));
            require_rejected(file, 5, {expected});
        }
    }
    SECTION("joint-type fractions that sum over 1 name the key and the rule") {
        write_file(file, config_with("material", "model = \"flat_joint\"\nbonded_fraction = 0.7\ngapped_fraction = 0.5"));
        require_rejected(file, 6, {"material.gapped_fraction", "the fractions sum to at most 1"});
    }
}

TEST_CASE("material table: one row per key, defaults in range, ranges agree with core's validators", "[material_table]") {
    std::set<std::string> keys;
    MaterialParams defaults;
    for (const MaterialParameter& p : material_table()) {
        INFO(p.key);
        CHECK(keys.insert(std::string(p.key)).second);
        CHECK_FALSE(p.unit.empty());
        CHECK_FALSE(p.description.empty());
        if (p.in_config) CHECK_FALSE(p.si_name.empty());
        if (p.integer) CHECK((p.get_int && p.set_int));
        if (!p.follows.empty()) CHECK(find_material_parameter(p.follows) != nullptr);
        if (!p.cv_of.empty()) CHECK(find_material_parameter(p.cv_of) != nullptr);
        if (p.calibration == Calibration::free) {
            CHECK(p.lower < p.upper);
            if (p.log_scale) CHECK(p.lower > 0.0);
        }
        if (p.in_config && !p.integer) {  // config units <-> SI round trip
            MaterialParams m;
            set_config_value(p, m, 0.37);
            CHECK(config_value(p, m) == Approx(0.37));
        }
        // The struct default of every model's rows is valid.
        MaterialParams m;
        for (BondModel b : bond_models()) {
            m.bond.model = b;
            CHECK_FALSE(m.invalid_reason().has_value());
        }
        // Just below the lower bound: the table says so in config units, and if core checks
        // the field too, its message names a field that maps back to this row.
        if (p.flag) CHECK((p.integer && p.range.lower == 0.0 && p.range.upper == 1.0));  // a yes/no: nothing below it
        if (p.in_config && !p.flag && std::isfinite(p.range.lower) && p.applies_to(BondModel::parallel_bond) == false) {
            m.bond.model = p.applies_to(BondModel::soft_bond) ? BondModel::soft_bond : BondModel::flat_joint;
            const double below = p.range.lower_open ? p.range.lower : p.range.lower - 1.0;
            if (p.integer) p.set_int(m, static_cast<std::int64_t>(below));
            else set_config_value(p, m, below);
            const auto why = material_range_violation(m);
            REQUIRE(why.has_value());
            CHECK_THAT(*why, Contains("material." + std::string(p.key) + " = "));
            const auto core = m.bond.invalid_reason();
            REQUIRE(core.has_value());
            CHECK(material_parameter_of_field(core->substr(0, core->find(" = "))) == &p);
        }
    }
    CHECK(bond_model_names() == "parallel_bond, soft_bond, flat_joint");
    CHECK(Range{0.0, 1.0, true, false}.rule() == "in (0, 1]");
    CHECK(Range{0.0, std::numeric_limits<double>::infinity(), false, false}.rule() == ">= 0");
    CHECK_FALSE(Range{0.0, 1.0, true, false}.contains(std::nan("")));
}
