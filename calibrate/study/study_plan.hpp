#pragma once
// The cost of a study before it runs (`gradem study --plan`, docs/calibration.md "The cost
// before the run"):
//   1. cases: the kind runs on a planning StudyRunner (study_runner.hpp) that records every case
//      it asks for and answers it on the analytic stand-in, so a kind whose later cases depend on
//      earlier answers asks for them too (about a second, nothing written);
//   2. per case and sand: its packings and the cost of its runs at the case's first point, from
//      a second of engine timing, as a calibration's plan prices its runs (calibrate/plan.hpp,
//      steps 2-4);
//   3. wall time: Σ particle-steps × seconds per particle-step over min(workers, cores).
// Runs already in the study's ledger are served from it when the study runs: the plan counts them
// as runs (it opens no ledger).
#include <string>
#include <vector>

#include "calibrate/plan.hpp"
#include "calibrate/study/study_config.hpp"

namespace gradem::cal {

/// Its specimens' set is the case's label; one RunCostPlan per case (of one or more points) and sand.
struct StudyPlan : PlanCost {
    std::string kind;
    int cases = 0;                       ///< the cases the kind asked for (a point on a specimen set)
    int compression_runs = 0, tension_runs = 0;
};

/// The plan of the study (steps 1-3). Throws what the study would throw for bad input
/// (InputError naming the file, line and key) before any genesis.
StudyPlan plan_study(const StudyConfig& config, double probe_seconds = 1.0);

/// For people (stdout of --plan) and for programs (--json).
std::string study_plan_text(const StudyPlan& plan);
std::string study_plan_json(const StudyPlan& plan);

}  // namespace gradem::cal
