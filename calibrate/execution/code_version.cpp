#include "calibrate/execution/code_version.hpp"

#ifndef GRADEM_CODE_VERSION
#define GRADEM_CODE_VERSION "unknown"
#endif

namespace gradem::cal {

const char* code_version() { return GRADEM_CODE_VERSION; }

}  // namespace gradem::cal
