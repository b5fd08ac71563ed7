#include "calibrate/rescaling.hpp"

namespace gradem::cal {

ScaleIndices split_by_role(const ParameterSpace& space) {
    ScaleIndices s;
    for (std::size_t k = 0; k < space.size(); ++k) {
        const Role r = space.free(k).role();
        (r == Role::stiffness_scale ? s.stiffness : r == Role::strength_scale ? s.strength : s.shape).push_back(k);
    }
    return s;
}

std::vector<double> apply_scales(const ParameterSpace& space, const ScaleIndices& idx, std::vector<double> x, Scales sc,
                                 Scales* applied) {
    Scales got;
    for (std::size_t k : idx.stiffness) {
        const double v = space.clamp(k, x[k] * sc.alpha);
        if (k == idx.stiffness.front()) got.alpha = v / x[k];
        x[k] = v;
    }
    for (std::size_t k : idx.strength) {
        const double v = space.clamp(k, x[k] * sc.beta);
        if (k == idx.strength.front()) got.beta = v / x[k];
        x[k] = v;
    }
    if (applied) *applied = got;
    return x;
}

Rescaling rescale(const CalibrationProblem& problem, const ParameterSpace& space, const ScaleIndices& idx, const Evaluation& e) {
    Rescaling r;
    const Scales want = best_scales(e, problem, !idx.stiffness.empty(), !idx.strength.empty());
    r.point = apply_scales(space, idx, e.values, want, &r.scales);
    r.prediction = rescaled(e, r.scales.alpha, r.scales.beta);
    r.predicted = objective(r.prediction, problem);
    return r;
}

}  // namespace gradem::cal
