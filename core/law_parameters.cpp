#include "core/law_parameters.hpp"

#include <sstream>

namespace gradem {
namespace {

std::string show(double v) {
    std::ostringstream out;
    out << v;
    return out.str();
}

}  // namespace

bool Range::contains(double v) const {
    if (!std::isfinite(v)) return false;
    if (lower_open ? !(v > lower) : !(v >= lower)) return false;
    if (upper_open ? !(v < upper) : !(v <= upper)) return false;
    return true;
}

std::string Range::rule() const {
    if (std::isinf(upper)) return std::string(lower_open ? "> " : ">= ") + show(lower);
    if (std::isinf(lower)) return std::string(upper_open ? "< " : "<= ") + show(upper);
    return std::string("in ") + (lower_open ? "(" : "[") + show(lower) + ", " + show(upper) + (upper_open ? ")" : "]");
}

}  // namespace gradem
