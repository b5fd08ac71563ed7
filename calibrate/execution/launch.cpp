#include "calibrate/execution/launch.hpp"

#include <stdexcept>

#ifdef GRADEM_HAVE_MPI
#include "calibrate/execution/mpi_executor.hpp"
#endif

namespace gradem::cal {
namespace {

/// An executor a launcher starts a job on.
struct LaunchedExecutor {
    const char* name;
    bool (*launched)();                                       ///< its launcher started this process
    int (*run_job)(const MakeJobModel& make, const RunJob& run);  ///< the whole job, every rank
};

#ifdef GRADEM_HAVE_MPI
int run_mpi_job(const MakeJobModel& make, const RunJob& run) {
    return mpi::run_job(make, [&run](CubeModel& model, mpi::MpiExecutor& executor) { return run(model, executor); });
}
#endif

int refuse_without_mpi(const MakeJobModel&, const RunJob&) {
    throw std::runtime_error("this gradem was built without MPI (GRADEM_MPI=OFF or no Open MPI found): run it without mpirun, "
                             "or rebuild with libopenmpi-dev installed");
}

// Checked in order: the first whose launcher started this process runs the job.
const LaunchedExecutor kLaunchedExecutors[] = {
#ifdef GRADEM_HAVE_MPI
    {"MPI", mpi::launched, run_mpi_job},
#endif
    {"MPI (not in this build)", started_by_mpi_launcher, refuse_without_mpi},
};

}  // namespace

std::optional<int> run_on_launched_executor(const MakeJobModel& make, const RunJob& run) {
    for (const LaunchedExecutor& executor : kLaunchedExecutors)
        if (executor.launched()) return executor.run_job(make, run);
    return std::nullopt;
}

}  // namespace gradem::cal
