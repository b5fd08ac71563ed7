#pragma once
// The code version: the project version and the git commit HEAD was at when the build was
// last configured, CMake configuring again when HEAD moves ("0.1.0+abc123def456"; "+unknown"
// outside a git checkout). The ledger stores it with every run; the MPI executor refuses ranks
// that run another.

namespace gradem::cal {

/// The code version of this build.
const char* code_version();

}  // namespace gradem::cal
