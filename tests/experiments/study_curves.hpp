#pragma once
// The study's sieve analyses (its Table 2), typed in for the experiments tests only; the
// program itself reads them from lab_data/datasets.
#include "lab_data/gradation.hpp"

namespace gradem::test {

inline lab::GradationCurve pre_blended_curve() {
    return lab::GradationCurve::from_points({4.75e-3, 2.36e-3, 1.18e-3, 0.595e-3, 0.4e-3, 0.3e-3, 0.149e-3, 0.075e-3},
                                            {1.0, 0.996, 0.981, 0.919, 0.832, 0.699, 0.256, 0.0});
}

inline lab::GradationCurve van_buren_curve() {
    return lab::GradationCurve::from_points({4.75e-3, 2.36e-3, 1.18e-3, 0.595e-3, 0.4e-3, 0.3e-3, 0.149e-3, 0.075e-3},
                                            {1.0, 0.998, 0.955, 0.825, 0.519, 0.144, 0.006, 0.0});
}

}  // namespace gradem::test
