// Explicit-paste specimens end to end: the config keys ([specimen] representation,
// [mix], [paste]) with their errors naming file, line and key; the paste cache keyed on the
// paste settings; bond families in the bonded cube specimen (sand-sand frictional, ITZ bonds
// scaled, paste-paste bonds = [material]); the memory estimate checked before the fill against
// the bonded cube's arrays; the cube test of a paste specimen bitwise the same for 1, 2 and 3
// threads.
#include "../input_files.hpp"
#include "../temp_dir.hpp"
#include <catch2/catch.hpp>

#include <fstream>

#include "core/parallel.hpp"
#include "experiments/config/cube_config.hpp"
#include "experiments/virtual_tests/cube_specimen.hpp"
#include "experiments/specimen/packing_cache.hpp"
#include "experiments/paste/paste_cache.hpp"
#include "experiments/paste/paste_fill.hpp"
#include "experiments/virtual_tests/tension_test.hpp"
#include "common/input_error.hpp"
#include "reports/cube_output.hpp"
#include <nlohmann/json.hpp>
#include "study_curves.hpp"

using namespace gradem;
using namespace gradem::exp;
using namespace gradem::report;
namespace fs = std::filesystem;
using Catch::Matchers::Contains;

namespace {

using test::write_file;

/// load_cube_config must throw an InputError at `line` whose message contains every `parts`.
void require_rejected(const fs::path& file, int line, std::initializer_list<std::string> parts) {
    test::require_input_error([&] { (void)load_cube_config(file); }, file, line, parts);
}

// A small explicit-paste specimen: sand 0.3-0.42 mm in a 1.3 mm cube, paste 0.12 mm.
SpecimenSpec small_paste_spec() {
    SpecimenSpec s;
    s.size_rule.min_diameter = 0.3e-3;
    s.size_rule.max_diameter = 0.42e-3;
    s.genesis.edge = 1.3e-3;
    s.genesis.target_solid_fraction = 0.5;  // the small cube jams at ~0.52 (walls); the mix needs 0.497
    s.genesis.equilibrium_ratio = 0.05;
    PasteSettings p;
    p.mix.sand_specific_gravity = 2.64;
    p.mix.sand_to_cementitious_volume = 2.0;  // sand fraction 0.43: below the small cube's packed 0.49
    p.paste.min_diameter = p.paste.max_diameter = 0.12e-3;
    s.paste = p;
    return s;
}

}  // namespace

TEST_CASE("paste config: the shipped paste cube reads the study's mix and the dataset's SG", "[paste]") {
    const CubeConfig c = load_cube_config(fs::path(GRADEM_SOURCE_DIR) / "experiments" / "configs" / "paste_cube.toml");
    CHECK(c.representation == exp::Representation::explicit_paste);
    REQUIRE(c.specimen.paste);
    CHECK(c.specimen.paste->mix.sand_to_cementitious_volume == 2.6);
    CHECK(c.specimen.paste->mix.water_cement_ratio == 0.53);
    CHECK(c.specimen.paste->mix.sand_specific_gravity == 2.64);  // from dataset.toml
    CHECK(c.specimen.paste->paste.min_diameter == Approx(0.1e-3));
    CHECK_FALSE(c.material.families.sand_sand_bonded);
    // The parallel-bond configs stay as they were.
    const CubeConfig pb = load_cube_config(fs::path(GRADEM_SOURCE_DIR) / "experiments" / "configs" / "calibration_cube.toml");
    CHECK(pb.representation == exp::Representation::parallel_bonds);
    CHECK_FALSE(pb.specimen.paste);
}

