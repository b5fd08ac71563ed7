#include "calibrate/execution/code_version.hpp"

#include "code_version_string.hpp"  // generated at build time: GRADEM_CODE_VERSION

namespace gradem::cal {

const char* code_version() { return GRADEM_CODE_VERSION; }

}  // namespace gradem::cal
