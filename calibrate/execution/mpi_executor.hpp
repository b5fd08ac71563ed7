#pragma once
// Cube tests spread over the ranks of an MPI job (Open MPI; GRADEM_MPI builds only).
//
// Rank 0 runs the optimizer, the ledger and the reports; it coordinates and runs no cube
// test itself. Ranks 1..N-1 are workers: each loads the same problem (every rank reads the
// same config, so the folders must be on a file system all nodes see), says hello (code
// version, host, model fingerprint), loads rank 0's packings from the shared packing cache,
// then runs one request at a time (OpenMP threads: OMP_NUM_THREADS) until told to stop. The
// messages are calibrate/execution/run_message.hpp's versioned byte strings.
//
// Faults (Open MPI 4.1 as Debian 12 builds it has no ULFM, so a rank that dies takes the job):
//   - a run that fails, throws or times out on its worker is an outcome (status and reason)
//     sent back like any result: recorded, and the calibration goes on;
//   - a worker that sends no result within timeout_s + grace is recorded as timed out and no
//     longer used; if none is left the calibration stops with a message; a job with a lost
//     rank ends with rank 0 exiting (status 5) without MPI_Finalize once it has written its
//     outputs (a lost rank cannot finalize), and mpirun ending the job;
//   - a worker process that exits or is killed: mpirun ends the whole job (its default), so
//     nothing hangs; rerun the same command and it resumes from the ledger. Under
//     `mpirun --enable-recovery` the job lives on and the dead worker is given up after
//     timeout_s + grace like a stuck one.
// Bad setups end at start-up with a message from rank 0 naming the rank, its host and what
// is wrong (one rank only, another code version or model, packings it cannot read).
#include <functional>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include "calibrate/execution/launch.hpp"
#include "calibrate/execution/run_executor.hpp"

namespace gradem::cal::mpi {

/// A setup or coordination error of the MPI job (the message names rank and host).
class ExecutorError : public std::runtime_error {
public:
    using std::runtime_error::runtime_error;
};

/// True when an MPI launcher (mpirun, mpiexec, srun with PMIx/PMI) started this process.
bool launched();

/// The job's MPI session: MPI_Init_thread (funneled) on construction; MPI_Finalize on
/// destruction, or an exit without it when a rank was lost (finalizing would wait for it
/// forever; MPI_Abort can leave Open MPI 4.1's mpirun hanging: mpi_executor.cpp).
class Session {
public:
    Session();
    ~Session();
    Session(const Session&) = delete;
    Session& operator=(const Session&) = delete;
    [[nodiscard]] int rank() const { return rank_; }
    [[nodiscard]] int size() const { return size_; }

private:
    int rank_ = 0, size_ = 1;
};

/// What a worker rank says about itself (tests fake another build with `code_version`).
struct WorkerIdentity {
    std::string code_version;  ///< default: cal::code_version()
};

/// A worker rank's life: hello (with `load_error` if it could not load the problem or
/// model), then prepare and run requests until rank 0 says stop. Returns 0 then, whatever
/// the reason: rank 0 reports and sets the job's exit code (mpirun kills the job as soon as
/// one rank exits non-zero, which could cut rank 0's message off).
int serve(CubeModel* model, const std::string& load_error, const WorkerIdentity& identity = {});

/// Rank 0, when it cannot go on before an executor exists: waits for every worker's hello
/// (at most `timeout_s`) and tells each to stop with `reason`.
void dismiss_workers(const std::string& reason, double timeout_s = 60.0);

class MpiExecutor final : public RunExecutor {
public:
    /// Rank 0: waits for every worker's hello (at most `handshake_timeout_s`) and checks
    /// it. Throws ExecutorError (after stopping every worker) if a worker could not load
    /// the problem, runs another code version or another model. `threads`: rank 0's
    /// threads for making the packings.
    MpiExecutor(CubeModel& model, int threads, double handshake_timeout_s = 300.0);
    /// Tells every worker still in contact to stop.
    ~MpiExecutor() override;
    MpiExecutor(const MpiExecutor&) = delete;
    MpiExecutor& operator=(const MpiExecutor&) = delete;

    /// Makes the packings on rank 0 (cached), then has every worker load them from the cache.
    void prepare(const PackingSeeds& seeds, const Log& log) override;
    void run(const std::vector<RunRequest>& requests, double timeout_s, const RunDone& done) override;
    [[nodiscard]] int slots() const override;
    [[nodiscard]] std::string describe() const override;
    /// Workers that did not answer in time and are no longer used.
    [[nodiscard]] std::vector<int> lost_ranks() const;
    /// Seconds rank 0 waits beyond a run's timeout before giving its worker up.
    [[nodiscard]] static double grace_seconds(double timeout_s) { return 5.0 + 0.1 * timeout_s; }

private:
    struct Worker {
        int rank = 0;
        std::string host;
        std::int64_t threads = 1;
        bool lost = false, stopped = false;
    };
    void stop_all(const std::string& reason);
    class Batch;  ///< one run() call: requests handed out, results collected (mpi_executor.cpp)

    CubeModel& model_;
    int threads_;
    std::string model_hash_;
    std::vector<Worker> workers_;  // ranks 1..N-1
    std::uint64_t next_job_ = 1;
    double handshake_timeout_s_;
};

/// The whole MPI job around a task that uses the runs (gradem calibrate; a study later):
/// every rank calls `make_model` (it reads the config; a throw on a worker becomes that
/// worker's load error, reported by rank 0); the workers serve; rank 0 makes an MpiExecutor
/// and returns `coordinate(model, executor)`. Rank 0's errors are rethrown after the workers
/// were stopped and MPI finalized; a worker returns its exit code.
using JobModel = cal::JobModel;  ///< the model every rank makes; threads: rank 0's for making packings
int run_job(const std::function<JobModel(int rank)>& make_model, const std::function<int(CubeModel&, MpiExecutor&)>& coordinate,
            const WorkerIdentity& identity = {});

}  // namespace gradem::cal::mpi
