// The DEM twin experiment (tagged slow): synthetic lab targets made by gradem's own cube test
// at known parameters on other packing seeds; the scaling path must recover them. And the DEM
// model's other test: the direct-tension test (what `gradem study` model_form runs for σc/σt).
#include <catch2/catch.hpp>

#include "calibrate_fixture.hpp"
#include "experiments/specimen/packing_cache.hpp"
#include "experiments/config/tension_config.hpp"
#include "reports/calibration_report.hpp"

namespace fs = std::filesystem;
using namespace gradem;
using gradem::test::TempDir;

TEST_CASE("twin experiment, real DEM: modulus and peak within 3 %, parameters within 10 %", "[calibrate][.slow]") {
    TempDir dir("cal-dem-twin");
    // The calibration specimen with its paths made absolute and the packing cache in the temp dir.
    std::ifstream in(test::calibration_base_config());
    std::stringstream text;
    text << in.rdbuf();
    std::string base = text.str();
    const std::string study = (fs::path(GRADEM_SOURCE_DIR) / "lab_data" / "datasets" / "study").string();
    base.replace(base.find("\"../../lab_data/datasets/study\""), std::string("\"../../lab_data/datasets/study\"").size(), "\"" + study + "\"");
    base.replace(base.find("\"../../out/packing-cache\""), std::string("\"../../out/packing-cache\"").size(), "\"cache\"");
    test::write_text(dir.path / "base.toml", base);
    const exp::CubeConfig cube = exp::load_cube_config(dir.path / "base.toml");

    auto model = cal::make_dem_model(cube, {"Van Buren"});
    model->prepare({1, 2, 11, 12}, 2, {});
    exp::MaterialParams truth = cube.material;  // E* = 11 GPa, σ̄c = 9 MPa in the base: truth elsewhere
    truth.contact.effective_modulus = truth.bond.effective_modulus = 16e9;
    const double strength = 12e6 / truth.bond.tensile_strength_mean;
    truth.bond.tensile_strength_mean *= strength, truth.bond.tensile_strength_std *= strength;
    truth.bond.cohesion_mean *= strength, truth.bond.cohesion_std *= strength;
    test::write_text(dir.path / "lab_results.json", test::synthetic_lab_results(*model, {"Van Buren"}, truth, {11, 12}).dump(1));

    std::string cfg = "[calibration]\nbase = \"base.toml\"\nsands = [\"Van Buren\"]\nseeds = [1, 2]\n"
                      "[targets]\nlab_results = \"lab_results.json\"\n"
                      "[parameters.cohesion_ratio]\nfree = false\n[parameters.strength_cv]\nfree = false\n"
                      "[solver]\nmax_runs = 16\n[output]\ndir = \"out\"\n";
    test::write_text(dir.path / "problem.toml", cfg);
    const cal::CalibrationProblem problem = cal::load_calibration_problem(dir.path / "problem.toml");
    const cal::CalibrationResult r = cal::run_calibration(problem, *model);
    const cal::CalibrationStage& st = r.stages.at(0);
    CHECK(st.solution.homogeneity.holds);
    const std::vector<double> got = st.solution.best;  // E* GPa, σ̄c MPa
    INFO("recovered E* " << got.at(0) << " GPa, tensile strength " << got.at(1) << " MPa");
    CHECK(std::fabs(got[0] / 16.0 - 1.0) < 0.10);
    CHECK(std::fabs(got[1] / 12.0 - 1.0) < 0.10);
    for (const auto& row : report::summary_json(problem, r)["targets"])
        if (row["quantity"] != "strain_at_peak") {
            INFO(row.dump());
            CHECK(std::fabs(row["rel_error"].get<double>()) < 0.03);
        }
    CHECK(r.runs_used <= 16);
}

