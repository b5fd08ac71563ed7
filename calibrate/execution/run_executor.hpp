#pragma once
// Where the cube tests of an evaluation run. The Evaluator hands an executor a batch of
// independent runs - each a pure function of (sand, packing seed, material) - and is told of
// every finished one; the optimizer, the ledger and the reports never know where a run went.
//   ThreadExecutor  `workers` std::threads in this process, one OpenMP thread each
//   MpiExecutor     worker ranks of an MPI job (calibrate/execution/mpi_executor.hpp; GRADEM_MPI builds)
// A study (several calibrations) can share one executor: it only sees RunRequests.
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "calibrate/cube_model.hpp"

namespace gradem::cal {

/// Where a run ran: the MPI rank (0 for the thread executor) and the host name.
struct RunPlace {
    int rank = 0;
    std::string host;
};

/// This machine's host name ("unknown" if it cannot be read).
std::string host_name();

/// True when an MPI launcher (mpirun, mpiexec, srun with PMIx/PMI) started this process,
/// whether or not this build has MPI (a build without it must refuse such a start).
bool started_by_mpi_launcher();

class RunExecutor {
public:
    /// Called once per request when it ends: its index in the batch, outcome and place.
    using RunDone = std::function<void(std::size_t index, const RunOutcome& outcome, const RunPlace& place)>;
    using Log = std::function<void(const std::string&)>;

    virtual ~RunExecutor() = default;
    /// Makes (or loads) what the runs of these packing seeds need, everywhere they may run.
    virtual void prepare(const PackingSeeds& seeds, const Log& log) = 0;
    /// Runs every request and returns when all have ended. `done` is called once per request,
    /// never concurrently (it may record into the ledger without a lock of its own). A run
    /// that fails is an outcome, not an exception; an exception thrown by `done` is rethrown
    /// after the runs in flight have ended.
    virtual void run(const std::vector<RunRequest>& requests, double timeout_s, const RunDone& done) = 0;
    /// Runs at a time (for the ETA).
    [[nodiscard]] virtual int slots() const = 0;
    /// One line for the log, e.g. "2 threads on host a" or "MPI: 63 worker ranks on 4 hosts".
    [[nodiscard]] virtual std::string describe() const = 0;
};

/// Today's behaviour: the runs of a batch on `workers` threads of this process.
class ThreadExecutor final : public RunExecutor {
public:
    ThreadExecutor(CubeModel& model, int workers);
    /// Over a model prepared elsewhere: prepare() is then an error.
    ThreadExecutor(const CubeModel& model, int workers);
    void prepare(const PackingSeeds& seeds, const Log& log) override;
    void run(const std::vector<RunRequest>& requests, double timeout_s, const RunDone& done) override;
    [[nodiscard]] int slots() const override { return workers_; }
    [[nodiscard]] std::string describe() const override;

private:
    const CubeModel& model_;
    CubeModel* preparable_;  ///< the same model, when it may be prepared here
    int workers_;
    RunPlace place_;
};

}  // namespace gradem::cal
