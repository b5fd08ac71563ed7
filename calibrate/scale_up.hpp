#pragma once
// Scales set on larger specimens ([scale_up] edge_mm, seeds; docs/calibration.md "Scales set on
// larger specimens"). Small cubes are cheap but not converged: a 3.5 mm cube of the coarser
// sand is softer and weaker than a large one, while its shape (strain at peak over σ/E, σc/σt)
// moves much less. So after a stage's fit on the calibration specimens:
//   1. its result runs once on every sand's scale-up specimens (and seed; the direct-tension
//      test too when tension is a target);
//   2. the closed-form rescaling of that evaluation (rescaling.hpp: moduli × α, strengths × β,
//      the log least-squares best against the same targets) gives the stage's result, and its
//      outputs on those specimens follow without a run (E × α, strengths × β, ε × β/α).
// The homogeneity that makes step 2 exact was checked on the fit's specimens (the scaling
// solver's step 2); the validation specimens, which must be unseen by both, measure the result.
#include <functional>
#include <string>
#include <vector>

#include "calibrate/rescaling.hpp"
#include "calibrate/validation.hpp"

namespace gradem::cal {

/// One stage's scale-up.
struct StageScaleUp {
    Evaluation measured;        ///< the fit's result run on the scale-up specimens
    Evaluation prediction;      ///< the same runs after the rescaling: the stage's result there
    Scales scales;              ///< α (moduli), β (strengths) applied
    std::vector<double> point;  ///< the rescaled parameters: the stage's result (empty: not done)
    int runs = 0, from_ledger = 0;
    StageCost cost;             ///< what its runs cost
    double noise_floor[kQuantityCount] = {0, 0, 0, 0};  ///< of `measured`: max relative SE of the seed mean (measure_noise)
    std::string note;           ///< why it was not done, if it was not
};

/// Steps 1-2 for `point` (the fit's result) and the stage's `sands`; `log` gets one line.
StageScaleUp scale_up_point(const CalibrationProblem& problem, const ValidatedModel& model, RunExecutor& executor, Ledger& ledger,
                            const std::vector<double>& point, const std::vector<std::size_t>& sands,
                            const std::function<void(const std::string&)>& log);

/// Max relative standard error of the seed mean over the evaluated sands, by quantity; NaN where
/// no sand has two seeds that ran it (one cube has no standard error, not a zero one).
void measure_noise(const Evaluation& e, double out[kQuantityCount]);

}  // namespace gradem::cal
