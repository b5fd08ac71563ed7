// Calibrations, studies and ledgers: what `gradem calibrate` and `gradem study` run
// (app/calibrate_command.cpp, app/study_command.cpp), with their documents (summary.json,
// study.json, written by the same writers) returned as Python objects; and a ledger read as
// records. (gradem.Model, the function of the free parameters: model.cpp.)
// The work runs on a thread of its own while the calling thread waits and checks for Ctrl-C
// (common.hpp, in_background): an interrupt stops after the runs in flight, which are recorded
// in the ledger, so the next call resumes without repeating them.
#include <pybind11/stl.h>

#include <atomic>
#include <filesystem>
#include <memory>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include "calibrate/calibration.hpp"
#include "calibrate/execution/ledger.hpp"
#include "calibrate/plan.hpp"
#include "calibrate/problem.hpp"
#include "calibrate/study/study.hpp"
#include "calibrate/study/study_config.hpp"
#include "common/text_file.hpp"
#include "python/bindings/calibration_hooks.hpp"
#include "python/bindings/common.hpp"
#include "reports/calibration_report.hpp"
#include "reports/html_report.hpp"
#include "reports/study_report.hpp"

namespace gradem::py_api {

void check_count(const char* name, std::optional<int> v, int lo, int hi) {
    if (v && (*v < lo || *v > hi))
        throw py::value_error(std::string(name) + " = " + std::to_string(*v) + ": expected an integer in [" + std::to_string(lo) +
                              ", " + std::to_string(hi) + "]");
}

std::function<void(const std::string&)> log_hook(const py::object& log, const std::atomic<bool>& cancel) {
    const py::object* callback = log.is_none() ? nullptr : &log;
    return [callback, &cancel](const std::string& line) {
        if (cancel) throw Interrupted();
        if (callback) call_python(*callback, [&] { return py::str(line); });
    };
}

py::dict progress_dict(const cal::Progress& p) {
    py::dict d;
    d["runs_used"] = p.runs_used;
    d["max_runs"] = p.max_runs;
    d["from_ledger"] = p.from_ledger;
    d["evaluations"] = p.evaluations;
    d["elapsed_s"] = p.elapsed_s;
    d["mean_run_s"] = p.mean_run_s;
    d["sand_mean_run_s"] = p.sand_mean_run_s;  // per sand of the problem, in its order (0: no run yet)
    d["best_objective"] = p.best_objective;
    d["workers"] = p.workers;
    return d;
}

namespace {

namespace fs = std::filesystem;

/// The command line's --out: the result folder, and the ledger with it unless it was set.
void apply_out(const std::string& out, fs::path& out_dir, fs::path& ledger) {
    if (out.empty()) return;
    const bool default_ledger = ledger == out_dir / "ledger.sqlite";
    out_dir = out;
    if (default_ledger) ledger = out_dir / "ledger.sqlite";
}

/// The progress callback of a whole calibration: the dict, with the command line's ETA of the
/// runs still expected (`eta_s`) and its upper bound from the budget (`eta_max_s`), NaN while
/// no run has been timed (calibrate/plan.hpp eta_seconds).
std::function<void(const cal::Progress&)> progress_hook(const py::object& progress, const std::atomic<bool>& cancel,
                                                         const cal::ExpectedRuns& expected) {
    const py::object* callback = progress.is_none() ? nullptr : &progress;
    return [callback, &cancel, &expected](const cal::Progress& p) {
        if (cancel) throw Interrupted();
        if (!callback) return;
        call_python(*callback, [&] {
            py::dict d = progress_dict(p);
            d["eta_s"] = cal::eta_seconds(p, expected);
            d["eta_max_s"] = cal::eta_seconds(p, expected, true);
            return d;
        });
    };
}

/// report.html of a command's folder (as the command ends); a missing matplotlib is a warning.
void html_report(report::ReportKind kind, const fs::path& out_dir) {
    std::ostringstream announce, warn;
    report::write_html_report_or_warn(kind, out_dir, announce, warn);
    if (!warn.str().empty()) py::module_::import("warnings").attr("warn")(warn.str());
}

py::object calibrate(const std::string& path, std::optional<int> max_runs, std::optional<int> workers, const std::string& out,
                     const py::object& progress, const py::object& log, bool report) {
    check_count("max_runs", max_runs, 1, 100000);
    check_count("workers", workers, 1, 64);
    LabWarnings warnings;
    cal::CalibrationProblem problem = cal::load_calibration_problem(path);
    apply_out(out, problem.out_dir, problem.ledger);
    if (max_runs) problem.solver.max_runs = *max_runs;
    if (workers) problem.workers = *workers;
    std::unique_ptr<cal::CubeModel> model = cal::make_model(problem);
    warnings.emit();
    const cal::ExpectedRuns expected = progress.is_none() ? cal::ExpectedRuns{} : cal::expected_runs(problem);
    std::atomic<bool> cancel = false;
    cal::CalibrationResult result;
    in_background(
        [&] {
            result = cal::run_calibration(problem, *model, log_hook(log, cancel), progress_hook(progress, cancel, expected));
            report::write_calibration_outputs(problem, result);
        },
        cancel);
    if (report) html_report(report::ReportKind::calibrate, problem.out_dir);
    return json_to_python(common::read_file_bytes(problem.out_dir / "summary.json"));
}

py::object study(const std::string& path, std::optional<int> workers, const std::string& out, const py::object& log, bool report) {
    check_count("workers", workers, 1, 64);
    LabWarnings warnings;
    cal::StudyConfig config = cal::load_study_config(path);
    apply_out(out, config.out_dir, config.ledger);
    if (workers) config.workers = *workers;
    std::atomic<bool> cancel = false;
    in_background(
        [&] {
            const cal::StudyResult result = cal::run_study(config, log_hook(log, cancel));
            report::write_study_outputs(result);
        },
        cancel);
    warnings.emit();
    if (report) html_report(report::ReportKind::study, config.out_dir);
    return json_to_python(common::read_file_bytes(config.out_dir / "study.json"));
}

py::dict run_dict(const cal::RunOutcome& o) {
    py::dict d;
    d["status"] = std::string(to_string(o.status));
    d["reason"] = o.reason;
    d["modulus_pa"] = o.modulus_pa;
    d["peak_pa"] = o.peak_pa;
    d["strain_at_peak"] = o.strain_at_peak;
    d["poisson"] = o.poisson;
    d["particles"] = o.particles;
    d["bonds"] = o.bonds;
    d["steps"] = o.steps;
    d["wall_seconds"] = o.wall_seconds;
    d["curve_strain"] = to_array(o.curve_strain);
    d["curve_stress_pa"] = to_array(o.curve_stress_pa);
    return d;
}

py::dict read_ledger(const std::string& path) {
    cal::LedgerContents contents;
    {
        py::gil_scoped_release release;
        contents = cal::read_ledger(path);
    }
    py::dict meta;
    for (const auto& [k, v] : contents.meta) meta[py::str(k)] = v;
    py::list runs;
    for (const cal::LedgerRun& r : contents.runs) {
        py::dict d;
        d["run_key"] = r.run_key;
        d["sequence"] = r.sequence;
        d["sand"] = r.sand;
        d["seed"] = r.seed;
        d["parameters"] = r.parameters.empty() ? py::object(py::dict()) : json_to_python(r.parameters);
        d["material"] = r.material;
        for (auto item : run_dict(r.outcome)) d[item.first] = item.second;
        d["code_version"] = r.code_version;
        d["finished_utc"] = r.finished_utc;
        d["rank"] = r.rank >= 0 ? py::object(py::int_(r.rank)) : py::object(py::none());
        d["host"] = r.host;
        runs.append(d);
    }
    py::dict out;
    out["meta"] = meta;
    out["runs"] = runs;
    return out;
}

}  // namespace

void register_calibration(py::module_& m) {
    m.def("calibrate", &calibrate, py::arg("problem"), py::arg("max_runs") = py::none(), py::arg("workers") = py::none(),
          py::arg("out") = "", py::arg("progress") = py::none(), py::arg("log") = py::none(), py::arg("report") = false,
          "A calibration (gradem calibrate): its outputs written, summary.json returned");
    m.def("study", &study, py::arg("study"), py::arg("workers") = py::none(), py::arg("out") = "", py::arg("log") = py::none(),
          py::arg("report") = false, "A parameter study (gradem study): its outputs written, study.json returned");
    m.def("read_ledger", &read_ledger, py::arg("path"), "A run ledger, read-only: {meta, runs}");
}

}  // namespace gradem::py_api
