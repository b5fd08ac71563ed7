// The MPI executor end to end: mpirun --allow-run-as-root --oversubscribe -np 3 on this
// machine (rank 0 coordinates, 2 worker ranks). The same answer as the thread executor,
// bitwise (analytic stand-in and a tiny DEM problem), for gradem calibrate and gradem study
// (a resolution study: one model per cube edge on every worker); a worker that exits mid-run ends the
// job without a hang and the rerun resumes from the ledger; a job killed as a whole resumes
// too; a worker that stops answering is given up after timeout + grace; bad setups (one
// rank, a mismatched build, a rank without the packing cache, a bad config) end with one
// clear message from rank 0 and a non-zero exit.
#include <signal.h>
#include <sqlite3.h>
#include <sys/wait.h>
#include <unistd.h>

#include <catch2/catch.hpp>
#include <chrono>
#include <fcntl.h>
#include <fstream>
#include <map>
#include <sstream>
#include <thread>

#include "calibrate/execution/ledger.hpp"
#include "calibrate_fixture.hpp"
#include "experiments/config/cube_config.hpp"

namespace fs = std::filesystem;
using namespace gradem;
using gradem::test::TempDir;
using Catch::Matchers::Contains;

namespace {

using Clock = std::chrono::steady_clock;

std::vector<std::string> mpirun(int ranks, std::vector<std::string> command) {
    std::vector<std::string> argv = {GRADEM_MPIEXEC, "--allow-run-as-root", "--oversubscribe", "-np", std::to_string(ranks)};
    argv.insert(argv.end(), command.begin(), command.end());
    return argv;
}

/// A child process in its own process group, stdout and stderr into `log`.
pid_t start(const std::vector<std::string>& argv, const fs::path& cwd, const fs::path& log) {
    const pid_t pid = fork();
    if (pid == 0) {
        setpgid(0, 0);
        if (chdir(cwd.c_str()) != 0) _exit(126);
        const int fd = open(log.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
        dup2(fd, 1);
        dup2(fd, 2);
        std::vector<char*> args;
        for (const auto& a : argv) args.push_back(const_cast<char*>(a.c_str()));
        args.push_back(nullptr);
        execv(args[0], args.data());
        _exit(127);
    }
    return pid;
}

struct Finished {
    int exit_code = -1;  ///< -1 if killed by a signal or by the time limit
    bool timed_out = false;
    double seconds = 0.0;
    std::string output;
};

/// Waits for `pid` at most `limit_s` seconds (then kills its process group: a hang fails the test).
Finished finish(pid_t pid, const fs::path& log, double limit_s) {
    const auto t0 = Clock::now();
    Finished f;
    int status = 0;
    while (waitpid(pid, &status, WNOHANG) == 0) {
        if (std::chrono::duration<double>(Clock::now() - t0).count() > limit_s) {
            kill(-pid, SIGKILL);
            waitpid(pid, &status, 0);
            f.timed_out = true;
            break;
        }
        std::this_thread::sleep_for(std::chrono::milliseconds(20));
    }
    f.seconds = std::chrono::duration<double>(Clock::now() - t0).count();
    if (!f.timed_out && WIFEXITED(status)) f.exit_code = WEXITSTATUS(status);
    std::ifstream in(log);
    std::stringstream text;
    text << in.rdbuf();
    f.output = text.str();
    return f;
}

Finished run(const std::vector<std::string>& argv, const fs::path& cwd, double limit_s = 90.0) {
    const fs::path log = cwd / ("run-" + std::to_string(Clock::now().time_since_epoch().count()) + ".log");
    return finish(start(argv, cwd, log), log, limit_s);
}

/// A ledger row: outputs as exact doubles, the curve text, where it ran.
struct Row {
    std::string status, reason, curve, host;
    double modulus = 0, peak = 0, strain = 0;
    std::int64_t rank = -1;
};

std::map<std::string, Row> ledger_rows(const fs::path& path) {
    std::map<std::string, Row> rows;
    sqlite3* db = nullptr;
    // Read-write (no create): a job killed mid-commit leaves a hot journal that only a writer
    // may roll back; a read-only connection would see nothing.
    if (sqlite3_open_v2(path.c_str(), &db, SQLITE_OPEN_READWRITE, nullptr) == SQLITE_OK) {
        sqlite3_busy_timeout(db, 2000);
        sqlite3_stmt* s = nullptr;
        if (sqlite3_prepare_v2(db, "SELECT run_key, status, reason, modulus_pa, peak_pa, strain_at_peak, curve, rank, host FROM runs", -1, &s,
                               nullptr) == SQLITE_OK)
            while (sqlite3_step(s) == SQLITE_ROW) {
                auto text = [&](int i) {
                    const unsigned char* t = sqlite3_column_text(s, i);
                    return t ? std::string(reinterpret_cast<const char*>(t)) : std::string();
                };
                Row r{text(1), text(2), text(6), text(8), sqlite3_column_double(s, 3), sqlite3_column_double(s, 4),
                      sqlite3_column_double(s, 5), sqlite3_column_int64(s, 7)};
                rows[text(0)] = r;
            }
        sqlite3_finalize(s);
    }
    sqlite3_close(db);
    return rows;
}

nlohmann::json read_json(const fs::path& p) {
    std::ifstream in(p);
    return nlohmann::json::parse(in);
}

/// The parameter values of a summary.json, in order.
std::vector<double> parameters_of(const nlohmann::json& summary) {
    std::vector<double> v;
    for (const auto& p : summary["parameters"]) v.push_back(p["value"].get<double>());
    return v;
}

const std::vector<std::string> kSands = {"pre-blended", "Van Buren"};

/// An analytic twin problem (targets from known parameters) in `dir`: Ceres, whose Jacobian
/// batches fill the ranks. `extra`: more keys for [solver] and after.
fs::path analytic_problem(const fs::path& dir, int max_runs, const std::string& extra = "") {
    auto model = cal::make_analytic_model(2, 0.001);
    exp::MaterialParams truth = exp::load_cube_config(test::calibration_base_config()).material;
    truth.contact.effective_modulus = truth.bond.effective_modulus = 20e9;
    truth.bond.tensile_strength_mean = 12e6, truth.bond.tensile_strength_std = 3e6;
    truth.bond.cohesion_mean = 19.2e6, truth.bond.cohesion_std = 4.8e6;
    test::write_text(dir / "lab_results.json", test::synthetic_lab_results(*model, kSands, truth, {101, 102, 103}).dump(1));
    return test::write_problem(dir, "model = \"analytic\"\nseeds = [1, 2, 3]\n",
                               "[solver]\nmethod = \"ceres\"\nmax_runs = " + std::to_string(max_runs) + "\n" + extra +
                                   "[output]\ndir = \"out\"\n");
}

/// A tiny DEM problem: 1.8 mm cubes of ~110 grains, one sand, two seeds, packings cached in
/// `dir`/cache; four runs (start and rescaled point).
fs::path dem_problem(const fs::path& dir) {
    std::ifstream in(test::calibration_base_config());
    std::stringstream text;
    text << in.rdbuf();
    std::string base = text.str();
    auto replace = [&](const std::string& from, const std::string& to) {
        const auto at = base.find(from);
        REQUIRE(at != std::string::npos);
        base.replace(at, from.size(), to);
    };
    const std::string study = (fs::path(GRADEM_SOURCE_DIR) / "lab_data" / "datasets" / "study").string();
    replace("\"../../lab_data/datasets/study\"", std::string("\"") + study + "\"");
    replace("\"../../out/packing-cache\"", "\"cache\"");
    replace("min_diameter_mm = 0.149", "min_diameter_mm = 0.25");
    replace("max_diameter_mm = 0.8", "max_diameter_mm = 0.5");
    replace("edge_mm = 2.5", "edge_mm = 1.8");
    replace("target_solid_fraction = 0.60", "target_solid_fraction = 0.52");  // a box ~5 grains wide jams loose
    test::write_text(dir / "base.toml", base);
    const nlohmann::json stat = {{"n", 3}, {"mean", 1.0}, {"std", 0.1}};
    nlohmann::json lab = {{"schema", "gradem-lab-results/1"}, {"representative_data", true}, {"note", "test targets"},
                          {"sands", {{{"name", "Van Buren"},
                                      {"chord_modulus_mpa", {{"n", 3}, {"mean", 20000.0}, {"std", 1500.0}}},
                                      {"peak_stress_mpa", {{"n", 3}, {"mean", 40.0}, {"std", 3.0}}},
                                      {"strain_at_peak", {{"n", 3}, {"mean", 0.003}, {"std", 0.0003}}}}}}};
    test::write_text(dir / "lab_results.json", lab.dump(1));
    test::write_text(dir / "problem.toml",
                     "[calibration]\nbase = \"base.toml\"\nsands = [\"Van Buren\"]\nseeds = [1, 2]\n"
                     "[targets]\nlab_results = \"lab_results.json\"\n"
                     "[solver]\nmax_runs = 4\n[run]\nworkers = 2\n[output]\ndir = \"out\"\n");
    return dir / "problem.toml";
}

/// Same run keys, and every outcome bitwise the same (SQLite REAL keeps a double's bits).
void check_same_runs(const std::map<std::string, Row>& a, const std::map<std::string, Row>& b) {
    REQUIRE(a.size() == b.size());
    for (const auto& [key, ra] : a) {
        INFO("run " << key);
        REQUIRE(b.count(key));
        const Row& rb = b.at(key);
        CHECK(ra.status == rb.status);
        CHECK(ra.modulus == rb.modulus);
        CHECK(ra.peak == rb.peak);
        CHECK(ra.strain == rb.strain);
        CHECK(ra.curve == rb.curve);
    }
}

}  // namespace

TEST_CASE("mpirun -np 3 gradem calibrate: the thread executor's answer bitwise, analytic stand-in", "[calibrate][mpi]") {
    TempDir dir("cal-mpi-analytic");
    const fs::path cfg = analytic_problem(dir.path, 150);
    const Finished threads = run({GRADEM_BIN, "calibrate", cfg.string(), "--out", "threads"}, dir.path);
    INFO(threads.output);
    REQUIRE(threads.exit_code == 0);
    const Finished ranks = run(mpirun(3, {GRADEM_BIN, "calibrate", cfg.string(), "--out", "mpi"}), dir.path);
    INFO(ranks.output);
    REQUIRE(ranks.exit_code == 0);
    CHECK_THAT(ranks.output, Contains("MPI: 2 worker ranks on 1 host"));
    const auto a = read_json(dir.path / "threads" / "summary.json"), b = read_json(dir.path / "mpi" / "summary.json");
    CHECK(parameters_of(a) == parameters_of(b));  // bitwise: JSON doubles round-trip exactly
    CHECK(a["parameters"] == b["parameters"]);     // values, standard errors, intervals
    CHECK(a["targets"] == b["targets"]);
    CHECK(a["runs"]["total"] == b["runs"]["total"]);
    const auto ta = ledger_rows(dir.path / "threads" / "ledger.sqlite"), tb = ledger_rows(dir.path / "mpi" / "ledger.sqlite");
    check_same_runs(ta, tb);
    // Who ran what: rank 0 for threads; both worker ranks under MPI, with the host name.
    std::map<std::int64_t, int> per_rank;
    for (const auto& [key, r] : tb) {
        ++per_rank[r.rank];
        CHECK(r.host == cal::host_name());
    }
    CHECK(per_rank.size() == 2);
    CHECK(per_rank[1] > 0);
    CHECK(per_rank[2] > 0);
    for (const auto& [key, r] : ta) CHECK(r.rank == 0);
}

TEST_CASE("mpirun -np 3 gradem calibrate: the thread executor's answer bitwise, tiny DEM problem", "[calibrate][mpi]") {
    TempDir dir("cal-mpi-dem");
    const fs::path cfg = dem_problem(dir.path);
    const Finished threads = run({GRADEM_BIN, "calibrate", cfg.string(), "--out", "threads"}, dir.path, 300);
    INFO(threads.output);
    REQUIRE(threads.exit_code == 0);
    // The packings are now in the cache: the workers load them from there.
    const Finished ranks = run(mpirun(3, {GRADEM_BIN, "calibrate", cfg.string(), "--out", "mpi"}), dir.path, 300);
    INFO(ranks.output);
    REQUIRE(ranks.exit_code == 0);
    CHECK_THAT(ranks.output, Contains("worker ranks loaded the packings"));
    const auto a = read_json(dir.path / "threads" / "summary.json"), b = read_json(dir.path / "mpi" / "summary.json");
    CHECK(parameters_of(a) == parameters_of(b));
    CHECK(a["targets"] == b["targets"]);
    const auto ta = ledger_rows(dir.path / "threads" / "ledger.sqlite"), tb = ledger_rows(dir.path / "mpi" / "ledger.sqlite");
    REQUIRE(ta.size() == 4);
    check_same_runs(ta, tb);
    for (const auto& [key, r] : tb) {
        CHECK(r.status == "ok");
        CHECK((r.rank == 1 || r.rank == 2));
    }
}

namespace {

/// `j` without the wall times (every key that starts with "wall_seconds"), which differ between
/// two runs of the same study.
nlohmann::json without_wall_times(nlohmann::json j) {
    if (j.is_object()) {
        for (auto it = j.begin(); it != j.end();)
            if (it.key().rfind("wall_seconds", 0) == 0) it = j.erase(it);
            else *it = without_wall_times(*it), ++it;
    } else if (j.is_array()) {
        for (auto& v : j) v = without_wall_times(v);
    }
    return j;
}

/// A study of a calibration of `problem` (run first into dir/cal), run with threads (into
/// dir/threads) and under mpirun -np 3 (dir/mpi): both study.json files and ledgers.
struct StudyBothWays {
    nlohmann::json threads, mpi;
    std::map<std::string, Row> threads_ledger, mpi_ledger;
    std::string mpi_output;
};

StudyBothWays study_both_ways(const fs::path& dir, const fs::path& problem, const std::string& study_keys) {
    const Finished calibration = run({GRADEM_BIN, "calibrate", problem.string(), "--out", "cal"}, dir, 300);
    INFO(calibration.output);
    REQUIRE(calibration.exit_code == 0);
    test::write_text(dir / "study.toml", "[study]\ncalibration = \"cal/summary.json\"\n" + study_keys + "[output]\ndir = \"study\"\n");
    const Finished threads = run({GRADEM_BIN, "study", "study.toml", "--out", "threads"}, dir, 300);
    INFO(threads.output);
    REQUIRE(threads.exit_code == 0);
    const Finished ranks = run(mpirun(3, {GRADEM_BIN, "study", "study.toml", "--out", "mpi"}), dir, 300);
    INFO(ranks.output);
    REQUIRE(ranks.exit_code == 0);
    return {read_json(dir / "threads" / "study.json"), read_json(dir / "mpi" / "study.json"),
            ledger_rows(dir / "threads" / "ledger.sqlite"), ledger_rows(dir / "mpi" / "ledger.sqlite"), ranks.output};
}

}  // namespace

TEST_CASE("mpirun -np 3 gradem study: the thread run's study bitwise, its cube tests on the worker ranks", "[calibrate][mpi]") {
    TempDir dir("study-mpi");
    // Two cube edges: two case models, both on every worker rank.
    const StudyBothWays r = study_both_ways(dir.path, analytic_problem(dir.path, 40),
                                            "kind = \"resolution\"\nedges_mm = [2.5, 3.0]\nseeds = [1, 2, 3]\n");
    CHECK_THAT(r.mpi_output, Contains("MPI: 2 worker ranks on 1 host"));
    CHECK(r.threads["runs"] == r.mpi["runs"]);
    CHECK(r.threads["verdict"] == r.mpi["verdict"]);
    CHECK(without_wall_times(r.threads["data"]) == without_wall_times(r.mpi["data"]));    // bitwise: JSON doubles round-trip
    CHECK(without_wall_times(r.threads["cases"]) == without_wall_times(r.mpi["cases"]));  // every run's outputs
    REQUIRE(r.threads_ledger.size() == 6);  // 2 sands x 3 seeds; the stand-in ignores the edge, so case 2 is served from the ledger
    check_same_runs(r.threads_ledger, r.mpi_ledger);
    std::map<std::int64_t, int> per_rank;
    for (const auto& [key, row] : r.mpi_ledger) ++per_rank[row.rank];
    CHECK(per_rank[0] == 0);
    CHECK(per_rank[1] + per_rank[2] == 6);
}

TEST_CASE("mpirun -np 3 gradem study: a tiny DEM resolution study, bitwise the thread run, each edge's model on the workers",
          "[calibrate][mpi]") {
    TempDir dir("study-mpi-dem");
    // Two edges: two DEM models (other packings, other fingerprints), so the workers run
    // requests of both cases (sand 0 of case 2 is StudyModels sand 1).
    const StudyBothWays r = study_both_ways(dir.path, dem_problem(dir.path),
                                            "kind = \"resolution\"\nedges_mm = [1.6, 1.8]\nseeds = [1, 2]\n[run]\nworkers = 2\n");
    CHECK_THAT(r.mpi_output, Contains("worker ranks loaded the packings"));
    CHECK(without_wall_times(r.threads["data"]) == without_wall_times(r.mpi["data"]));
    CHECK(without_wall_times(r.threads["cases"]) == without_wall_times(r.mpi["cases"]));
    REQUIRE(r.threads_ledger.size() == 4);  // 2 edges x 2 seeds, one sand: every run is a DEM run of its own
    check_same_runs(r.threads_ledger, r.mpi_ledger);
    for (const auto& [key, row] : r.mpi_ledger) {
        CHECK(row.status == "ok");
        CHECK((row.rank == 1 || row.rank == 2));
    }
}

namespace {

/// The uninterrupted answer of a problem with the thread executor, in its own ledger.
cal::CalibrationResult reference_of(const fs::path& cfg, const fs::path& ledger) {
    cal::CalibrationProblem p = cal::load_calibration_problem(cfg);
    p.ledger = ledger;
    auto model = cal::make_model(p);
    return cal::run_calibration(p, *model);
}

std::vector<double> best_of(const cal::CalibrationResult& r) { return r.stages.at(0).solution.best; }

/// Rank 0 ends a job that lost a rank without MPI_Finalize (a lost rank cannot finalize); what
/// mpiexec then does with the ranks it must kill is Open MPI's, and its teardown has taken from
/// seconds to over three minutes on a loaded 2-core machine. So such a job counts as ended if it
/// exited, or if rank 0 had said it ends the job when the time limit came (the test then kills
/// it); one that never got that far fails.
bool rank0_ended_job(const Finished& f) {
    return !f.timed_out || f.output.find("ending the job without MPI_Finalize") != std::string::npos;
}

}  // namespace

TEST_CASE("a worker rank that exits mid-run ends the job without a hang, the rerun resumes from the ledger",
          "[calibrate][mpi]") {
    TempDir dir("cal-mpi-die");
    const fs::path cfg = analytic_problem(dir.path, 60);
    const cal::CalibrationResult reference = reference_of(cfg, dir.path / "reference.sqlite");
    // Rank 2 exits (no MPI_Finalize) at its 6th run: mpirun ends the whole job.
    const Finished died = run(mpirun(3, {GRADEM_MPI_DRIVER, cfg.string(), "--slow-ms", "20", "--die-rank", "2", "--die-after", "5"}),
                              dir.path, 60);
    INFO(died.output);
    CHECK_FALSE(died.timed_out);
    CHECK(died.exit_code != 0);
    const fs::path ledger = dir.path / "out" / "ledger.sqlite";
    const auto recorded = ledger_rows(ledger);
    REQUIRE(recorded.size() >= 5);  // rank 2's five and whatever rank 1 finished
    REQUIRE(static_cast<int>(recorded.size()) < reference.runs_used);
    CHECK_FALSE(fs::exists(dir.path / "out" / "summary.json"));
    // The same command without the fault: resumes, repeats no run, same answer as never killed.
    const Finished again = run(mpirun(3, {GRADEM_MPI_DRIVER, cfg.string()}), dir.path, 60);
    INFO(again.output);
    REQUIRE(again.exit_code == 0);
    const auto summary = read_json(dir.path / "out" / "summary.json");
    CHECK(summary["runs"]["from_ledger"].get<int>() == static_cast<int>(recorded.size()));
    CHECK(summary["runs"]["total"].get<int>() == reference.runs_used);
    CHECK(parameters_of(summary) == best_of(reference));
}

TEST_CASE("a whole MPI job killed mid-way resumes from the ledger to the uninterrupted answer", "[calibrate][mpi]") {
    TempDir dir("cal-mpi-kill");
    const fs::path cfg = analytic_problem(dir.path, 60);
    const cal::CalibrationResult reference = reference_of(cfg, dir.path / "reference.sqlite");
    const fs::path ledger = dir.path / "out" / "ledger.sqlite", log = dir.path / "killed.log";
    const pid_t job = start(mpirun(3, {GRADEM_MPI_DRIVER, cfg.string(), "--slow-ms", "40"}), dir.path, log);
    std::size_t rows = 0;
    for (int k = 0; k < 3000 && rows < 10; ++k) {
        std::this_thread::sleep_for(std::chrono::milliseconds(10));
        if (fs::exists(ledger)) rows = ledger_rows(ledger).size();
    }
    kill(job, SIGTERM);  // what a batch scheduler does at the end of a job's time
    const Finished killed = finish(job, log, 30);
    INFO(killed.output);
    CHECK_FALSE(killed.timed_out);
    CHECK(killed.exit_code != 0);
    // Count the rows on a copy: the ledger itself may hold a hot journal (killed mid-commit),
    // which the resumed calibration must cope with.
    for (const char* suffix : {"", "-journal"})
        if (fs::exists(ledger.string() + suffix)) fs::copy_file(ledger.string() + suffix, dir.path / (std::string("copy.sqlite") + suffix));
    const std::size_t recorded = ledger_rows(dir.path / "copy.sqlite").size();
    REQUIRE(recorded >= 10);
    REQUIRE(static_cast<int>(recorded) < reference.runs_used);
    const Finished again = run(mpirun(3, {GRADEM_MPI_DRIVER, cfg.string()}), dir.path, 60);
    INFO(again.output);
    REQUIRE(again.exit_code == 0);
    const auto summary = read_json(dir.path / "out" / "summary.json");
    CHECK(summary["runs"]["from_ledger"].get<std::size_t>() == recorded);
    CHECK(summary["runs"]["total"].get<int>() == reference.runs_used);
    CHECK(parameters_of(summary) == best_of(reference));
}

TEST_CASE("a worker rank that stops answering is given up after timeout + grace: recorded, the calibration goes on",
          "[calibrate][mpi]") {
    TempDir dir("cal-mpi-hang");
    const fs::path cfg = analytic_problem(dir.path, 40, "[run]\ntimeout_s = 3\n");
    const Finished f = run(mpirun(3, {GRADEM_MPI_DRIVER, cfg.string(), "--hang-rank", "2", "--hang-after", "3"}), dir.path, 120);
    INFO(f.output);
    CHECK(rank0_ended_job(f));
    CHECK((f.timed_out || f.exit_code != 0));  // a lost rank cannot finalize: rank 0 exits without it...
    CHECK_THAT(f.output, Contains("did not answer"));
    CHECK(fs::exists(dir.path / "out" / "summary.json"));  // ...after rank 0 wrote its outputs
    int lost = 0, by_rank_1 = 0;
    for (const auto& [key, r] : ledger_rows(dir.path / "out" / "ledger.sqlite")) {
        if (r.status == "timeout") {
            ++lost;
            CHECK(r.rank == 2);
            CHECK_THAT(r.reason, Contains("rank 2") && Contains("sent no result within"));
        }
        by_rank_1 += r.rank == 1;
    }
    CHECK(lost == 1);
    CHECK(by_rank_1 > 3);  // the rest went to rank 1
}

TEST_CASE("bad MPI setups: one clear message from rank 0 and a non-zero exit", "[calibrate][mpi]") {
    TempDir dir("cal-mpi-bad");
    const fs::path cfg = analytic_problem(dir.path, 20);
    SECTION("launched with one rank") {
        const Finished f = run(mpirun(1, {GRADEM_BIN, "calibrate", cfg.string()}), dir.path);
        INFO(f.output);
        CHECK(f.exit_code == 1);  // refused before any run (common/exit_status.hpp)
        CHECK_THAT(f.output, Contains("MPI launched with one rank") && Contains("-np 3"));
    }
    SECTION("a worker rank of another build") {
        const Finished f = run(mpirun(3, {GRADEM_MPI_DRIVER, cfg.string(), "--code-version-rank", "2", "0.0.0+other"}), dir.path);
        INFO(f.output);
        CHECK(f.exit_code == 2);
        CHECK_THAT(f.output, Contains("rank 2 on host") && Contains("0.0.0+other") && Contains("mismatched builds"));
        CHECK_FALSE(fs::exists(dir.path / "out" / "ledger.sqlite"));  // nothing ran
    }
    SECTION("a config no rank can read: rank 0 says so, once") {
        const Finished f = run(mpirun(3, {GRADEM_BIN, "calibrate", (dir.path / "missing.toml").string()}), dir.path);
        INFO(f.output);
        CHECK(f.exit_code == 1);  // bad input
        std::size_t count = 0;
        for (std::size_t at = f.output.find("missing.toml"); at != std::string::npos; at = f.output.find("missing.toml", at + 1)) ++count;
        CHECK(count == 1);
    }
}

TEST_CASE("a worker rank that cannot reach the packing cache: rank 0 names it and stops", "[calibrate][mpi]") {
    TempDir dir("cal-mpi-cache");
    const fs::path cfg = dem_problem(dir.path);
    const Finished f = run(mpirun(3, {GRADEM_MPI_DRIVER, cfg.string(), "--cache-dir-rank", "2", (dir.path / "no-such-cache").string()}),
                           dir.path, 300);
    INFO(f.output);
    CHECK(f.exit_code == 2);
    CHECK_THAT(f.output, Contains("rank 2 on host") && Contains("cannot load the packings") && Contains("not found") &&
                             Contains("every rank can read"));
    CHECK(ledger_rows(dir.path / "out" / "ledger.sqlite").empty());  // no run went out
}

TEST_CASE("with mpirun --enable-recovery a worker that exits is given up after timeout + grace and the calibration "
          "finishes on the others", "[calibrate][mpi]") {
    TempDir dir("cal-mpi-recover");
    const fs::path cfg = analytic_problem(dir.path, 40, "[run]\ntimeout_s = 3\n");
    std::vector<std::string> argv = mpirun(3, {GRADEM_MPI_DRIVER, cfg.string(), "--slow-ms", "20", "--die-rank", "2", "--die-after", "5"});
    argv.insert(argv.begin() + 1, "--enable-recovery");  // Open MPI 4.1: keep the job when a process dies
    const Finished f = run(argv, dir.path, 60);
    INFO(f.output);
    CHECK(rank0_ended_job(f));
    // Rank 0 ends it without finalizing (the dead rank cannot); mpirun's exit status under
    // --enable-recovery does not tell, so the message is what tells.
    CHECK_THAT(f.output, Contains("did not answer"));
    CHECK(fs::exists(dir.path / "out" / "summary.json"));
    int lost = 0, by_rank_2 = 0, by_rank_1 = 0;
    for (const auto& [key, r] : ledger_rows(dir.path / "out" / "ledger.sqlite")) {
        if (r.status == "timeout") {
            ++lost;
            CHECK(r.rank == 2);
            CHECK_THAT(r.reason, Contains("rank 2") && Contains("no longer used"));
        } else {
            by_rank_2 += r.rank == 2;
            by_rank_1 += r.rank == 1;
        }
    }
    CHECK(lost == 1);
    CHECK(by_rank_2 == 5);  // its runs before it died
    CHECK(by_rank_1 > 5);   // the calibration went on on rank 1
}
