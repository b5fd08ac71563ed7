#pragma once
// Which executor runs a command's cube tests: `workers` threads of this process
// (ThreadExecutor), unless a launcher started this process as one rank of a job on another
// executor. THE list of those executors is kLaunchedExecutors in launch.cpp: one row each, its
// name, how it tells that its launcher started this process, and how it runs a job. An executor
// is its file (a RunExecutor and its job, as execution/mpi_executor.cpp) plus that row
// (docs/extending.md "A run executor"); the commands that run cube tests (calibrate, study)
// call run_on_launched_executor and need no edit.
#include <functional>
#include <memory>
#include <optional>

#include "calibrate/cube_model.hpp"
#include "calibrate/execution/run_executor.hpp"

namespace gradem::cal {

/// What every process of a job makes first, from the config every process reads: the job's
/// cube model, and the threads the coordinating process prepares it with.
struct JobModel {
    std::unique_ptr<CubeModel> model;
    int threads = 1;
};
using MakeJobModel = std::function<JobModel(int rank)>;
/// The job itself, on the process that coordinates it: its runs go through `executor`.
using RunJob = std::function<int(CubeModel& model, RunExecutor& executor)>;

/// Runs the job on the executor whose launcher started this process and returns its exit
/// status; nullopt when no launcher did (the caller then runs it on threads). Throws
/// std::runtime_error when a launcher started it that this build has no executor for (mpirun
/// and a build without MPI: every copy would run the whole job into one ledger).
std::optional<int> run_on_launched_executor(const MakeJobModel& make, const RunJob& run);

}  // namespace gradem::cal