TEST_CASE("paste config: bad input names the file, line and key", "[paste]") {
    const test::TempDir dir("paste-config");
    const fs::path file = dir.path / "c.toml";
    write_file(dir.path / "sand.csv", "sieve_mm,passing_pct\n0.6,100\n0.3,50\n0.15,0\n");
    const std::string head = "[specimen]\nsieve_csv = \"sand.csv\"\n";
    SECTION("[paste] with parallel bonds") {
        write_file(file, head + "[paste]\nmin_diameter_mm = 0.1\n");
        require_rejected(file, 3, {"[paste]", "explicit_paste"});
    }
    SECTION("unknown representation") {
        write_file(file, head + "representation = \"paste\"\n");
        require_rejected(file, 3, {"specimen.representation", "explicit_paste"});
    }
    SECTION("missing specific gravity (a sieve table has none)") {
        write_file(file, head + "representation = \"explicit_paste\"\n[mix]\nwater_cement_ratio = 0.5\n");
        require_rejected(file, 3, {"mix.sand_specific_gravity", "expected"});
    }
    SECTION("a value out of range") {
        write_file(file, head + "representation = \"explicit_paste\"\n[mix]\nsand_specific_gravity = 2.64\n[paste]\n"
                           "min_diameter_mm = 0.1\nmax_diameter_mm = 0.05\n");
        require_rejected(file, 8, {"paste.max_diameter_mm", ">= min_diameter"});
    }
    SECTION("a bad mix") {
        write_file(file, head + "representation = \"explicit_paste\"\n[mix]\nsand_specific_gravity = 2.64\nair_content = 0.7\n");
        require_rejected(file, 6, {"mix.air_content", "[0, 0.5)"});
    }
    SECTION("sand_sand") {
        write_file(file, head + "representation = \"explicit_paste\"\n[mix]\nsand_specific_gravity = 2.64\n[paste]\nsand_sand = \"glued\"\n");
        require_rejected(file, 7, {"paste.sand_sand", "frictional"});
    }
}

TEST_CASE("paste cache: keyed on the paste settings, reloaded bit for bit, bad family file refused", "[paste]") {
    const test::TempDir dir("paste-cache");
    const lab::GradationCurve curve = test::pre_blended_curve();
    SpecimenSpec spec = small_paste_spec();
    bool cached = true;
    PasteReport report;
    const Packing made = load_or_generate(curve, spec, dir.path, &cached);
    CHECK_FALSE(cached);
    const Packing again = load_or_generate_paste(curve, spec, dir.path, &cached, &report);
    CHECK(cached);
    REQUIRE(again.position.size() == made.position.size());
    CHECK(again.family == made.family);
    CHECK(again.paste_density == made.paste_density);
    CHECK(report.paste_count > 0);
    for (std::size_t i = 0; i < made.radius.size(); ++i) CHECK(again.radius[i] == made.radius[i]);
    // The key follows every paste setting, and the sand key ignores them.
    SpecimenSpec sand = spec;
    sand.paste.reset();
    const std::uint64_t sand_key = packing_key(curve, sand);
    CHECK(packing_key(curve, spec) == sand_key);
    const std::uint64_t key = paste_packing_key(sand_key, *spec.paste);
    PasteSettings other = *spec.paste;
    other.paste.min_diameter = other.paste.max_diameter = 0.11e-3;
    CHECK(paste_packing_key(sand_key, other) != key);
    other = *spec.paste;
    other.mix.water_cement_ratio = 0.5;
    CHECK(paste_packing_key(sand_key, other) != key);
    // A damaged family file is an error naming it.
    for (const auto& entry : fs::directory_iterator(dir.path))
        if (entry.path().extension() == ".family") std::ofstream(entry.path(), std::ios::app) << "x";
    CHECK_THROWS_WITH(load_or_generate(curve, spec, dir.path), Contains(".family"));
}

TEST_CASE("paste specimen: bond families in the bonded cube", "[paste]") {
    const test::TempDir dir("paste-bonds");
    const Packing k = load_or_generate(test::pre_blended_curve(), small_paste_spec(), dir.path);
    MaterialParams m;
    m.bond.tensile_strength_mean = 4.0e6;
    m.bond.cohesion_mean = 8.0e6;
    m.bond_gap_fraction = 0.5;
    m.families.itz_strength_factor = 0.5;
    m.families.itz_modulus_factor = 0.8;
    CubeTestSpec spec;
    spec.max_settle_steps = 0;
    CubeTestResult r;
    const World w = settled_cube_specimen(k, m, spec, r);
    std::size_t paste_paste = 0, itz = 0;
    for (const ParallelBond& b : w.bonds()) {
        const std::uint8_t fi = k.family[static_cast<std::size_t>(b.i)], fj = k.family[static_cast<std::size_t>(b.j)];
        REQUIRE_FALSE((fi == kSandFamily && fj == kSandFamily));  // sand-sand: frictional only
        const BondParams& p = w.bond_family_params()[b.family_pair];
        if (fi != fj) {
            ++itz;
            CHECK(b.tensile_strength == 2.0e6);
            CHECK(p.effective_modulus == Approx(0.8 * m.bond.effective_modulus));
        } else {
            ++paste_paste;
            CHECK(b.tensile_strength == 4.0e6);
            CHECK(p.effective_modulus == m.bond.effective_modulus);
        }
    }
    CHECK(itz > 0);
    CHECK(paste_paste > 0);
    // Paste particles carry the paste they stand for: density = paste density / solid fraction.
    for (std::size_t i = 0; i < k.family.size(); ++i)
        if (k.family[i] == kPasteFamily) {
            const double r3 = k.radius[i] * k.radius[i] * k.radius[i];
            CHECK(w.particles().mass[i] == Approx(k.paste_density * 4.0 / 3.0 * M_PI * r3));
            break;
        }
    // sand_sand = bonded adds the sand-sand pairs.
    m.families.sand_sand_bonded = true;
    CubeTestResult r2;
    CHECK(settled_cube_specimen(k, m, spec, r2).bonds().size() > w.bonds().size());
}

