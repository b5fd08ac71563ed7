// Bad calibration configs and ledgers: a clear error naming the file, line and key, and an
// existing ledger left untouched.
#include <catch2/catch.hpp>
#include <fstream>
#include <sstream>

#include "calibrate/ledger.hpp"
#include "calibrate/problem.hpp"
#include "calibrate_fixture.hpp"
#include "lab_data/input_error.hpp"

namespace fs = std::filesystem;
using namespace gradem;
using gradem::test::TempDir;
using Catch::Matchers::Contains;

namespace {

void write_lab(const fs::path& dir) {
    auto model = cal::make_analytic_model(2, 0.0);
    const exp::MaterialParams m = exp::load_cube_config(test::calibration_base_config()).material;
    test::write_text(dir / "lab_results.json", test::synthetic_lab_results(*model, {"pre-blended", "Van Buren"}, m, {1, 2}).dump());
}

std::string bytes(const fs::path& p) {
    std::ifstream in(p, std::ios::binary);
    std::ostringstream s;
    s << in.rdbuf();
    return s.str();
}

std::string replace_once(const std::string& text, const std::string& from, const std::string& to) {
    const auto at = text.find(from);
    REQUIRE(at != std::string::npos);
    return text.substr(0, at) + to + text.substr(at + from.size());
}

}  // namespace

TEST_CASE("bad calibration configs are rejected with the file, line and key", "[calibrate]") {
    TempDir dir("cal-bad-config");
    write_lab(dir.path);
    struct Case {
        const char* name;
        std::string calibration, rest, expected;
    };
    const std::vector<Case> cases = {
        {"lower >= upper", "", "[parameters.effective_modulus_gpa]\nlower = 50.0\nupper = 5.0\n", "must be < upper"},
        {"start outside bounds", "", "[parameters.tensile_strength_mpa]\nstart = 500.0\n", "is outside [lower, upper]"},
        {"unknown solver", "", "[solver]\nmethod = \"newton\"\n", "unknown solver"},
        {"unknown parameter", "", "[parameters.youngs_modulus]\nfree = true\n", "unknown parameter 'youngs_modulus'"},
        {"unknown key", "", "[solver]\nmax_run = 3\n", "unknown key 'solver.max_run'"},
        {"unknown mode", "mode = \"both\"\n", "", "expected \"joint\", \"per_sand\" or \"study\""},
        {"sand not in the lab results", "sands = [\"Ottawa\"]\n", "", "sand 'Ottawa' is not in the lab results"},
        {"log scale with lower 0", "", "[parameters.strength_cv]\nscale = \"log\"\nlower = 0.0\n", "needs lower > 0"},
        {"calibrate_on not a sand", "mode = \"study\"\ncalibrate_on = \"Ottawa\"\n", "", "is not one of calibration.sands"},
        {"bad seeds", "seeds = [1, 1]\n", "", "distinct seeds"},
    };
    for (const Case& c : cases) {
        DYNAMIC_SECTION(c.name) {
            const fs::path cfg = test::write_problem(dir.path, c.calibration, c.rest);
            REQUIRE_THROWS_AS(cal::load_calibration_problem(cfg), lab::InputError);
            // Named: the config file, or for a target the lab results file it points to.
            REQUIRE_THROWS_WITH(cal::load_calibration_problem(cfg), (Contains(cfg.string()) || Contains("lab_results.json")) &&
                                                                        Contains(c.expected));
        }
    }
}

TEST_CASE("missing or inconsistent lab results are rejected", "[calibrate]") {
    TempDir dir("cal-bad-lab");
    const fs::path cfg = test::write_problem(dir.path, "", "");
    REQUIRE_THROWS_WITH(cal::load_calibration_problem(cfg), Contains("lab_results.json not found") && Contains("gradem lab"));
    test::write_text(dir.path / "lab_results.json", "{\"sands\": [{\"name\": \"pre-blended\", \"chord_modulus_mpa\": {\"n\": 3, \"mean\": -5}}]}");
    REQUIRE_THROWS_WITH(cal::load_calibration_problem(cfg), Contains("chord_modulus_mpa.mean is missing or not positive"));
    test::write_text(dir.path / "lab_results.json", "{not json");
    REQUIRE_THROWS_WITH(cal::load_calibration_problem(cfg), Contains("not valid JSON"));
}

TEST_CASE("a ledger of another problem is refused and left untouched", "[calibrate]") {
    TempDir dir("cal-ledger-mismatch");
    write_lab(dir.path);
    auto model = cal::make_analytic_model(2, 0.001);
    const fs::path a = test::write_problem(dir.path, "", "[solver]\nmax_runs = 12\n[output]\ndir = \"out\"\n", "a.toml");
    const cal::CalibrationProblem pa = cal::load_calibration_problem(a);
    cal::run_calibration(pa, *model);
    REQUIRE(fs::exists(pa.ledger));
    const std::string before = bytes(pa.ledger);
    const auto mtime = fs::last_write_time(pa.ledger);
    // Same ledger, other bounds: another problem.
    const fs::path b = test::write_problem(dir.path, "", "[parameters.effective_modulus_gpa]\nupper = 40.0\n[solver]\nmax_runs = 12\n"
                                                         "[output]\ndir = \"out\"\n", "b.toml");
    const cal::CalibrationProblem pb = cal::load_calibration_problem(b);
    REQUIRE_THROWS_AS(cal::run_calibration(pb, *model), cal::LedgerMismatch);
    REQUIRE_THROWS_WITH(cal::run_calibration(pb, *model), Contains("another problem definition") && Contains("left untouched") &&
                                                               Contains("effective_modulus_gpa"));
    CHECK(bytes(pa.ledger) == before);
    CHECK(fs::last_write_time(pa.ledger) == mtime);
    // Not a ledger at all.
    test::write_text(dir.path / "not-a-ledger.sqlite", "hello");
    CHECK_THROWS_AS(cal::Ledger(dir.path / "not-a-ledger.sqlite", "x", "y"), cal::LedgerError);
    CHECK(bytes(dir.path / "not-a-ledger.sqlite") == "hello");
}

TEST_CASE("the shipped calibration configs load, with their documented defaults", "[calibrate]") {
    TempDir dir("cal-shipped");
    write_lab(dir.path);
    const fs::path configs = fs::path(GRADEM_SOURCE_DIR) / "calibrate" / "configs";
    for (const char* name : {"joint.toml", "study.toml", "per_sand.toml"}) {
        DYNAMIC_SECTION(name) {
            // The same file with its base and lab results made absolute (the bundled lab results
            // exist only after the main job has run).
            std::string text = bytes(configs / name);
            const std::string base = "\"../../experiments/configs/calibration_cube.toml\"";
            const std::string lab = "\"../../out/lab/lab_results.json\"";
            std::string quoted_base = "\"";
            quoted_base += test::calibration_base_config().string();
            quoted_base += "\"";
            text = replace_once(text, base, quoted_base);
            text = replace_once(text, lab, "\"lab_results.json\"");
            test::write_text(dir.path / name, text);
            const cal::CalibrationProblem p = cal::load_calibration_problem(dir.path / name);
            CHECK(p.sands == std::vector<std::string>{"pre-blended", "Van Buren"});
            CHECK(p.solver.method == cal::Method::scaling);
            CHECK(p.seeds.size() == 2);
            const cal::ParameterSpace space(p.parameters, p.base.material);
            CHECK(space.size() == 4);  // E*, tensile strength, cohesion ratio, strength cv
            CHECK(space.index_of(cal::Role::stiffness_scale).has_value());
            CHECK(space.index_of(cal::Role::strength_scale).has_value());
        }
    }
}
