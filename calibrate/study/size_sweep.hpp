#pragma once
// What the sweeps over a specimen size share (the cube edge, the smallest kept grain): the
// swept specimens, their cases, the `sands` key that picks the sands swept, and where the means
// stop changing along the sweep.
#include "calibrate/study/study.hpp"
#include "calibrate/study/study_runner.hpp"

namespace gradem::cal {

enum class SweepKind { edge, min_diameter };

/// The study.sands key: a subset of the calibration's sands to sweep (checked against the
/// calibration when the study runs, as_study_problem).
void read_swept_sands(StudyKeys& keys);

/// The specimens of the sweep, in the config's order (study.sweep_mm); InputError naming the
/// study file for a value that gives a bad specimen.
std::vector<CalibrationProblem> sweep_problems(const CalibratedPoint& point, const StudyConfig& config, SweepKind kind);

/// Runs the calibrated parameters on every swept specimen (one case each, in increasing size)
/// and fills the table of macro properties per case and result.data's `x_name` and `cases`.
void run_size_sweep(const CalibratedPoint& point, StudyRunner& runner, StudyResult& result, SweepKind kind);

/// Per sand and quantity, the smallest swept size beyond which the means change less than the
/// seed spread (or than study.tolerance × the mean): a table, result.data["convergence"] and a
/// verdict per sand and property.
void summarise_convergence(StudyResult& result);

}  // namespace gradem::cal
