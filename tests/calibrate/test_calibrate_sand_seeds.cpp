// A sand's own packing seeds ([calibration] sand_seeds): the sand runs on its list and every
// other sand on calibration.seeds, in every evaluation, the preparation, the plan's run count,
// the noise floor (each sand's standard error with its own n), the curves and the MPI prepare
// message; bad tables are refused naming the key and line.
#include <catch2/catch.hpp>
#include <cmath>
#include <mutex>
#include <set>
#include <sstream>

#include "calibrate/execution/run_message.hpp"
#include "calibrate/plan.hpp"
#include "calibrate/problem.hpp"
#include "calibrate_fixture.hpp"
#include "reports/calibration_report.hpp"

namespace fs = std::filesystem;
using namespace gradem;
using gradem::test::TempDir;

namespace {

const std::vector<std::string> kSands = {"pre-blended", "Van Buren"};

fs::path problem_with(const fs::path& dir, const std::string& calibration_keys, const std::string& rest = "") {
    auto truth = cal::make_analytic_model(2, 0.001);
    test::write_text(dir / "lab_results.json",
                     test::synthetic_lab_results(*truth, kSands, test::material_at({20.0, 12.0, 1.6, 0.25}), {101, 102, 103}).dump(1));
    return test::write_problem(dir, "model = \"analytic\"\n" + calibration_keys,
                               "strain_weight = 1.0\n[solver]\nmethod = \"scaling\"\nmax_runs = 200\n" + rest + "\n[output]\ndir = \"out\"\n");
}

/// The stand-in with a noise large enough to see in the noise floor, recording what it is asked
/// to prepare and every (sand, seed) it runs.
class RecordingModel final : public cal::CubeModel {
public:
    RecordingModel() : inner_(cal::make_analytic_model(2, 0.02)) {}
    void prepare(const cal::PackingSeeds& s, int w, const std::function<void(const std::string&)>& l) override {
        prepared = s;
        inner_->prepare(s, w, l);
    }
    cal::RunOutcome run(const cal::RunRequest& q, double t) const override {
        const std::lock_guard lock(mutex_);
        ran.insert({q.sand, q.seed});
        return inner_->run(q, t);
    }
    std::string fingerprint() const override { return inner_->fingerprint(); }
    std::string run_fingerprint(cal::CubeTest t) const override { return inner_->run_fingerprint(t); }

    cal::PackingSeeds prepared;
    mutable std::set<std::pair<std::size_t, std::uint64_t>> ran;

private:
    std::unique_ptr<cal::CubeModel> inner_;
    mutable std::mutex mutex_;
};

/// std / mean / sqrt(n) of one quantity over runs [first, first + n) of an evaluation.
double relative_standard_error(const cal::Evaluation& e, std::size_t first, std::size_t n, double cal::RunOutcome::*field) {
    double sum = 0, sum2 = 0;
    for (std::size_t k = first; k < first + n; ++k) sum += e.runs.at(k).*field;
    const double mean = sum / static_cast<double>(n);
    for (std::size_t k = first; k < first + n; ++k) sum2 += (e.runs.at(k).*field - mean) * (e.runs.at(k).*field - mean);
    return std::sqrt(sum2 / static_cast<double>(n - 1)) / mean / std::sqrt(static_cast<double>(n));
}

}  // namespace

