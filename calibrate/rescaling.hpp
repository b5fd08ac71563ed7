#pragma once
// The closed-form rescaling of a calibration point (docs/calibration.md "Homogeneity"): every
// stiffness parameter × α and every strength parameter × β moves E × α, the strengths × β and
// the strain at peak × β/α (objective.hpp), so one evaluation gives the best α, β against the
// targets and the outputs they will give, without a run. The scaling solver uses it between its
// steps; the scale-up stage uses it to set the scales on larger specimens.
#include <cstddef>
#include <vector>

#include "calibrate/evaluator.hpp"
#include "calibrate/objective.hpp"
#include "calibrate/parameters.hpp"
#include "calibrate/problem.hpp"

namespace gradem::cal {

/// The free parameters by homogeneity role (indices into the free parameters).
struct ScaleIndices {
    std::vector<std::size_t> stiffness, strength, shape;
};
ScaleIndices split_by_role(const ParameterSpace& space);

/// x with the stiffness parameters × α and strength parameters × β, clamped to their bounds;
/// `applied` receives the α, β that survived the clamping (of the first parameter of each kind).
std::vector<double> apply_scales(const ParameterSpace& space, const ScaleIndices& idx, std::vector<double> x, Scales sc,
                                 Scales* applied);

/// One evaluation's best closed-form rescaling, and what it predicts.
struct Rescaling {
    Scales scales;              ///< applied (after clamping)
    std::vector<double> point;  ///< rescaled parameters
    double predicted = 0.0;     ///< predicted objective
    Evaluation prediction;      ///< the evaluation's outputs at `scales`
};
Rescaling rescale(const CalibrationProblem& problem, const ParameterSpace& space, const ScaleIndices& idx, const Evaluation& e);

}  // namespace gradem::cal
