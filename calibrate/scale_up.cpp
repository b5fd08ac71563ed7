#include "calibrate/scale_up.hpp"

#include <cmath>
#include <sstream>

#include "common/number_format.hpp"

namespace gradem::cal {

void measure_noise(const Evaluation& e, double out[kQuantityCount]) {
    for (Quantity q : {Quantity::modulus, Quantity::peak, Quantity::strain, Quantity::tension}) {
        const int k = static_cast<int>(q);
        bool measured = false;  // a standard error needs two seeds of one sand
        for (const SandOutcome& s : e.sands)
            if (s.count(q) > 1 && std::isfinite(s.std[k]) && s.mean[k] != 0.0) {
                out[k] = std::max(measured ? out[k] : 0.0, std::fabs(s.std[k] / s.mean[k]) / std::sqrt(static_cast<double>(s.count(q))));
                measured = true;
            }
        if (!measured) out[k] = std::nan("");
    }
}

StageScaleUp scale_up_point(const CalibrationProblem& problem, const ValidatedModel& model, RunExecutor& executor, Ledger& ledger,
                            const std::vector<double>& point, const std::vector<std::size_t>& sands,
                            const std::function<void(const std::string&)>& log) {
    StageScaleUp up;
    if (point.empty()) {
        up.note = "not run: the fit has no result";
        return up;
    }
    // 1. The fit's result on the scale-up specimens.
    const CalibrationProblem on_set = scale_up_problem(problem);
    up.measured = evaluate_on_set(on_set, model, SpecimenSet::scale_up, executor, ledger, point, sands, "scale-up", up.runs,
                                  up.from_ledger, up.cost);
    if (up.measured.failed) {
        up.note = "not done: a scale-up run failed (" + up.measured.failure + "); the fit's result stands";
    } else {
        // 2. The closed-form rescaling there.
        measure_noise(up.measured, up.noise_floor);
        const ParameterSpace space(on_set.parameters, on_set.base.material);
        const Rescaling r = rescale(on_set, space, split_by_role(space), up.measured);
        up.scales = r.scales;
        up.point = r.point;
        up.prediction = r.prediction;
    }
    if (log) {
        std::ostringstream line;
        line << "scale-up on " << on_set.seeds.size() << (on_set.seeds.size() == 1 ? " seed" : " seeds") << ", edge "
             << common::format_significant(on_set.base.specimen.genesis.edge * 1e3, 4) << " mm: "
             << up.runs << " runs (" << up.from_ledger << " from the ledger)";
        if (up.point.empty()) line << "; " << up.note;
        else line << "; moduli x " << up.scales.alpha << ", strengths x " << up.scales.beta;
        log(line.str());
    }
    return up;
}

}  // namespace gradem::cal