TEST_CASE("paste specimen: the memory estimate checked before the fill bounds the bonded cube's arrays", "[paste]") {
    // The estimate refuses a paste size the machine cannot hold before anything is allocated
    // (paste_fill.cpp check_memory); it must not fall under what the bonded specimen then
    // holds, flat joints (the paste cube's law) with their pair slots and side state, once
    // its pair list is built by a few steps.
    const test::TempDir dir("paste-memory");
    const Packing k = load_or_generate(test::pre_blended_curve(), small_paste_spec(), dir.path);
    MaterialParams m;
    m.bond.model = BondModel::flat_joint;
    m.bond.tensile_strength_mean = 4.0e6;
    m.bond.cohesion_mean = 8.0e6;
    m.bond_gap_fraction = 0.5;
    CubeTestSpec spec;
    spec.max_settle_steps = 0;
    CubeTestResult r;
    World w = settled_cube_specimen(k, m, spec, r);
    REQUIRE(w.run(20) == RunStatus::running);
    const double n = static_cast<double>(w.particles().size());
    const double held = static_cast<double>(w.memory_bytes());  // particles, pairs, slots, bonds, side state
    const double estimated = estimated_specimen_bytes(n);
    INFO("held " << held / n << " B per particle, estimated " << estimated / n);
    CHECK(held <= estimated);
    CHECK(held >= 0.4 * estimated);  // a stated figure, not an arbitrary bound
}

TEST_CASE("paste specimen: the cube test is bitwise the same for 1, 2 and 3 threads", "[paste][determinism]") {
    const test::TempDir dir("paste-threads");
    const Packing k = load_or_generate(test::pre_blended_curve(), small_paste_spec(), dir.path);
    MaterialParams m;
    m.contact.effective_modulus = 5.0e9;
    m.bond.effective_modulus = 5.0e9;
    m.bond.tensile_strength_mean = 3.0e6;
    m.bond.tensile_strength_std = 0.6e6;
    m.bond_gap_fraction = 0.5;
    CubeTestSpec spec;
    spec.max_settle_steps = 200;
    spec.loading.strain_rate = 40.0;
    spec.loading.max_strain = 0.0008;
    spec.loading.ramp_strain = 1e-4;
    spec.loading.record_interval = 20;
    std::vector<double> stress[3];
    for (int threads = 1; threads <= 3; ++threads) {
#ifdef _OPENMP
        omp_set_num_threads(threads);
#endif
        const CubeTestResult r = run_cube_test(k, m, spec);
        for (const CurvePoint& p : r.test.curve) stress[threads - 1].push_back(p.stress);
    }
    REQUIRE(stress[0].size() > 5);
    CHECK(stress[0] == stress[1]);
    CHECK(stress[0] == stress[2]);
}

