#pragma once
// The cost of a calibration before it runs (`gradem calibrate --plan`, docs/calibration.md
// "The cost before the run"):
//   1. runs: the solver's path on the analytic stand-in (the same problem, solver, budget and
//      validation, in-memory ledger: about a second) gives the number of evaluations and
//      distinct runs; the budget is their upper bound;
//   2. specimens: each packing from the cache, or, when genesis has not run yet, the number of
//      grains genesis would sample (and genesis' step budget as its cost bound); where none of
//      a sand's packings of a set is cached, its first seed's is made (and cached: the run
//      reads it) for the timing;
//   3. engine timing: a cached packing of each sand and specimen set bonded with the start
//      material and cycled for a few seconds on one thread (what a worker runs): seconds per
//      particle-step (the median 100-step batch), the time step and the settling steps;
//   4. steps per run: settling + the platen travel to the end strain at the test's rate over
//      the time step. Compression ends at the law's PlatenTestCost::compression_end_over_elastic
//      × σ_lab/E_lab (core/law_parameters.hpp), or, for a law without that row, at
//      kEndOverPeakStrain × the lab's strain at peak; direct tension at
//      the law's PlatenTestCost::tension_end_over_expected × its expected peak strain;
//   5. wall time: Σ particle-steps × seconds per particle-step over min(workers, cores); the
//      genesis still to run at the pace of the packings made in step 2 (or bounded by its step
//      budget where the plan made none).
#include <cstdint>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "calibrate/evaluator.hpp"
#include "calibrate/problem.hpp"

