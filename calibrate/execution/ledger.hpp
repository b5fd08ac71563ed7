#pragma once
// The calibration ledger: every cube test run in an SQLite file, one row per run, committed as
// soon as the run ends (so `kill -9` loses at most the runs in flight). A run is looked up by
// its key - FNV-1a of (model fingerprint, sand, packing seed, exact material) - so an identical
// request is served from the ledger and a resumed calibration repeats no run.
//
// The file belongs to one problem definition: its meta table holds the problem's fingerprint
// and description. Opening it for another problem throws LedgerMismatch before anything is
// written (the file is first opened read-only to check).
//
// Tables:
//   meta(key TEXT PRIMARY KEY, value TEXT)        problem_fingerprint, problem, created, code_version
//   runs(run_key TEXT PRIMARY KEY, sand TEXT, seed INTEGER, parameters TEXT (JSON, config units),
//        material TEXT, status TEXT, reason TEXT, modulus_pa REAL, peak_pa REAL,
//        strain_at_peak REAL, poisson REAL, particles INTEGER, bonds INTEGER, steps INTEGER,
//        wall_seconds REAL, curve TEXT ("strain stress;..."), code_version TEXT,
//        finished_utc TEXT, sequence INTEGER, rank INTEGER, host TEXT)
// rank and host (where the run ran: MPI rank, 0 for threads) came with schema 2 (meta
// schema_version); a schema-1 ledger gains the two columns when opened (its rows keep NULL
// there); a ledger of a newer schema is refused with a message.
#include <filesystem>
#include <mutex>
#include <optional>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "calibrate/cube_model.hpp"
#include "calibrate/execution/code_version.hpp"  // stored with every run
#include "calibrate/execution/run_executor.hpp"

struct sqlite3;

namespace gradem::cal {

class LedgerError : public std::runtime_error {
public:
    using std::runtime_error::runtime_error;
};
class LedgerMismatch : public LedgerError {
public:
    using LedgerError::LedgerError;
};

/// The ledger layout this build writes (meta schema_version; 1 when absent).
inline constexpr int kLedgerSchemaVersion = 2;

/// What one successful run of a ledger cost: its sand, particles, time steps and wall time.
struct RunCost {
    std::string sand;
    std::int64_t particles = 0, steps = 0;
    double wall_seconds = 0.0;  ///< [s], as measured where it ran (with the other runs in flight)
};

/// Every run of status ok in a ledger file, read-only, in the order they were recorded; throws
/// LedgerError naming the file when it cannot be read as a ledger.
std::vector<RunCost> read_run_costs(const std::filesystem::path& ledger_file);

/// One row of a ledger as recorded: what `read_ledger` returns (the Python module's
/// gradem.Ledger). The outcome's curve is the thinned gauge-strain curve kept with the run.
struct LedgerRun {
    std::string run_key, sand;
    std::uint64_t seed = 0;
    std::string parameters;  ///< JSON object, config units
    std::string material;    ///< the material's exact key (calibrate/cube_model.hpp material_key)
    RunOutcome outcome;
    std::string code_version, finished_utc;
    std::int64_t sequence = 0;
    int rank = -1;           ///< -1: not recorded (a schema-1 row)
    std::string host;
};

/// A whole ledger, read-only: its meta table (problem_fingerprint, problem, created,
/// code_version, schema_version) and every run in the order recorded.
struct LedgerContents {
    std::vector<std::pair<std::string, std::string>> meta;
    std::vector<LedgerRun> runs;
};

/// Reads a ledger file read-only; throws LedgerError naming the file when it cannot be read as
/// a ledger (missing, not SQLite, no runs table).
LedgerContents read_ledger(const std::filesystem::path& ledger_file);

class Ledger {
public:
    /// Opens (or creates) `path` for the problem with this fingerprint; `description` is kept
    /// in the file for people (and for the mismatch message).
    Ledger(const std::filesystem::path& path, const std::string& problem_fingerprint, const std::string& description);
    ~Ledger();
    Ledger(const Ledger&) = delete;
    Ledger& operator=(const Ledger&) = delete;

    [[nodiscard]] std::optional<RunOutcome> find(const std::string& run_key) const;
    void record(const std::string& run_key, const std::string& sand, std::uint64_t seed,
                const std::string& parameters_json, const std::string& material, const RunOutcome& outcome,
                const RunPlace& place = {});
    [[nodiscard]] std::int64_t size() const;
    [[nodiscard]] const std::filesystem::path& path() const { return path_; }

private:
    void upgrade_schema();
    std::filesystem::path path_;
    sqlite3* db_ = nullptr;
    mutable std::mutex mutex_;
};

}  // namespace gradem::cal
