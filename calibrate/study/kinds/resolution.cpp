// The resolution study: how do the results change with the cube edge? The calibrated
// parameters on cubes of every edge of study.edges_mm, every sand and seed; the size beyond
// which the properties change less than their seed spread, or than study.tolerance
// (docs/calibration.md "Studies").
#include <algorithm>
#include <cmath>

#include "calibrate/study/size_sweep.hpp"
#include "calibrate/study/study_keys.hpp"
#include "calibrate/study/study_runner.hpp"
#include "calibrate/study/study_tables.hpp"

namespace gradem::cal {
namespace {

void read_keys(StudyKeys& keys) {
    StudyConfig& c = keys.config;
    read_swept_sands(keys);
    const auto edges = study_keys::read_list<double>(keys.section, "edges_mm", "a non-empty array of positive numbers [mm]",
                                                     study_keys::positive_number);
    keys.section.real("tolerance", c.tolerance);
    if (edges.size() < 2) study_keys::refuse(keys, "edges_mm", "key 'study.edges_mm' needs at least two cube edges [mm]");
    c.sweep_mm = edges;
    if (!(c.tolerance >= 0.0 && c.tolerance < 1.0))
        study_keys::refuse(keys, "tolerance", "key 'study.tolerance' must be a relative change in [0, 1)");
}

std::vector<CalibrationProblem> problems(const CalibratedPoint& point, const StudyConfig& config) {
    return sweep_problems(point, config, SweepKind::edge);
}

void run(const std::vector<CalibratedPoint>& calibrations, StudyRunner& runner, StudyResult& result) {
    run_size_sweep(calibrations.front(), runner, result, SweepKind::edge);
    summarise_convergence(result);
}

}  // namespace

const StudyKindSpec resolution_study = {
    .keys = {"sands", "edges_mm", "tolerance"},
    .read_keys = read_keys,
    .one_calibration = true,
    .problems = problems,
    .run = run,
};

}  // namespace gradem::cal
