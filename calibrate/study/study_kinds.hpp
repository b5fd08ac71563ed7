#pragma once
// Internals of `gradem study`: the runner that turns parameter points into StudyCases through
// the Evaluator and the study's ledger, and one function per study kind (study_kinds.cpp).
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "calibrate/execution/ledger.hpp"
#include "calibrate/study/study.hpp"

namespace gradem::cal {

class Ledger;
struct StudyExecution;

/// How a case runs besides its points: the test, and whose packing seeds.
struct CaseOptions {
    CubeTest test = CubeTest::compression;
    bool calibration_seeds = false;  ///< the problem's own seeds (the calibration's) instead of the study's
};

class StudyRunner {
public:
    /// `execution`: run on that executor (an MPI job's) instead of threads of this process.
    StudyRunner(const StudyConfig& config, std::function<void(const std::string&)> log, const StudyExecution* execution = nullptr);
    ~StudyRunner();
    /// Runs every point on every sand of `problem` and the study's seeds (one case per point).
    /// A tension case always runs on threads of this process (the MPI job's StudyModels hold
    /// the compression models of study_problems() only).
    std::vector<StudyCase> run(CalibrationProblem problem, const std::vector<std::vector<double>>& points,
                               const std::vector<std::string>& labels, const std::vector<double>& xs,
                               const CaseOptions& options = {});
    void say(const std::string& line) const;
    [[nodiscard]] int executed() const { return executed_; }
    [[nodiscard]] int from_ledger() const { return from_ledger_; }
    [[nodiscard]] int failed() const { return failed_; }

private:
    const StudyConfig& config_;
    std::function<void(const std::string&)> log_;
    std::unique_ptr<Ledger> ledger_;
    const StudyExecution* execution_;
    int executed_ = 0, from_ledger_ = 0, failed_ = 0;
};

enum class SweepKind { edge, min_diameter };

void run_gradation_effect(const CalibratedPoint& point, StudyRunner& runner, StudyResult& result);
/// The specimens of a resolution (edge) or fines_truncation (min_diameter) sweep, in the
/// config's order; InputError naming the study file for a value that gives a bad specimen.
std::vector<CalibrationProblem> sweep_problems(const CalibratedPoint& point, const StudyConfig& config, SweepKind kind);
void run_size_sweep(const CalibratedPoint& point, StudyRunner& runner, StudyResult& result, SweepKind kind);
void run_sensitivity(const CalibratedPoint& point, StudyRunner& runner, StudyResult& result);
/// model_form: the calibrations side by side; runs the direct-tension test of each at its
/// calibrated parameters (its sands and seeds) for σc/σt, and reads each one's ledger for the
/// cost per cube test.
void run_model_form(const std::vector<CalibratedPoint>& calibrations, StudyRunner& runner, StudyResult& result);

/// Cost per cube test of a calibration, per sand, from its ledger's successful runs.
struct RunCostSummary {
    int runs = 0;
    double mean_wall_seconds = 0.0;         ///< [s] per run
    double particle_steps_per_second = 0.0; ///< Σ particles·steps / Σ wall seconds [1/s]
};
RunCostSummary summarise_costs(const std::vector<RunCost>& runs, const std::string& sand);

/// σc/σt: the calibrated mean peak compressive stress over the mean tensile strength of the
/// successful tension runs (NaN when either is missing or not positive).
double compressive_to_tensile_ratio(double peak_compression_pa, const Sample& tensile_strength_pa);

/// resolution: per sand and quantity, the smallest edge beyond which the means change less
/// than the seed spread (study_analysis.cpp).
void summarise_convergence(StudyResult& result);
/// fines_truncation: cost and change of each cut against the finest case.
void summarise_truncation(StudyResult& result);

/// "12.3 ± 0.4" with `digits` significant digits; "-" for NaN.
std::string mean_pm(double mean, double std, int digits = 4);
std::string fmt_num(double v, int digits = 4);

}  // namespace gradem::cal
