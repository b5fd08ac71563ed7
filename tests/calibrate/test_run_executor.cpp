// The run executor layer without MPI: the versioned run messages (every material field, the
// outcome bitwise, bad headers refused), the thread executor's contract, the ledger's
// rank/host columns and its schema upgrade, and bond-law-aware material keys.
#include <sqlite3.h>
#include <sys/wait.h>
#include <unistd.h>

#include <atomic>
#include <catch2/catch.hpp>
#include <cmath>
#include <cstring>
#include <limits>
#include <set>
#include <thread>

#include "calibrate/execution/ledger.hpp"
#include "calibrate/execution/run_executor.hpp"
#include "calibrate/execution/run_message.hpp"
#include "calibrate_fixture.hpp"

namespace fs = std::filesystem;
using namespace gradem;
using gradem::test::TempDir;
using Catch::Matchers::Contains;

namespace {

/// A material whose every field differs from its default and from every other field.
exp::MaterialParams odd_material() {
    exp::MaterialParams m;
    double v = 1.25;
    for (double* x : {&m.contact.effective_modulus, &m.contact.stiffness_ratio, &m.contact.friction, &m.bond.effective_modulus,
                      &m.bond.stiffness_ratio, &m.bond.radius_multiplier, &m.bond.moment_factor, &m.bond.tensile_strength_mean,
                      &m.bond.tensile_strength_std, &m.bond.cohesion_mean, &m.bond.cohesion_std, &m.bond.friction_angle_deg,
                      &m.bond_gap_fraction, &m.bond_gap_absolute, &m.platen_friction, &m.damping})
        *x = (v += 0.1) / 3.0;  // not exactly representable in decimal: bits matter
    m.bond.seed = 0xDEADBEEFCAFEull;
    m.bond.model = BondModel::flat_joint;
    m.bond.replaces_contact = !m.bond.replaces_contact;
    // every row of every law: doubles as above, counts distinct, yes/no flipped
    std::int64_t count = 3;
    for_each_bond_law([&](auto kernel) {
        using Law = decltype(kernel);
        for (const auto& row : Law::kParameters) {
            auto& own = m.bond.law<Law>();
            if (row.field.flag) row.field.set_int(own, 1 - row.field.get_int(own));
            else if (row.field.integer) row.field.set_int(own, count += 4);
            else row.field.set(own, (v += 0.1) / 3.0);
        }
    });
    return m;
}

/// Every row of every law holds the same bits in a and b; the number of rows compared.
std::size_t same_law_rows(const exp::MaterialParams& a, const exp::MaterialParams& b) {
    std::size_t rows = 0;
    for_each_bond_law([&](auto kernel) {
        using Law = decltype(kernel);
        for (const auto& row : Law::kParameters) {
            INFO(bond_model_name(bond_model_of<Law>) << " row " << row.key);
            if (row.field.integer) CHECK(row.field.get_int(b.bond.law<Law>()) == row.field.get_int(a.bond.law<Law>()));
            else {
                const double x = row.field.get(a.bond.law<Law>()), y = row.field.get(b.bond.law<Law>());
                CHECK(std::memcmp(&x, &y, sizeof x) == 0);
            }
            ++rows;
        }
    });
    return rows;
}

bool same_bits(double a, double b) { return std::memcmp(&a, &b, sizeof a) == 0; }

}  // namespace

