#pragma once
// The result files of a `gradem study` (reports/study_report.cpp).
#include "calibrate/study/study.hpp"

namespace gradem::report {

/// study.json, study.md and runs.csv in config.out_dir, each written atomically.
void write_study_outputs(const cal::StudyResult& result);

}  // namespace gradem::report