TEST_CASE("explicit paste: a tiny paste calibration runs end to end and recovers the twin's modulus within 10 %", "[calibrate][paste]") {
    // A 1.3 mm paste cube (sand 0.3-0.42 mm, paste 0.12 mm: ≈ 520 particles); synthetic targets
    // from seed 2 at E* = 15 GPa; only E* free, 4 runs on seed 1.
    TempDir dir("cal-paste");
    const std::string study = (fs::path(GRADEM_SOURCE_DIR) / "lab_data" / "datasets" / "study").string();
    test::write_text(dir.path / "base.toml",
                     "[specimen]\ndataset = \"" + study + "\"\nsand = \"pre-blended\"\nrepresentation = \"explicit_paste\"\n"
                     "[mix]\nsand_to_cementitious_volume = 2.0\n"
                     "[paste]\nmin_diameter_mm = 0.12\nmax_diameter_mm = 0.12\n"
                     "[size_rule]\nmin_diameter_mm = 0.3\nmax_diameter_mm = 0.42\n"
                     "[genesis]\nedge_mm = 1.3\ntarget_solid_fraction = 0.5\nequilibrium_ratio = 0.05\n"
                     "[material]\neffective_modulus_gpa = 11.0\ntensile_strength_mpa = 9.0\ncohesion_mpa = 18.0\nbond_gap_fraction = 0.5\n"
                     "[test]\nstrain_rate_per_s = \"auto\"\nmax_settle_steps = 200\n"
                     "[output]\ndir = \"out\"\ncache_dir = \"cache\"\n");
    const exp::CubeConfig cube = exp::load_cube_config(dir.path / "base.toml");
    REQUIRE(cube.specimen.paste);

    auto model = cal::make_dem_model(cube, {"pre-blended"});
    model->prepare({1, 2}, 2, {});
    exp::MaterialParams truth = cube.material;
    truth.contact.effective_modulus = truth.bond.effective_modulus = 15e9;
    test::write_text(dir.path / "lab_results.json", test::synthetic_lab_results(*model, {"pre-blended"}, truth, {2}).dump(1));
    // The MPI workers' path: a fresh model loads the cached paste specimen and runs it bitwise the same.
    auto worker = cal::make_dem_model(cube, {"pre-blended"});
    worker->load_prepared({1});
    const cal::RunOutcome a = model->run({0, 1, cube.material}, 0.0), b = worker->run({0, 1, cube.material}, 0.0);
    REQUIRE(a.ok());
    CHECK(a.particles > 400);
    CHECK(a.modulus_pa == b.modulus_pa);
    CHECK(a.peak_pa == b.peak_pa);

    test::write_text(dir.path / "problem.toml",
                     "[calibration]\nbase = \"base.toml\"\nsands = [\"pre-blended\"]\nseeds = [1]\nstop_strain_ratio = 1.2\n"
                     "[targets]\nlab_results = \"lab_results.json\"\n"
                     "[parameters.tensile_strength_mpa]\nfree = false\n[parameters.cohesion_ratio]\nfree = false\n"
                     "[parameters.strength_cv]\nfree = false\n"
                     "[solver]\nmax_runs = 4\n[run]\nworkers = 2\n[output]\ndir = \"out\"\n");
    const cal::CalibrationProblem problem = cal::load_calibration_problem(dir.path / "problem.toml");
    const cal::CalibrationResult r = cal::run_calibration(problem, *model);
    CHECK(r.runs_failed == 0);
    CHECK(r.runs_used <= 4);
    const double got = r.stages.at(0).solution.best.at(0);  // E* [GPa]
    // Recovered E* within 10 % of the truth (15 GPa): the targets come from another packing
    // seed (2), so seed-to-seed scatter stays in the answer (about 16.2 GPa here, 8 % high);
    // the start point (11 GPa) is 27 % off.
    INFO("E* from 11 GPa, truth 15 GPa, recovered " << got);
    CHECK(std::fabs(got / 15.0 - 1.0) < 0.10);

    // calibrated-pre-blended.toml: the base config at the best point, loadable elsewhere (absolute
    // paths), whose cube test is the calibration's run at the best point, bitwise.
    fs::create_directories(problem.out_dir);
    report::write_calibration_outputs(problem, r);
    const fs::path written = problem.out_dir / "calibrated-pre-blended.toml";
    REQUIRE(fs::exists(written));
    TempDir elsewhere("cal-paste-calibrated");
    fs::copy_file(written, elsewhere.path / "calibrated.toml");
    const exp::CubeConfig calibrated = exp::load_cube_config(elsewhere.path / "calibrated.toml");
    CHECK(calibrated.material.contact.effective_modulus == got * 1e9);
    CHECK(calibrated.material.bond.effective_modulus == got * 1e9);
    CHECK(calibrated.material.bond.tensile_strength_mean == cube.material.bond.tensile_strength_mean);
    REQUIRE(calibrated.specimen.paste);
    CHECK(calibrated.specimen.paste->paste.min_diameter == cube.specimen.paste->paste.min_diameter);
    CHECK(calibrated.cache_dir == fs::absolute(dir.path / "cache"));
    CHECK(calibrated.test.loading.stop_strain_ratio == 1.2);  // the calibration's stop rules, so its runs repeat
    const cal::RunOutcome* at_best = nullptr;
    for (const cal::Evaluation& e : r.history)
        if (e.values == r.stages.at(0).solution.best && !e.runs.empty()) at_best = &e.runs.front();
    REQUIRE(at_best != nullptr);
    auto rerun = cal::make_dem_model(calibrated, {"pre-blended"});
    rerun->load_prepared({1});
    const cal::RunOutcome again = rerun->run({0, 1, calibrated.material}, 0.0);
    REQUIRE(again.ok());
    CHECK(again.modulus_pa == at_best->modulus_pa);
    CHECK(again.peak_pa == at_best->peak_pa);
    CHECK(again.steps == at_best->steps);
}

