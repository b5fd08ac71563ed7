#pragma once
// The runner of a study's cases: parameter points run on every sand of a problem and the
// study's packing seeds through the Evaluator and the study's ledger (study.cpp), on threads of
// this process or on a shared executor (study_models.hpp).
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

/// A case as a kind asked for it, recorded by a planning runner: the problem its runs go to
/// (after as_study_problem: the study's seeds and sands), its parameter points and its test.
struct PlannedCase {
    CalibrationProblem problem;
    std::vector<std::vector<double>> points;
    std::string label;
    CubeTest test = CubeTest::compression;
};

class StudyRunner {
public:
    /// A planning runner (`gradem study --plan`, study_plan.hpp): records every case in `planned`
    /// and answers it on the analytic stand-in with an in-memory ledger, so the kind's analysis
    /// runs through and asks for its later cases; nothing is written.
    StudyRunner(const StudyConfig& config, std::vector<PlannedCase>& planned);
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
    std::vector<PlannedCase>* planned_ = nullptr;
    int executed_ = 0, from_ledger_ = 0, failed_ = 0;
};

}  // namespace gradem::cal
