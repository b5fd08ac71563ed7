#pragma once
// What the calibration bindings share (calibration.cpp: calibrate, study; model.cpp: Model):
// the checks of their counts, and the hooks that pass milestones and progress to Python
// callables and stop the work when the calling thread saw Ctrl-C (common.hpp, in_background).
#include <pybind11/pybind11.h>

#include <atomic>
#include <functional>
#include <optional>
#include <string>

#include "calibrate/evaluator.hpp"

namespace gradem::py_api {

/// A count argument (max_runs, workers) outside [lo, hi] is a ValueError naming it.
void check_count(const char* name, std::optional<int> v, int lo, int hi);

/// A milestone line: passed to the Python `log` callable if any; throws Interrupted once
/// `cancel` is set.
std::function<void(const std::string&)> log_hook(const pybind11::object& log, const std::atomic<bool>& cancel);

/// A calibration's progress as the dict progress callbacks get.
pybind11::dict progress_dict(const cal::Progress& p);

}  // namespace gradem::py_api