TEST_CASE("paste specimen: the auto loading rate is quasi-static by the particles' own masses", "[paste]") {
    // Criterion (docs/virtual_tests.md "Loading rate"): time to the expected peak ε_p/ε̇ ≥ 200 transits L/c, c =
    // sqrt(E*/ρ) with ρ = Σm/ΣV of the bonded World's particles (paste particles weigh
    // paste density / solid fraction: the sand density would give a rate too fast).
    const test::TempDir dir("paste-rate");
    const Packing k = load_or_generate(test::pre_blended_curve(), small_paste_spec(), dir.path);
    MaterialParams m;
    CubeTestSpec spec;
    spec.max_settle_steps = 0;
    CubeTestResult r;
    const World w = settled_cube_specimen(k, m, spec, r);
    double mass = 0.0, volume = 0.0;
    for (std::size_t i = 0; i < w.particles().size(); ++i) {
        const double rad = w.particles().radius[i];
        mass += w.particles().mass[i];
        volume += 4.0 / 3.0 * M_PI * rad * rad * rad;
    }
    const double rho = mass / volume;
    REQUIRE(rho > 1.2 * k.density);  // 3595 vs 2640 kg/m³ here
    CHECK(mean_particle_density(k) == Approx(rho).epsilon(1e-12));
    const auto transits = [&](double rate, double density) {
        return (0.003 / rate) / (k.edge() / std::sqrt(m.contact.effective_modulus / density));
    };
    const double rate = quasi_static_strain_rate(k, m);
    CHECK(transits(rate, rho) == Approx(200.0).epsilon(1e-9));
    // Every particle at the sand density (families cleared): the sand rule, 200 transits too.
    Packing sand_only = k;
    sand_only.family.clear();
    CHECK(transits(quasi_static_strain_rate(sand_only, m), k.density) == Approx(200.0).epsilon(1e-9));
    // The sand-density rate would give the paste specimen fewer than 200 transits.
    CHECK(transits(quasi_static_strain_rate(sand_only, m), rho) < 180.0);  // 200 sqrt(2640/3595) = 171
}

TEST_CASE("paste specimen: macro.json carries the paste report and the bonds per family", "[paste]") {
    const test::TempDir dir("paste-macro");
    PasteReport report;
    bool cached = true;
    const Packing k = load_or_generate_paste(test::pre_blended_curve(), small_paste_spec(), dir.path, &cached, &report);
    CHECK_FALSE(cached);
    MaterialParams m;
    m.bond_gap_fraction = 0.5;
    CubeTestSpec spec;
    spec.max_settle_steps = 0;
    CubeTestResult r;
    const World w = settled_cube_specimen(k, m, spec, r);
    // Oracle: the families of the packing, counted here.
    std::size_t paste_count = 0, itz = 0, paste_paste = 0;
    for (std::uint8_t f : k.family) paste_count += f == kPasteFamily;
    for (const ParallelBond& b : w.bonds()) {
        const int ends = (k.family[static_cast<std::size_t>(b.i)] == kPasteFamily) + (k.family[static_cast<std::size_t>(b.j)] == kPasteFamily);
        itz += ends == 1;
        paste_paste += ends == 2;
    }
    CubeConfig c;
    c.specimen = small_paste_spec();
    const auto j = nlohmann::json::parse(macro_json(r, c, k, 1.0, {}, &report));
    REQUIRE(j.contains("paste"));
    const auto& p = j["paste"];
    CHECK(p["paste_count"].get<std::size_t>() == paste_count);
    CHECK(p["sand_count"].get<std::size_t>() == k.radius.size() - paste_count);
    CHECK(p["bonds"]["sand_sand"].get<std::size_t>() == 0);  // sand-sand frictional by default
    CHECK(p["bonds"]["sand_paste"].get<std::size_t>() == itz);
    CHECK(p["bonds"]["paste_paste"].get<std::size_t>() == paste_paste);
    CHECK(itz + paste_paste == j["run"]["bonds"].get<std::size_t>());
    // Volume placed vs the mix design (the fill's tolerance, test_paste.cpp: 2 % absolute).
    CHECK(p["paste_fraction"].get<double>() == Approx(p["mix_paste_fraction"].get<double>()).margin(0.02));
    CHECK(p["size_ratio"].get<double>() == Approx(report.sand_d_max / report.paste_d_min));
    // A parallel-bond specimen's macro.json has no paste block.
    CHECK_FALSE(nlohmann::json::parse(macro_json(r, c, k, 1.0)).contains("paste"));
}

TEST_CASE("paste specimen: the direct tension test runs past its stress-free start to a peak", "[paste]") {
    // The paste specimen starts free of stress (~1e-29 J supplied): round-off motion after the
    // settling must not read as an instability (SimParams::divergence_energy_floor).
    const test::TempDir dir("paste-tension");
    const Packing k = load_or_generate(test::pre_blended_curve(), small_paste_spec(), dir.path);
    MaterialParams m;
    m.bond.tensile_strength_mean = 3.0e6;
    m.bond.cohesion_mean = 6.0e6;
    m.bond_gap_fraction = 0.5;
    TensionTestSpec t;
    t.test.max_settle_steps = 2000;
    t.test.loading.strain_rate = 2.0;
    const TensionTestResult r = run_tension_test(k, m, t);
    INFO(r.cube.test.stop_reason);
    CHECK_FALSE(r.cube.diverged());
    CHECK(r.cube.macro.peak_stress_pa > 0.1e6);
}