TEST_CASE("a sand's own packing seeds: every evaluation runs it on its list and the other sands on calibration.seeds",
          "[calibrate][seeds]") {
    TempDir dir("cal-sand-seeds");
    const cal::CalibrationProblem problem =
        cal::load_calibration_problem(problem_with(dir.path, "seeds = [1, 2, 3]\nsand_seeds = { \"Van Buren\" = [1, 2, 3, 5, 6] }\n"));
    CHECK(problem.seeds_of(0) == std::vector<std::uint64_t>{1, 2, 3});
    CHECK(problem.seeds_of(1) == std::vector<std::uint64_t>{1, 2, 3, 5, 6});
    CHECK(problem.runs_per_test() == 8);
    CHECK(problem.runs_per_test({1}) == 5);

    RecordingModel model;
    const cal::CalibrationResult r = cal::run_calibration(problem, model);
    // Prepared and run: each sand on its own seeds, nothing else.
    CHECK(model.prepared.of(0) == problem.seeds_of(0));
    CHECK(model.prepared.of(1) == problem.seeds_of(1));
    std::set<std::pair<std::size_t, std::uint64_t>> expected;
    for (std::size_t s = 0; s < 2; ++s)
        for (std::uint64_t seed : problem.seeds_of(s)) expected.insert({s, seed});
    CHECK(model.ran == expected);
    // Every evaluation is 3 + 5 runs; the budget counts them so.
    REQUIRE(!r.history.empty());
    for (const cal::Evaluation& e : r.history) {
        REQUIRE(e.sands.size() == 2);
        CHECK(e.sands[0].ok == 3);
        CHECK(e.sands[1].ok == 5);
        CHECK(e.runs.size() == 8);
    }
    CHECK(r.runs_used % 8 == 0);  // (a point evaluated twice is served: fewer than 8 x evaluations)
    CHECK(r.runs_used > 8);
    // The plan counts the stand-in's path with the same per-sand runs.
    TempDir other("cal-sand-seeds-plan");
    const cal::CalibrationProblem in_other = cal::load_calibration_problem(
        problem_with(other.path, "seeds = [1, 2, 3]\nsand_seeds = { \"Van Buren\" = [1, 2, 3, 5, 6] }\n"));
    const auto stand_in = cal::make_model(in_other);
    const cal::CalibrationResult planned_path = cal::run_calibration(in_other, *stand_in);
    CHECK(cal::expected_runs(in_other).fitted == planned_path.runs_used);
    CHECK(planned_path.runs_used % 8 == 0);
    // The noise floor: each sand's relative standard error of the seed mean with its own n, the worse sand.
    const cal::CalibrationStage& st = r.stages.at(0);
    const cal::Evaluation& best = st.solution.best_eval;
    for (const auto& [q, field] : {std::pair{cal::Quantity::modulus, &cal::RunOutcome::modulus_pa},
                                   std::pair{cal::Quantity::peak, &cal::RunOutcome::peak_pa}}) {
        const double pre = relative_standard_error(best, 0, 3, field), van = relative_standard_error(best, 3, 5, field);
        CHECK(pre > 0.0);
        CHECK(van > 0.0);
        CHECK(st.noise_floor[static_cast<int>(q)] == Approx(std::max(pre, van)).epsilon(1e-9));
    }
    // The summary names each sand's seeds; the curves carry Van Buren's fifth and sixth seeds.
    const nlohmann::json summary = report::summary_json(problem, r);
    CHECK(summary["packing_seeds_by_sand"]["Van Buren"] == nlohmann::json({1, 2, 3, 5, 6}));
    CHECK(summary["packing_seeds_by_sand"]["pre-blended"] == nlohmann::json({1, 2, 3}));
    CHECK_THAT(report::summary_markdown(problem, r), Catch::Contains("packing seeds per sand: 3, Van Buren 5"));
    std::istringstream csv(report::curves_csv(problem, r));
    std::set<std::pair<std::string, std::string>> sand_seed;
    for (std::string line; std::getline(csv, line);)
        if (line.find(",simulated,") != std::string::npos) {
            const std::size_t a = line.find(",simulated,") + 11;
            const std::string sand = line.substr(line.find("\",\"") + 3, line.find("\",simulated") - line.find("\",\"") - 3);
            sand_seed.insert({sand, line.substr(a, line.find(',', a) - a)});
        }
    CHECK(sand_seed.count({"Van Buren", "6"}) == 1);
    CHECK(sand_seed.count({"pre-blended", "5"}) == 0);
    CHECK(sand_seed.size() == 8);
    // Part of the problem's identity: the same file without the key is another problem.
    const cal::CalibrationProblem plain = cal::load_calibration_problem(problem_with(dir.path, "seeds = [1, 2, 3]\n"));
    CHECK(plain.describe() != problem.describe());
    CHECK(plain.runs_per_test() == 6);
}

TEST_CASE("the MPI prepare message carries each sand's own seeds", "[calibrate][seeds]") {
    cal::wire::Prepare m;
    m.seeds = cal::PackingSeeds({1, 2, 3});
    m.seeds.by_sand = {{}, {1, 2, 3, 5, 6}, {9}};
    const cal::wire::Prepare back = cal::wire::decode_prepare(cal::wire::encode(m));
    CHECK(back.seeds.common == m.seeds.common);
    CHECK(back.seeds.by_sand == m.seeds.by_sand);
    CHECK(back.seeds.of(0) == std::vector<std::uint64_t>{1, 2, 3});
    CHECK(back.seeds.of(1) == std::vector<std::uint64_t>{1, 2, 3, 5, 6});
    CHECK(back.seeds.of(3) == std::vector<std::uint64_t>{1, 2, 3});  // a sand beyond the list: every sand's
}

TEST_CASE("bad calibration.sand_seeds are refused naming the key, line and rule", "[calibrate][seeds]") {
    TempDir dir("cal-sand-seeds-bad");
    auto refused = [&](const std::string& keys, const std::string& rest, const std::string& what) {
        INFO(keys << rest);
        CHECK_THROWS_WITH(cal::load_calibration_problem(problem_with(dir.path, "seeds = [1, 2, 3]\n" + keys, rest)),
                          Catch::Contains("problem.toml:") && Catch::Contains(what));
    };
    refused("sand_seeds = [1, 2]\n", "", "key 'calibration.sand_seeds' = [ 1, 2 ]: expected a table of sand names");
    refused("sand_seeds = { \"Ottawa\" = [1, 2] }\n", "", "\"Ottawa\" is not one of calibration.sands");
    refused("sand_seeds = { \"Van Buren\" = [] }\n", "", "expected a non-empty array of positive integers");
    refused("sand_seeds = { \"Van Buren\" = [1, 0] }\n", "", "expected a non-empty array of positive integers");
    refused("sand_seeds = { \"Van Buren\" = [1, 2, 1] }\n", "", "expected distinct seeds");
    refused("sand_seeds = { \"Van Buren\" = [1, 2, 4] }\n", "[validation]\nseeds = [4]\n",
            "key 'validation.seeds': seed 4 is also a fitted seed of Van Buren (calibration.sand_seeds)");
    // A validation seed must be unseen by every sand, whichever list holds it.
    refused("sand_seeds = { \"pre-blended\" = [4, 5] }\n", "[validation]\nseeds = [4]\n", "fitted seed of pre-blended");
}
