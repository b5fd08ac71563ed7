// Calibrations, studies, ledgers and the model function for external optimizers: what
// `gradem calibrate` and `gradem study` run (app/calibrate_command.cpp, app/study_command.cpp),
// with their documents (summary.json, study.json, written by the same writers) returned as
// Python objects, and the calibration's Evaluator (cube model, packing cache, run ledger) behind
// a function of the free parameters.
// The work runs on a thread of its own while the calling thread waits and checks for Ctrl-C
// (common.hpp, in_background): an interrupt stops after the runs in flight, which are recorded
// in the ledger, so the next call resumes without repeating them.
#include <pybind11/stl.h>

#include <atomic>
#include <climits>
#include <cmath>
#include <filesystem>
#include <memory>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include "calibrate/calibration.hpp"
#include "calibrate/evaluator.hpp"
#include "calibrate/execution/ledger.hpp"
#include "calibrate/objective.hpp"
#include "calibrate/problem.hpp"
#include "calibrate/study/study.hpp"
#include "calibrate/study/study_config.hpp"
#include "common/text_file.hpp"
#include "common/toml_section.hpp"
#include "python/bindings/common.hpp"
#include "reports/calibration_report.hpp"
#include "reports/html_report.hpp"
#include "reports/study_report.hpp"

namespace gradem::py_api {

namespace {

namespace fs = std::filesystem;

/// The command line's --out: the result folder, and the ledger with it unless it was set.
void apply_out(const std::string& out, fs::path& out_dir, fs::path& ledger) {
    if (out.empty()) return;
    const bool default_ledger = ledger == out_dir / "ledger.sqlite";
    out_dir = out;
    if (default_ledger) ledger = out_dir / "ledger.sqlite";
}

void check_count(const char* name, std::optional<int> v, int lo, int hi) {
    if (v && (*v < lo || *v > hi))
        throw py::value_error(std::string(name) + " = " + std::to_string(*v) + ": expected an integer in [" + std::to_string(lo) +
                              ", " + std::to_string(hi) + "]");
}

/// A milestone line: kept, passed to the Python `log` callable if any; stops on a cancel.
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
    d["best_objective"] = p.best_objective;
    d["workers"] = p.workers;
    return d;
}

std::function<void(const cal::Progress&)> progress_hook(const py::object& progress, const std::atomic<bool>& cancel) {
    const py::object* callback = progress.is_none() ? nullptr : &progress;
    return [callback, &cancel](const cal::Progress& p) {
        if (cancel) throw Interrupted();
        if (callback) call_python(*callback, [&] { return progress_dict(p); });
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
    std::atomic<bool> cancel = false;
    cal::CalibrationResult result;
    in_background(
        [&] {
            result = cal::run_calibration(problem, *model, log_hook(log, cancel), progress_hook(progress, cancel));
            cal::write_calibration_outputs(problem, result);
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

/// The quantity's name in the Python results: the names of macro.json and lab_results.json.
const char* quantity_name(cal::Quantity q) {
    switch (q) {
        case cal::Quantity::modulus: return "chord_modulus_mpa";
        case cal::Quantity::peak: return "peak_stress_mpa";
        case cal::Quantity::strain: return "strain_at_peak";
        case cal::Quantity::tension: return "tensile_strength_mpa";
    }
    return "";
}

double in_display_units(cal::Quantity q, double si) { return q == cal::Quantity::strain ? si : si * 1e-6; }

/// gradem.Model: a calibration problem's cube tests as a function of its free parameters.
class Model {
public:
    Model(const std::string& path, std::optional<int> workers, const std::string& ledger, const py::object& log) {
        check_count("workers", workers, 1, 64);
        LabWarnings warnings;
        problem_ = cal::load_calibration_problem(path);
        if (!ledger.empty()) problem_.ledger = ledger;
        if (workers) problem_.workers = *workers;
        problem_.solver.max_runs = INT_MAX / 2;  // no budget: each call runs what it is asked for
        model_ = cal::make_model(problem_);
        space_ = cal::ParameterSpace(problem_.parameters, problem_.base.material);
        warnings.emit();
        std::atomic<bool> cancel = false;
        in_background(
            [&] {
                ledger_ = std::make_unique<cal::Ledger>(problem_.ledger, cal::problem_fingerprint(problem_, *model_),
                                                        problem_.describe() + model_->fingerprint() + "\n");
                executor_ = std::make_unique<cal::ThreadExecutor>(*model_, problem_.workers);
                executor_->prepare(problem_.seeds, log_hook(log, cancel));
            },
            cancel);
        make_evaluator();
    }

    /// The free parameters' values (config units) of `params`, checked.
    std::vector<double> values_of(const py::dict& params) const {
        std::vector<double> values(space_.size(), std::nan(""));
        for (const auto& [k, v] : params) {
            const std::string name = py::str(k).cast<std::string>();
            const auto index = space_.index_of(name);
            if (!index) {
                const bool fixed = std::any_of(problem_.parameters.begin(), problem_.parameters.end(),
                                               [&](const cal::ParameterSpec& p) { return p.name == name; });
                throw py::value_error("parameter '" + name + "' " + (fixed ? "is fixed in " : "is not a parameter of ") +
                                      problem_.file.string() + " (free: " + free_names() + ")");
            }
            double x = 0.0;
            try {
                if (py::isinstance<py::str>(v)) throw py::cast_error();
                x = v.cast<double>();
            } catch (const py::cast_error&) {
                throw py::value_error("parameter '" + name + "' = " + py::repr(v).cast<std::string>() + ": expected a number");
            }
            const cal::ParameterSpec& p = space_.free(*index);
            if (!(x >= p.lower && x <= p.upper))
                throw py::value_error("parameter '" + name + "' = " + py::repr(v).cast<std::string>() + " violates in [" +
                                      common::toml_io::show(p.lower) + ", " + common::toml_io::show(p.upper) + "]" +
                                      (p.unit() == "-" ? std::string() : " " + std::string(p.unit())) + " (its bounds in " +
                                      problem_.file.string() + ")");
            values[*index] = x;
        }
        for (std::size_t k = 0; k < values.size(); ++k)
            if (std::isnan(values[k])) throw py::value_error("parameter '" + space_.free(k).name + "' missing (free: " + free_names() + ")");
        if (auto why = space_.material(values).invalid_reason()) throw py::value_error("the material of these parameters: " + *why);
        return values;
    }

    std::vector<cal::Evaluation> evaluate(const std::vector<std::vector<double>>& points, const py::object& progress) {
        std::vector<std::size_t> sands(problem_.sands.size());
        for (std::size_t s = 0; s < sands.size(); ++s) sands[s] = s;
        std::vector<cal::Evaluation> out;
        progress_ = progress.is_none() ? nullptr : &progress;
        try {
            in_background([&] { out = evaluator_->evaluate(points, sands, "python"); }, cancel_);
        } catch (...) {
            progress_ = nullptr;
            make_evaluator();  // a fresh one after an interrupt (the ledger keeps what ran)
            throw;
        }
        progress_ = nullptr;
        return out;
    }

    py::dict results(const cal::Evaluation& e) const {
        py::dict out;
        const std::size_t seeds = problem_.seeds.size();
        for (std::size_t s = 0; s < problem_.sands.size(); ++s) {
            py::dict sand;
            sand["seeds"] = problem_.seeds;
            std::vector<const cal::RunOutcome*> runs, tension;
            for (std::size_t k = 0; k < seeds; ++k) {
                runs.push_back(&e.runs.at(s * seeds + k));
                if (!e.tension_runs.empty()) tension.push_back(&e.tension_runs.at(s * seeds + k));
            }
            const auto values = [](const std::vector<const cal::RunOutcome*>& rs, cal::Quantity q) {
                return column<double>(rs, [q](const cal::RunOutcome* r) {
                    return r->ok() ? in_display_units(q, cal::outcome_value(*r, q)) : std::nan("");
                });
            };
            for (cal::Quantity q : cal::kQuantities) sand[quantity_name(q)] = values(runs, q);
            sand["poisson_ratio"] = column<double>(runs, [](const cal::RunOutcome* r) { return r->ok() ? r->poisson : std::nan(""); });
            if (!tension.empty()) sand[quantity_name(cal::Quantity::tension)] = values(tension, cal::Quantity::tension);
            py::list status;
            for (const cal::RunOutcome* r : runs) status.append(std::string(to_string(r->status)));
            for (const cal::RunOutcome* r : tension) status.append("tension " + std::string(to_string(r->status)));
            sand["status"] = status;
            sand["failure"] = e.sands.at(s).failure;
            out[py::str(problem_.sands[s])] = sand;
        }
        return out;
    }

    py::array_t<double> residuals(const cal::Evaluation& e) const { return to_array(cal::residuals(e, problem_)); }

    py::list parameters() const {
        py::list out;
        for (std::size_t k = 0; k < space_.size(); ++k) {
            const cal::ParameterSpec& p = space_.free(k);
            py::dict d;
            d["name"] = p.name;
            d["start"] = p.start;
            d["lower"] = p.lower;
            d["upper"] = p.upper;
            d["log_scale"] = p.log_scale;
            d["unit"] = p.unit();
            d["role"] = p.role() == cal::Role::stiffness_scale ? "stiffness scale"
                        : p.role() == cal::Role::strength_scale  ? "strength scale"
                                                                 : "shape";
            out.append(d);
        }
        return out;
    }

    py::dict targets() const {
        py::dict out;
        for (std::size_t s = 0; s < problem_.sands.size(); ++s) {
            py::dict sand;
            for (cal::Quantity q : problem_.fitted_quantities()) {
                const cal::TargetStat& t = cal::target_of(problem_.targets[s], q);
                py::dict d;
                d["mean"] = in_display_units(q, t.mean);
                d["std"] = in_display_units(q, t.std);
                d["n"] = t.n;
                sand[quantity_name(q)] = d;
            }
            out[py::str(problem_.sands[s])] = sand;
        }
        return out;
    }

    py::list residual_labels() const {
        py::list out;
        for (const std::string& sand : problem_.sands)
            for (cal::Quantity q : problem_.fitted_quantities()) out.append(py::make_tuple(sand, quantity_name(q)));
        return out;
    }

    [[nodiscard]] const cal::CalibrationProblem& problem() const { return problem_; }
    [[nodiscard]] const cal::Evaluator& evaluator() const { return *evaluator_; }

private:
    std::string free_names() const {
        std::string names;
        for (std::size_t k = 0; k < space_.size(); ++k) names += (k ? ", " : "") + space_.free(k).name;
        return names.empty() ? "none" : names;
    }

    void make_evaluator() {
        cancel_ = false;
        evaluator_ = std::make_unique<cal::Evaluator>(problem_, space_, *executor_, *ledger_, *model_, [this](const cal::Progress& p) {
            if (cancel_) throw Interrupted();
            if (progress_) call_python(*progress_, [&] { return progress_dict(p); });
        });
    }

    cal::CalibrationProblem problem_;
    std::unique_ptr<cal::CubeModel> model_;
    cal::ParameterSpace space_;
    std::unique_ptr<cal::Ledger> ledger_;
    std::unique_ptr<cal::ThreadExecutor> executor_;
    std::unique_ptr<cal::Evaluator> evaluator_;
    std::atomic<bool> cancel_ = false;
    const py::object* progress_ = nullptr;  ///< the running call's callback
};

}  // namespace

void register_calibration(py::module_& m) {
    m.def("calibrate", &calibrate, py::arg("problem"), py::arg("max_runs") = py::none(), py::arg("workers") = py::none(),
          py::arg("out") = "", py::arg("progress") = py::none(), py::arg("log") = py::none(), py::arg("report") = false,
          "A calibration (gradem calibrate): its outputs written, summary.json returned");
    m.def("study", &study, py::arg("study"), py::arg("workers") = py::none(), py::arg("out") = "", py::arg("log") = py::none(),
          py::arg("report") = false, "A parameter study (gradem study): its outputs written, study.json returned");
    m.def("read_ledger", &read_ledger, py::arg("path"), "A run ledger, read-only: {meta, runs}");
    py::class_<Model>(m, "Model")
        .def(py::init<const std::string&, std::optional<int>, const std::string&, const py::object&>(), py::arg("problem"),
             py::arg("workers") = py::none(), py::arg("ledger") = "", py::arg("log") = py::none())
        .def("evaluate",
             [](Model& self, const py::list& points, const py::object& progress) {
                 std::vector<std::vector<double>> values;
                 for (const py::handle& p : points) values.push_back(self.values_of(p.cast<py::dict>()));
                 const std::vector<cal::Evaluation> evaluations = self.evaluate(values, progress);
                 py::list out;
                 for (const cal::Evaluation& e : evaluations) {
                     py::dict d;
                     d["results"] = self.results(e);
                     d["residuals"] = self.residuals(e);
                     d["objective"] = cal::objective(e, self.problem());
                     d["failed"] = e.failed;
                     d["failure"] = e.failure;
                     out.append(d);
                 }
                 return out;
             },
             py::arg("points"), py::arg("progress") = py::none())
        .def_property_readonly("parameters", &Model::parameters)
        .def_property_readonly("targets", &Model::targets)
        .def_property_readonly("residual_labels", &Model::residual_labels)
        .def_property_readonly("sands", [](const Model& self) { return self.problem().sands; })
        .def_property_readonly("seeds", [](const Model& self) { return self.problem().seeds; })
        .def_property_readonly("ledger", [](const Model& self) { return self.problem().ledger.string(); })
        .def_property_readonly("problem", [](const Model& self) { return self.problem().file.string(); })
        .def_property_readonly("runs_executed", [](const Model& self) { return self.evaluator().runs_executed(); })
        .def_property_readonly("runs_from_ledger", [](const Model& self) { return self.evaluator().runs_from_ledger(); });
}

}  // namespace gradem::py_api
