#pragma once
// The code version: the project version and the git commit of the source tree when the build
// was made ("0.1.0+abc123def456"), with "-dirty.<8 hex digits of the diff's SHA-1>" when its
// tracked files had uncommitted changes, "+unknown" outside a git checkout
// (calibrate/execution/code_version.cmake, run at every build). The ledger and the summaries
// store it; the MPI executor refuses ranks that run another.

namespace gradem::cal {

/// The code version of this build.
const char* code_version();

}  // namespace gradem::cal
