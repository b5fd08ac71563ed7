// gradem._gradem.Model: a calibration problem's Evaluator (cube model, packing cache, run
// ledger) behind a function of its free parameters, for external optimizers. The runs go to
// the problem's worker threads on a thread of their own while the calling thread waits and
// checks for Ctrl-C (common.hpp, in_background): an interrupt stops after the runs in flight,
// which are recorded in the ledger.
#include <pybind11/stl.h>

#include <algorithm>
#include <atomic>
#include <climits>
#include <cmath>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "calibrate/calibration.hpp"
#include "calibrate/evaluator.hpp"
#include "calibrate/execution/ledger.hpp"
#include "calibrate/objective.hpp"
#include "calibrate/problem.hpp"
#include "common/toml_section.hpp"
#include "python/bindings/calibration_hooks.hpp"
#include "python/bindings/common.hpp"

namespace gradem::py_api {

namespace {

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
                executor_->prepare(problem_.packing_seeds(), log_hook(log, cancel));
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
        std::size_t first = 0, first_tension = 0;  // the sand's first runs: runs are by sand, then seed
        for (std::size_t s = 0; s < problem_.sands.size(); ++s) {
            py::dict sand;
            const std::vector<std::uint64_t>& seeds = problem_.seeds_of(s);
            sand["seeds"] = seeds;
            std::vector<const cal::RunOutcome*> runs, tension;
            for (std::size_t k = 0; k < seeds.size(); ++k) {
                runs.push_back(&e.runs.at(first + k));
                if (!e.tension_runs.empty() && problem_.runs_tension_on(seeds[k])) tension.push_back(&e.tension_runs.at(first_tension++));
            }
            first += seeds.size();
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

void register_model(py::module_& m) {
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