TEST_CASE("run request round trip keeps every material field bit for bit", "[calibrate][executor]") {
    cal::wire::Run run;
    run.job = 42;
    run.code_version = cal::code_version();
    run.model_hash = "0123456789abcdef";
    run.timeout_s = 600.0;
    run.request = {1, 7, odd_material()};
    const cal::wire::Run back = cal::wire::decode_run(cal::wire::encode(run));
    CHECK(back.job == 42);
    CHECK(back.code_version == run.code_version);
    CHECK(back.model_hash == run.model_hash);
    CHECK(back.request.sand == 1);
    CHECK(back.request.seed == 7);
    const exp::MaterialParams &a = run.request.material, &b = back.request.material;
    CHECK(cal::material_key(a) == cal::material_key(b));  // every field material_key knows, as hex floats
    CHECK(b.bond.model == BondModel::flat_joint);
    CHECK(b.bond.seed == a.bond.seed);
    CHECK(b.bond.replaces_contact == a.bond.replaces_contact);
    CHECK(same_law_rows(a, b) >= 9);  // the soft bond's 2 rows and the flat joint's 7, at least
    CHECK(b.bond.law<FlatJointLaw>().radial_elements != FlatJointParams{}.radial_elements);
    CHECK(same_bits(b.bond.law<SoftBondLaw>().cut_fraction, a.bond.law<SoftBondLaw>().cut_fraction));
}

TEST_CASE("material keys tell bond laws apart and keep parallel-bond keys as before", "[calibrate][executor]") {
    exp::MaterialParams m = odd_material();
    m.bond.model = BondModel::parallel_bond;
    const std::string parallel = cal::material_key(m);
    CHECK(parallel.find("law=") == std::string::npos);  // the key text of ledgers written before the other laws
    m.bond.model = BondModel::soft_bond;
    const std::string soft = cal::material_key(m);
    m.bond.law<SoftBondLaw>().cut_fraction *= 2.0;
    CHECK(soft != parallel);
    CHECK(cal::material_key(m) != soft);
}

TEST_CASE("run result round trip is bitwise, NaN and curve included", "[calibrate][executor]") {
    cal::wire::Result r;
    r.job = 9;
    r.outcome.status = cal::OutcomeStatus::diverged;
    r.outcome.reason = "diverged: kinetic energy blew up";
    r.outcome.modulus_pa = 1.0 / 3.0 * 1e10;
    r.outcome.peak_pa = std::nextafter(2e7, 3e7);
    r.outcome.strain_at_peak = 2.9e-3;
    r.outcome.poisson = std::numeric_limits<double>::quiet_NaN();
    r.outcome.particles = 12345, r.outcome.bonds = 67890, r.outcome.steps = 1234567;
    r.outcome.wall_seconds = 12.5;
    for (int i = 0; i < 200; ++i) r.outcome.curve_strain.push_back(i / 7.0e4), r.outcome.curve_stress_pa.push_back(i * 1.1e5 / 3.0);
    const std::string bytes = cal::wire::encode(r);
    const cal::wire::Result b = cal::wire::decode_result(bytes);
    CHECK(b.job == 9);
    CHECK(b.outcome.status == cal::OutcomeStatus::diverged);
    CHECK(b.outcome.reason == r.outcome.reason);
    CHECK(same_bits(b.outcome.modulus_pa, r.outcome.modulus_pa));
    CHECK(same_bits(b.outcome.peak_pa, r.outcome.peak_pa));
    CHECK(std::isnan(b.outcome.poisson));
    CHECK(b.outcome.steps == 1234567);
    CHECK(b.outcome.curve_strain == r.outcome.curve_strain);
    CHECK(b.outcome.curve_stress_pa == r.outcome.curve_stress_pa);
    CHECK(bytes.size() < 200 * 16 + 200);  // a result is a few kB: the curve and a header
}

TEST_CASE("messages of another protocol version, truncated or of the wrong kind are refused with a reason",
          "[calibrate][executor]") {
    std::string hello = cal::wire::encode(cal::wire::Hello{"v1", "host", "fp", 1, 1, ""});
    CHECK(cal::wire::kind_of(hello) == cal::wire::Kind::hello);
    CHECK(cal::wire::decode_hello(hello).host == "host");
    std::string other = hello;
    other[4] = static_cast<char>(cal::wire::kProtocolVersion + 1);
    CHECK_THROWS_WITH(cal::wire::kind_of(other), Contains("protocol version") && Contains("mismatched gradem builds"));
    CHECK_THROWS_WITH(cal::wire::decode_hello(hello.substr(0, hello.size() - 3)), Contains("truncated"));
    CHECK_THROWS_WITH(cal::wire::decode_result(hello), Contains("expected a 'result' message, got 'hello'"));
    CHECK_THROWS_WITH(cal::wire::kind_of("GRDM"), Contains("shorter than a header"));
    CHECK_THROWS_WITH(cal::wire::decode_stop(cal::wire::encode(cal::wire::Stop{"x"}) + "junk"), Contains("unexpected bytes"));
}

