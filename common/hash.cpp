#include "common/hash.hpp"

#include <cstdio>

namespace gradem::common {

std::string hex16(std::uint64_t v) {
    char buf[17];
    std::snprintf(buf, sizeof buf, "%016llx", static_cast<unsigned long long>(v));
    return buf;
}

}  // namespace gradem::common