TEST_CASE("DEM tension model: the direct-tension test of `gradem tension` on the cached packing, own fingerprint",
          "[calibrate][tension]") {
    // A 1.6 mm cube of Van Buren grains 0.3-0.42 mm (a few hundred grains).
    TempDir dir("cal-dem-tension");
    const std::string study = (fs::path(GRADEM_SOURCE_DIR) / "lab_data" / "datasets" / "study").string();
    const std::string cube_text = "[specimen]\ndataset = \"" + study + "\"\nsand = \"Van Buren\"\n"
                                  "[size_rule]\nmin_diameter_mm = 0.3\nmax_diameter_mm = 0.42\n"
                                  "[genesis]\nedge_mm = 1.6\ntarget_solid_fraction = 0.5\n"
                                  "[material]\neffective_modulus_gpa = 11.0\ntensile_strength_mpa = 9.0\ncohesion_mpa = 18.0\n"
                                  "[test]\nstrain_rate_per_s = \"auto\"\nmax_settle_steps = 200\n"
                                  "[output]\ndir = \"out\"\ncache_dir = \"cache\"\n";
    test::write_text(dir.path / "base.toml", cube_text + "[tension]\ngrip_depth_fraction = 0.15\n");
    const exp::CubeConfig cube = exp::load_cube_config(dir.path / "base.toml");

    auto compression = cal::make_dem_model(cube, {"Van Buren"});
    auto tension = cal::make_dem_model(cube, {"Van Buren"}, true);
    compression->prepare({1}, 1, {});
    tension->prepare({1}, 1, {});  // the same cached packing
    CHECK(tension->fingerprint() != compression->fingerprint());
    CHECK_THAT(tension->fingerprint(), Catch::StartsWith(compression->fingerprint()) && Catch::Contains("direct tension"));
    // A model with both tests keys its compression runs as the compression-only model does.
    CHECK(tension->run_fingerprint(cal::CubeTest::compression) == compression->run_fingerprint(cal::CubeTest::compression));
    CHECK(tension->run_fingerprint(cal::CubeTest::tension) == tension->fingerprint());
    CHECK_THROWS_AS(compression->run_fingerprint(cal::CubeTest::tension), std::logic_error);

    const cal::RunOutcome t = tension->run({0, 1, cube.material, cal::CubeTest::tension}, 0.0);
    const cal::RunOutcome c = compression->run({0, 1, cube.material}, 0.0);
    // The both-tests model runs compression for a compression request: the same outcome, bitwise.
    CHECK(tension->run({0, 1, cube.material}, 0.0).peak_pa == c.peak_pa);
    INFO("sigma_t " << t.peak_pa << " Pa, sigma_c " << c.peak_pa << " Pa; " << t.reason);
    REQUIRE(t.ok());
    REQUIRE(c.ok());
    CHECK(t.particles == c.particles);
    CHECK(t.peak_pa > 0.0);
    CHECK(t.peak_pa < c.peak_pa);  // bonded particles: tensile strength below the compressive

    // The same test run directly, as `gradem tension` runs it: the same σt, bitwise.
    const exp::Packing packing = exp::load_or_generate(exp::load_gradation(cube), cube.specimen, cube.cache_dir);
    const exp::TensionConfig tc = exp::load_tension_config(cube);
    exp::TensionTestSpec spec = tc.spec;
    spec.test.loading.strain_rate = exp::tension_strain_rate(cube, tc, packing);
    const exp::TensionTestResult direct = exp::run_tension_test(packing, cube.material, spec);
    CHECK(direct.cube.macro.peak_stress_pa == t.peak_pa);
    CHECK(direct.cube.macro.strain_at_peak == t.strain_at_peak);

    // A bad [tension] table is the config's error, before anything runs.
    test::write_text(dir.path / "bad.toml", cube_text + "[tension]\ngrip_depth_fraction = 0.9\n");
    CHECK_THROWS_WITH(cal::make_dem_model(exp::load_cube_config(dir.path / "bad.toml"), {"Van Buren"}, true),
                      Catch::Contains("bad.toml") && Catch::Contains("tension.grip_depth_fraction"));
}