TEST_CASE("thread executor: every request once, callbacks one at a time, outcomes the model's", "[calibrate][executor]") {
    auto model = cal::make_analytic_model(2, 0.01);
    cal::ThreadExecutor threads(*model, 3);
    std::vector<cal::RunRequest> requests;
    for (std::uint64_t seed = 1; seed <= 40; ++seed) requests.push_back({seed % 2, seed, odd_material()});
    std::vector<int> calls(requests.size(), 0);
    std::atomic<int> inside{0};
    int overlap = 0;
    threads.run(requests, 0.0, [&](std::size_t k, const cal::RunOutcome& o, const cal::RunPlace& place) {
        if (inside++ != 0) ++overlap;
        ++calls.at(k);
        const cal::RunOutcome direct = model->run(requests[k], 0.0);
        CHECK(same_bits(o.modulus_pa, direct.modulus_pa));
        CHECK(place.rank == 0);
        CHECK(place.host == cal::host_name());
        std::this_thread::sleep_for(std::chrono::microseconds(200));
        --inside;
    });
    CHECK(overlap == 0);
    CHECK(std::set<int>(calls.begin(), calls.end()) == std::set<int>{1});
    CHECK(threads.slots() == 3);
    // Over a const model (prepared elsewhere) it runs, but does not prepare.
    const cal::CubeModel& prepared = *model;
    cal::ThreadExecutor over_const(prepared, 1);
    CHECK_THROWS_AS(over_const.prepare({1}, {}), std::logic_error);
}

namespace {

void sql(const fs::path& file, const std::string& text) {
    sqlite3* db = nullptr;
    REQUIRE(sqlite3_open(file.c_str(), &db) == SQLITE_OK);
    char* err = nullptr;
    const int rc = sqlite3_exec(db, text.c_str(), nullptr, nullptr, &err);
    INFO((err ? err : ""));
    sqlite3_free(err);
    sqlite3_close(db);
    REQUIRE(rc == SQLITE_OK);
}

}  // namespace

