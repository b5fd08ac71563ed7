#pragma once
// Internals of `gradem study`: the runner that turns parameter points into StudyCases through
// the Evaluator and the study's ledger, and one function per study kind (study_kinds.cpp).
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "calibrate/study.hpp"

namespace gradem::cal {

class Ledger;
struct StudyExecution;

class StudyRunner {
public:
    /// `execution`: run on that executor (an MPI job's) instead of threads of this process.
    StudyRunner(const StudyConfig& config, std::function<void(const std::string&)> log, const StudyExecution* execution = nullptr);
    ~StudyRunner();
    /// Runs every point on every sand of `problem` and the study's seeds (one case per point).
    std::vector<StudyCase> run(CalibrationProblem problem, const std::vector<std::vector<double>>& points,
                               const std::vector<std::string>& labels, const std::vector<double>& xs);
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
void run_model_form(const StudyConfig& config, StudyResult& result);

/// resolution: per sand and quantity, the smallest edge beyond which the means change less
/// than the seed spread (study_analysis.cpp).
void summarise_convergence(StudyResult& result);
/// fines_truncation: cost and change of each cut against the finest case.
void summarise_truncation(StudyResult& result);

/// "12.3 ± 0.4" with `digits` significant digits; "-" for NaN.
std::string mean_pm(double mean, double std, int digits = 4);
std::string fmt_num(double v, int digits = 4);

}  // namespace gradem::cal
