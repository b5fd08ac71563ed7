#include "calibrate/execution/ledger.hpp"

#include <sqlite3.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <sstream>

namespace gradem::cal {
namespace {

namespace fs = std::filesystem;

/// A prepared statement that finalizes itself.
class Statement {
public:
    Statement(sqlite3* db, const char* sql, const fs::path& file) : db_(db) {
        if (sqlite3_prepare_v2(db, sql, -1, &stmt_, nullptr) != SQLITE_OK)
            throw LedgerError(file.string() + ": SQLite: " + sqlite3_errmsg(db));
    }
    ~Statement() { sqlite3_finalize(stmt_); }
    Statement(const Statement&) = delete;
    Statement& operator=(const Statement&) = delete;
    sqlite3_stmt* get() { return stmt_; }
    void text(int i, const std::string& s) { sqlite3_bind_text(stmt_, i, s.c_str(), static_cast<int>(s.size()), SQLITE_TRANSIENT); }
    void real(int i, double v) {
        if (std::isfinite(v)) sqlite3_bind_double(stmt_, i, v);
        else sqlite3_bind_null(stmt_, i);
    }
    void integer(int i, std::int64_t v) { sqlite3_bind_int64(stmt_, i, v); }
    int step() { return sqlite3_step(stmt_); }
    std::string column_text(int i) {
        const unsigned char* t = sqlite3_column_text(stmt_, i);
        return t ? reinterpret_cast<const char*>(t) : "";
    }
    double column_real(int i) { return sqlite3_column_type(stmt_, i) == SQLITE_NULL ? std::nan("") : sqlite3_column_double(stmt_, i); }

private:
    sqlite3* db_;
    sqlite3_stmt* stmt_ = nullptr;
};

void exec(sqlite3* db, const char* sql, const fs::path& file) {
    char* err = nullptr;
    if (sqlite3_exec(db, sql, nullptr, nullptr, &err) != SQLITE_OK) {
        const std::string msg = err ? err : "unknown error";
        sqlite3_free(err);
        throw LedgerError(file.string() + ": SQLite: " + msg);
    }
}

std::string utc_now() {
    const std::time_t t = std::time(nullptr);
    char buf[32];
    std::strftime(buf, sizeof buf, "%Y-%m-%dT%H:%M:%SZ", std::gmtime(&t));
    return buf;
}

std::string meta_value(sqlite3* db, const std::string& key, const fs::path& file) {
    Statement s(db, "SELECT value FROM meta WHERE key = ?1", file);
    s.text(1, key);
    return s.step() == SQLITE_ROW ? s.column_text(0) : std::string();
}

/// A process killed in the middle of a commit (kill -9, a batch job's end) leaves a hot
/// journal. SQLite rolls it back - restoring the last committed state - on the next read by a
/// connection that may write; a read-only connection cannot, and would see no tables.
void roll_back_interrupted_commit(const fs::path& path) {
    std::error_code ec;
    if (!fs::exists(path.string() + "-journal", ec)) return;
    sqlite3* db = nullptr;
    if (sqlite3_open_v2(path.c_str(), &db, SQLITE_OPEN_READWRITE, nullptr) == SQLITE_OK) {
        sqlite3_busy_timeout(db, 5000);
        sqlite3_exec(db, "SELECT count(*) FROM sqlite_master", nullptr, nullptr, nullptr);
    }
    sqlite3_close(db);
}

/// Checks an existing file read-only: an SQLite ledger of this problem, or an error.
void check_existing(const fs::path& path, const std::string& fingerprint, const std::string& description) {
    roll_back_interrupted_commit(path);
    sqlite3* db = nullptr;
    if (sqlite3_open_v2(path.c_str(), &db, SQLITE_OPEN_READONLY, nullptr) != SQLITE_OK) {
        sqlite3_close(db);
        throw LedgerError(path.string() + ": cannot open the ledger read-only");
    }
    std::string found;
    try {
        found = meta_value(db, "problem_fingerprint", path);
    } catch (const LedgerError&) {
        sqlite3_close(db);
        throw LedgerMismatch(path.string() + ": not a gradem calibration ledger (no meta table); left untouched");
    }
    const std::string found_description = meta_value(db, "problem", path);
    const std::string schema = meta_value(db, "schema_version", path);
    sqlite3_close(db);
    if (!schema.empty() && std::atoi(schema.c_str()) > kLedgerSchemaVersion)
        throw LedgerMismatch(path.string() + ": ledger schema version " + schema + " is newer than this build's (" +
                             std::to_string(kLedgerSchemaVersion) + "); left untouched - use the gradem that wrote it");
    if (found != fingerprint) {
        // Name the first line of the problem description that differs.
        std::istringstream a(found_description), b(description);
        std::string la, lb;
        while (true) {
            const bool ga = static_cast<bool>(std::getline(a, la)), gb = static_cast<bool>(std::getline(b, lb));
            if (!ga && !gb) break;
            if (la != lb || ga != gb) break;
        }
        throw LedgerMismatch(path.string() + ": this ledger belongs to another problem definition (fingerprint " + found +
                             ", this problem " + fingerprint + "; first difference: ledger '" + la + "' vs config '" + lb +
                             "'); left untouched - use another [output] ledger path or the matching config");
    }
}

std::string curve_text(const RunOutcome& o) {
    std::string s;
    char buf[64];
    for (std::size_t i = 0; i < o.curve_strain.size(); ++i) {
        std::snprintf(buf, sizeof buf, "%s%.17g %.17g", i ? ";" : "", o.curve_strain[i], o.curve_stress_pa[i]);
        s += buf;
    }
    return s;
}

void parse_curve(const std::string& text, RunOutcome& o) {
    std::istringstream in(text);
    std::string item;
    while (std::getline(in, item, ';')) {
        double e = 0, s = 0;
        if (std::sscanf(item.c_str(), "%lg %lg", &e, &s) == 2) {
            o.curve_strain.push_back(e);
            o.curve_stress_pa.push_back(s);
        }
    }
}

/// The outcome columns status, reason, modulus_pa, peak_pa, strain_at_peak, poisson, particles,
/// bonds, steps, wall_seconds, curve of the row, starting at column `first`.
RunOutcome outcome_from_columns(Statement& s, int first) {
    RunOutcome o;
    o.status = parse_enum<OutcomeStatus>(s.column_text(first)).value_or(OutcomeStatus::failed);
    o.reason = s.column_text(first + 1);
    o.modulus_pa = s.column_real(first + 2);
    o.peak_pa = s.column_real(first + 3);
    o.strain_at_peak = s.column_real(first + 4);
    o.poisson = s.column_real(first + 5);
    o.particles = sqlite3_column_int64(s.get(), first + 6);
    o.bonds = sqlite3_column_int64(s.get(), first + 7);
    o.steps = sqlite3_column_int64(s.get(), first + 8);
    o.wall_seconds = s.column_real(first + 9);
    parse_curve(s.column_text(first + 10), o);
    return o;
}

}  // namespace

Ledger::Ledger(const fs::path& path, const std::string& fingerprint, const std::string& description) : path_(path) {
    const bool existed = fs::exists(path);
    if (existed) check_existing(path, fingerprint, description);
    if (!path.parent_path().empty()) fs::create_directories(path.parent_path());
    if (sqlite3_open_v2(path.c_str(), &db_, SQLITE_OPEN_READWRITE | SQLITE_OPEN_CREATE, nullptr) != SQLITE_OK) {
        const std::string msg = db_ ? sqlite3_errmsg(db_) : "out of memory";
        sqlite3_close(db_);
        db_ = nullptr;
        throw LedgerError(path.string() + ": cannot open the ledger: " + msg);
    }
    sqlite3_busy_timeout(db_, 5000);
    if (existed) {
        upgrade_schema();
        return;
    }
    exec(db_,
         "BEGIN;"
         "CREATE TABLE meta(key TEXT PRIMARY KEY, value TEXT);"
         "CREATE TABLE runs(run_key TEXT PRIMARY KEY, sand TEXT, seed INTEGER, parameters TEXT, material TEXT,"
         " status TEXT, reason TEXT, modulus_pa REAL, peak_pa REAL, strain_at_peak REAL, poisson REAL,"
         " particles INTEGER, bonds INTEGER, steps INTEGER, wall_seconds REAL, curve TEXT, code_version TEXT,"
         " finished_utc TEXT, sequence INTEGER, rank INTEGER, host TEXT);",
         path_);
    Statement s(db_, "INSERT INTO meta(key, value) VALUES (?1, ?2)", path_);
    for (const auto& [k, v] : {std::pair<std::string, std::string>{"problem_fingerprint", fingerprint},
                               {"problem", description}, {"created_utc", utc_now()}, {"code_version", code_version()},
                               {"schema_version", std::to_string(kLedgerSchemaVersion)}}) {
        s.text(1, k);
        s.text(2, v);
        if (s.step() != SQLITE_DONE) throw LedgerError(path_.string() + ": SQLite: " + sqlite3_errmsg(db_));
        sqlite3_reset(s.get());
    }
    exec(db_, "COMMIT;", path_);
}

Ledger::~Ledger() { sqlite3_close(db_); }

void Ledger::upgrade_schema() {
    // Schema 1 -> 2: where each run ran (rank, host). Old rows keep NULL.
    bool has_rank = false;
    {
        Statement s(db_, "SELECT name FROM pragma_table_info('runs')", path_);
        while (s.step() == SQLITE_ROW) has_rank = has_rank || s.column_text(0) == "rank";
    }
    if (has_rank) return;
    exec(db_,
         "BEGIN;"
         "ALTER TABLE runs ADD COLUMN rank INTEGER;"
         "ALTER TABLE runs ADD COLUMN host TEXT;"
         "INSERT OR REPLACE INTO meta(key, value) VALUES ('schema_version', '2');"
         "COMMIT;",
         path_);
}

std::optional<RunOutcome> Ledger::find(const std::string& run_key) const {
    const std::lock_guard lock(mutex_);
    Statement s(db_,
                "SELECT status, reason, modulus_pa, peak_pa, strain_at_peak, poisson, particles, bonds, steps, wall_seconds,"
                " curve FROM runs WHERE run_key = ?1",
                path_);
    s.text(1, run_key);
    if (s.step() != SQLITE_ROW) return std::nullopt;
    return outcome_from_columns(s, 0);
}

void Ledger::record(const std::string& run_key, const std::string& sand, std::uint64_t seed,
                    const std::string& parameters_json, const std::string& material, const RunOutcome& o,
                    const RunPlace& place) {
    const std::lock_guard lock(mutex_);
    Statement s(db_,
                "INSERT OR REPLACE INTO runs(run_key, sand, seed, parameters, material, status, reason, modulus_pa, peak_pa,"
                " strain_at_peak, poisson, particles, bonds, steps, wall_seconds, curve, code_version, finished_utc, sequence,"
                " rank, host) VALUES (?1, ?2, ?3, ?4, ?5, ?6, ?7, ?8, ?9, ?10, ?11, ?12, ?13, ?14, ?15, ?16,"
                " ?17, ?18, (SELECT COUNT(*) FROM runs), ?19, ?20)",
                path_);
    s.text(1, run_key);
    s.text(2, sand);
    s.integer(3, static_cast<std::int64_t>(seed));
    s.text(4, parameters_json);
    s.text(5, material);
    s.text(6, to_string(o.status));
    s.text(7, o.reason);
    s.real(8, o.modulus_pa);
    s.real(9, o.peak_pa);
    s.real(10, o.strain_at_peak);
    s.real(11, o.poisson);
    s.integer(12, o.particles);
    s.integer(13, o.bonds);
    s.integer(14, o.steps);
    s.real(15, o.wall_seconds);
    s.text(16, curve_text(o));
    s.text(17, code_version());
    s.text(18, utc_now());
    s.integer(19, place.rank);
    s.text(20, place.host);
    if (s.step() != SQLITE_DONE) throw LedgerError(path_.string() + ": SQLite: " + sqlite3_errmsg(db_));
}

std::int64_t Ledger::size() const {
    const std::lock_guard lock(mutex_);
    Statement s(db_, "SELECT COUNT(*) FROM runs", path_);
    return s.step() == SQLITE_ROW ? sqlite3_column_int64(s.get(), 0) : 0;
}

std::vector<RunCost> read_run_costs(const fs::path& ledger_file) {
    std::error_code ec;
    if (!fs::exists(ledger_file, ec)) throw LedgerError(ledger_file.string() + ": ledger not found");
    sqlite3* db = nullptr;
    if (sqlite3_open_v2(ledger_file.c_str(), &db, SQLITE_OPEN_READONLY, nullptr) != SQLITE_OK) {
        sqlite3_close(db);
        throw LedgerError(ledger_file.string() + ": cannot open the ledger read-only");
    }
    std::vector<RunCost> out;
    try {
        Statement s(db, "SELECT sand, particles, steps, wall_seconds FROM runs WHERE status = 'ok' ORDER BY sequence, rowid", ledger_file);
        while (s.step() == SQLITE_ROW)
            out.push_back({s.column_text(0), sqlite3_column_int64(s.get(), 1), sqlite3_column_int64(s.get(), 2), s.column_real(3)});
    } catch (...) {
        sqlite3_close(db);
        throw;
    }
    sqlite3_close(db);
    return out;
}

LedgerContents read_ledger(const fs::path& ledger_file) {
    std::error_code ec;
    if (!fs::exists(ledger_file, ec)) throw LedgerError(ledger_file.string() + ": ledger not found");
    roll_back_interrupted_commit(ledger_file);
    sqlite3* db = nullptr;
    if (sqlite3_open_v2(ledger_file.c_str(), &db, SQLITE_OPEN_READONLY, nullptr) != SQLITE_OK) {
        sqlite3_close(db);
        throw LedgerError(ledger_file.string() + ": cannot open the ledger read-only");
    }
    LedgerContents out;
    try {
        {
            Statement s(db, "SELECT key, value FROM meta ORDER BY key", ledger_file);
            while (s.step() == SQLITE_ROW) out.meta.emplace_back(s.column_text(0), s.column_text(1));
        }
        bool has_rank = false;  // schema 1 has no rank and host
        {
            Statement s(db, "SELECT name FROM pragma_table_info('runs')", ledger_file);
            while (s.step() == SQLITE_ROW) has_rank = has_rank || s.column_text(0) == "rank";
        }
        const std::string sql = std::string(
                                    "SELECT run_key, sand, seed, parameters, material, status, reason, modulus_pa, peak_pa,"
                                    " strain_at_peak, poisson, particles, bonds, steps, wall_seconds, curve, code_version,"
                                    " finished_utc, sequence") +
                                (has_rank ? ", rank, host" : "") + " FROM runs ORDER BY sequence, rowid";
        Statement s(db, sql.c_str(), ledger_file);
        while (s.step() == SQLITE_ROW) {
            LedgerRun r;
            r.run_key = s.column_text(0);
            r.sand = s.column_text(1);
            r.seed = static_cast<std::uint64_t>(sqlite3_column_int64(s.get(), 2));
            r.parameters = s.column_text(3);
            r.material = s.column_text(4);
            r.outcome = outcome_from_columns(s, 5);
            r.code_version = s.column_text(16);
            r.finished_utc = s.column_text(17);
            r.sequence = sqlite3_column_int64(s.get(), 18);
            if (has_rank && sqlite3_column_type(s.get(), 19) != SQLITE_NULL) r.rank = sqlite3_column_int(s.get(), 19);
            if (has_rank) r.host = s.column_text(20);
            out.runs.push_back(std::move(r));
        }
    } catch (...) {
        sqlite3_close(db);
        throw;
    }
    sqlite3_close(db);
    return out;
}

}  // namespace gradem::cal