namespace gradem::cal {

/// End of a compression run (stress down to stop_fraction × peak) over the expected gauge
/// strain at peak [-], for a law without a PlatenTestCost row: the platen strain exceeds the
/// gauge's before the peak, and the test runs on past it. Measured on parallel-bond
/// calibrations of 2.5 mm cubes (docs/calibration.md).
inline constexpr double kEndOverPeakStrain = 1.45;

/// One packing a calibration needs.
struct SpecimenPlan {
    std::string sand, set;           ///< set: "fit", "scale-up" or "validation"
    std::uint64_t seed = 1;
    std::int64_t particles = 0;      ///< the cached packing's, or genesis' sampled count
    bool cached = false;             ///< false: genesis runs first
    std::int64_t genesis_max_steps = 0;  ///< genesis' step budget (0 when cached)
    double genesis_s = 0.0;          ///< > 0: made by the plan for its engine timing, genesis' wall time [s]
    std::uint64_t packing_key = 0;   ///< exp::packing_key of the specimen (the same packing planned twice is made once)
};

/// The cost of one run of a sand on a specimen set, from the engine timing.
struct RunCostPlan {
    std::string sand, set;
    double particles = 0.0;              ///< mean over the set's seeds
    double time_step_s = 0.0;            ///< [s]
    double seconds_per_particle_step = 0.0;  ///< one thread, the bonded specimen at rest (the probe)
    double compression_cost_factor = 1.0;    ///< a compression run's mean cost per particle-step over the probe's (the law's PlatenTestCost before and after the peak)
    double tension_cost_factor = 1.0;        ///< a direct-tension test's
    double settle_steps = 0.0;
    double compression_steps = 0.0;      ///< settling + loading
    double tension_steps = 0.0;          ///< 0 when no tension test runs
    int compression_runs = 0, tension_runs = 0;  ///< of this sand and set in the plan
    [[nodiscard]] double seconds() const;  ///< of all its runs, one thread
};

/// What every plan prices (a calibration's, calibrate/study/study_plan.hpp's): its packings, its
/// runs and their cost on min(workers, cores) concurrent runs, and what it assumed.
struct PlanCost {
    int workers = 1, cores = 1;
    std::vector<SpecimenPlan> specimens;
    std::vector<RunCostPlan> runs;
    double run_particle_steps = 0.0;     ///< Σ over the planned runs
    double run_wall_s = 0.0;             ///< estimated wall time of the runs [s]
    /// The genesis still to run [s]: of the sets the plan made a packing of, at the pace it made it
    /// (its seconds per grain, on every core); of the others, an upper bound (genesis' step
    /// budget at the probe's cost per particle-step, over min(workers, cores)).
    double genesis_wall_s = 0.0;
    double genesis_wall_max_s = 0.0;
    std::vector<std::string> assumptions;
};

struct CalibrationPlan : PlanCost {
    int budget = 0;                      ///< solver.max_runs
    int expected_runs = 0;               ///< fitted runs on the stand-in's path (≤ budget)
    int expected_evaluations = 0;
    int scale_up_runs = 0;               ///< apart from the budget
    int validation_runs = 0;             ///< apart from the budget
    bool tension = false;                ///< the problem has a tension target
    bool tension_at_result = false;      ///< its tension tests run at the result only (else with every compression run)
};

/// Distinct fitted runs and validation runs of the problem's solver path on the analytic
/// stand-in (no DEM run; an in-memory ledger): {expected fitted runs, evaluations, validation
/// runs, scale-up runs}.
struct ExpectedRuns {
    int fitted = 0, evaluations = 0, validation = 0, scale_up = 0;
    /// A validation run's grains over a fitted run's of the same sand: the same gradation fills
    /// both cubes, (validation edge / fitted edge)³ [-].
    double validation_grains_ratio = 1.0;
    /// Its steps over a fitted run's: at the automatic rate, which gives the platens a fixed number
    /// of wave transits over the cube's height to the expected peak, the edge ratio; else 1 [-].
    double validation_steps_ratio = 1.0;
    /// A validation run's cost over a fitted run's of the same sand: grains × steps [-].
    double validation_run_weight = 1.0;
    /// A scale-up run's, the same way [-].
    double scale_up_run_weight = 1.0;
    /// Each sand's share of the path's runs (its seeds, and its tension seeds with a tension
    /// target, over every sand's) and of the scale-up and validation runs (alike for every sand) [-].
    std::vector<double> fitted_share, validation_share;
};
ExpectedRuns expected_runs(const CalibrationProblem& problem);

/// A run on cubes of edge `edge` [m] over a run of the same sand on the problem's fitted cubes:
/// (edge ratio)³ the grains, × the edge ratio the steps at the automatic rate (a fixed number of
/// wave transits), else × 1 [-]; edge 0: the fitted edge (1).
double run_weight_at_edge(const CalibrationProblem& problem, double edge);

/// The progress line's ETA [s]: the runs still expected on the solver's path (`upper`: the
/// budget's remaining runs instead), then the scale-up and validation runs at their weights,
/// each sand's share at that sand's mean run time so far (the mean of every run for a sand not
/// yet timed), `workers` at a time. NaN while no run has been timed (all from the ledger).
double eta_seconds(const Progress& p, const ExpectedRuns& e, bool upper = false);

/// The plan of `problem` (steps 1-5 above). Throws what the run would throw for bad input.
CalibrationPlan plan_calibration(const CalibrationProblem& problem, double probe_seconds = 2.0);

/// A set of packings the runs go to: the fit's (problem.base, problem.seeds), the scale-up's, the
/// validation's, or a study case's.
struct PlannedSpecimens {
    std::string name;
    exp::CubeConfig base;
    PackingSeeds seeds;
};

/// How many runs of each test a sand makes on a set (each on every seed in turn).
struct RunCounts {
    int compression = 0, tension = 0;
};

/// Steps 2-4 above for sand `s` of `problem` on `set` at `material`: the set's packings (cached
/// or to be made, appended to `specimens`) and the cost of `counts` runs, from `probe_seconds` of
/// engine timing on the first cached packing (the first seed's, made now, when none is cached).
RunCostPlan plan_runs(const CalibrationProblem& problem, const PlannedSpecimens& set, std::size_t s,
                      const exp::MaterialParams& material, RunCounts counts, double probe_seconds,
                      std::vector<SpecimenPlan>& specimens);

/// Step 5: Σ particle-steps and the wall time of the cost's runs over min(workers, cores)
/// concurrent runs, and the upper bound of the genesis still to run for its specimens (each
/// distinct packing once).
void add_totals(PlanCost& cost);

/// What every plan assumes of its runs' length and cost (the law's PlatenTestCost), for its
/// assumption lines.
std::string test_cost_assumption(BondModel model);

/// The specimen, run, wall-time and assumption lines of a plan, for people; the same as keys of
/// `j` (workers, cores, particle_steps, wall_s, genesis_wall_s, genesis_wall_max_s, specimens, runs,
/// assumptions), for programs.
std::string cost_text(const PlanCost& cost);
void add_cost_json(nlohmann::ordered_json& j, const PlanCost& cost);

/// For people (stdout of --plan) and for programs (--json).
std::string plan_text(const CalibrationPlan& plan);
std::string plan_json(const CalibrationPlan& plan);

}  // namespace gradem::cal
