// Fuzz builds leave Ceres out: the readers and reduce_curve() are fuzzed with fit_popovics =
// false, and this stub satisfies the link.
#include "lab_data/popovics.hpp"

namespace gradem::lab {

PopovicsFit fit_popovics(const StressStrainCurve&, std::size_t, double, double) {
    PopovicsFit fit;
    fit.message = "not fitted in fuzz builds";
    return fit;
}

}  // namespace gradem::lab