TEST_CASE("ledger: rank and host per run, a schema-1 ledger is upgraded and stays readable, a newer one is refused",
          "[calibrate][executor]") {
    TempDir dir("cal-ledger-schema");
    const fs::path old = dir.path / "old.sqlite";
    // A ledger as the first calibrate wrote it (no rank/host, no schema_version).
    sql(old,
        "CREATE TABLE meta(key TEXT PRIMARY KEY, value TEXT);"
        "CREATE TABLE runs(run_key TEXT PRIMARY KEY, sand TEXT, seed INTEGER, parameters TEXT, material TEXT,"
        " status TEXT, reason TEXT, modulus_pa REAL, peak_pa REAL, strain_at_peak REAL, poisson REAL,"
        " particles INTEGER, bonds INTEGER, steps INTEGER, wall_seconds REAL, curve TEXT, code_version TEXT,"
        " finished_utc TEXT, sequence INTEGER);"
        "INSERT INTO meta VALUES ('problem_fingerprint', 'fp'), ('problem', 'p');"
        "INSERT INTO runs VALUES ('k1', 'a', 1, '{}', 'm', 'ok', '', 1.5e10, 2e7, 0.003, 0.2, 100, 200, 300, 1.0,"
        " '0 0;0.001 1e7', 'old', '2026-01-01T00:00:00Z', 0);");
    {
        cal::Ledger ledger(old, "fp", "p");
        const auto found = ledger.find("k1");
        REQUIRE(found);
        CHECK(found->modulus_pa == 1.5e10);
        CHECK(found->curve_strain.size() == 2);
        cal::RunOutcome o;
        o.status = cal::OutcomeStatus::ok;
        ledger.record("k2", "a", 2, "{}", "m", o, {5, "node-17"});
        CHECK(ledger.size() == 2);
    }
    sqlite3* db = nullptr;
    REQUIRE(sqlite3_open_v2(old.c_str(), &db, SQLITE_OPEN_READONLY, nullptr) == SQLITE_OK);
    sqlite3_stmt* s = nullptr;
    REQUIRE(sqlite3_prepare_v2(db, "SELECT run_key, rank, host FROM runs ORDER BY run_key", -1, &s, nullptr) == SQLITE_OK);
    REQUIRE(sqlite3_step(s) == SQLITE_ROW);
    CHECK(sqlite3_column_type(s, 1) == SQLITE_NULL);  // the old row: where it ran is unknown
    REQUIRE(sqlite3_step(s) == SQLITE_ROW);
    CHECK(sqlite3_column_int(s, 1) == 5);
    CHECK(std::string(reinterpret_cast<const char*>(sqlite3_column_text(s, 2))) == "node-17");
    sqlite3_finalize(s);
    REQUIRE(sqlite3_prepare_v2(db, "SELECT value FROM meta WHERE key = 'schema_version'", -1, &s, nullptr) == SQLITE_OK);
    REQUIRE(sqlite3_step(s) == SQLITE_ROW);
    CHECK(std::string(reinterpret_cast<const char*>(sqlite3_column_text(s, 0))) == "2");
    sqlite3_finalize(s);
    sqlite3_close(db);
    // A ledger from a newer gradem: refused, untouched.
    sql(old, "UPDATE meta SET value = '99' WHERE key = 'schema_version';");
    const auto before = fs::last_write_time(old);
    CHECK_THROWS_WITH(cal::Ledger(old, "fp", "p"), Contains("schema version 99") && Contains("left untouched"));
    CHECK(fs::last_write_time(old) == before);
}

TEST_CASE("ledger: a process killed in the middle of a commit leaves a hot journal, the ledger still opens and resumes",
          "[calibrate][executor]") {
    TempDir dir("cal-ledger-journal");
    const fs::path path = dir.path / "ledger.sqlite";
    cal::RunOutcome ok;
    ok.status = cal::OutcomeStatus::ok;
    ok.modulus_pa = 1e10;
    { cal::Ledger(path, "fp", "p").record("committed", "a", 1, "{}", "m", ok); }
    // A child writes a row and dies before COMMIT (as kill -9 in Ledger::record would).
    const pid_t child = fork();
    REQUIRE(child >= 0);
    if (child == 0) {
        sqlite3* db = nullptr;
        sqlite3_open(path.c_str(), &db);
        // A cache of two pages: the transaction spills into the database file, so the journal
        // is synced and hot (a reader must roll it back before it can trust the file).
        sqlite3_exec(db,
                     "PRAGMA cache_size = 2; BEGIN; UPDATE runs SET status = 'half-written'; DELETE FROM meta;"
                     " CREATE TABLE junk(b BLOB); WITH RECURSIVE c(x) AS (SELECT 1 UNION ALL SELECT x + 1 FROM c WHERE x < 500)"
                     " INSERT INTO junk SELECT randomblob(4000) FROM c;",
                     nullptr, nullptr, nullptr);
        _exit(0);
    }
    int status = 0;
    waitpid(child, &status, 0);
    REQUIRE(fs::exists(path.string() + "-journal"));  // hot: the rollback is pending
    cal::Ledger ledger(path, "fp", "p");
    const auto found = ledger.find("committed");
    REQUIRE(found);
    CHECK(found->status == cal::OutcomeStatus::ok);
    CHECK(ledger.size() == 1);
}
