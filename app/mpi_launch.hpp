#pragma once
// The commands that run cube tests (calibrate, study) when an MPI launcher started them.
#include <stdexcept>

#include "calibrate/execution/run_executor.hpp"

namespace gradem::app {

/// In a build without MPI: several copies started by mpirun would each run the whole job into
/// one ledger, so such a start is refused with what to do instead.
inline void refuse_mpi_launch_without_mpi() {
    if (cal::started_by_mpi_launcher())
        throw std::runtime_error("this gradem was built without MPI (GRADEM_MPI=OFF or no Open MPI found): run it without mpirun, "
                                 "or rebuild with libopenmpi-dev installed");
}

}  // namespace gradem::app
