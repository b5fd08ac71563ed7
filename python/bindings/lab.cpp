// The lab side: what `gradem lab` computes (lab_data/lab_stats.hpp) as the document it writes
// (lab_results.json, made by the same writer), with each cube's stress-strain curve as numpy
// arrays beside it (the curves curves.csv thins for plots, here in full).
#include <pybind11/stl.h>

#include <filesystem>
#include <string>
#include <system_error>
#include <vector>

#include "lab_data/lab_stats.hpp"
#include "lab_data/sieve_table.hpp"
#include "python/bindings/common.hpp"
#include "reports/lab_report.hpp"

namespace gradem::py_api {

namespace {

namespace fs = std::filesystem;

bool is_dataset(const std::string& input) {
    std::error_code ec;
    return fs::is_directory(input, ec) || fs::path(input).extension() == ".toml";
}

/// The analysis `gradem lab` runs on its inputs: a dataset (folder or .toml), sieve analyses,
/// or load-frame exports (C109 cubes).
lab::LabStats analyse(const std::vector<std::string>& inputs) {
    if (inputs.empty()) throw py::value_error("lab.read: no input (a dataset folder or .toml, export files or sieve analyses)");
    if (is_dataset(inputs.front())) {
        if (inputs.size() > 1) throw py::value_error("lab.read: a dataset folder or .toml must be the only input");
        return lab::analyse_lab_dataset(inputs.front());
    }
    std::vector<fs::path> files(inputs.begin(), inputs.end());
    std::size_t sieves = 0;
    for (const fs::path& f : files) sieves += lab::is_sieve_csv_file(f) ? 1 : 0;
    if (sieves == files.size()) return lab::analyse_sieve_files(files, {});
    if (sieves > 0)
        throw py::value_error("lab.read: sieve analyses and load-frame exports given together: read them separately, or use a dataset");
    return lab::analyse_lab_files(files, lab::DatasetConfig{});
}

py::dict curve_dict(const lab::StressStrainCurve& c) {
    py::dict d;
    d["strain"] = to_array(c.strain);
    d["stress_mpa"] = column<double>(c.stress_pa, [](double v) { return v * 1e-6; });
    d["crosshead_strain"] = to_array(c.crosshead_strain);
    d["lateral_strain"] = to_array(c.lateral_strain);
    d["time_s"] = to_array(c.time_s);
    return d;
}

py::object read(const std::vector<std::string>& inputs) {
    LabWarnings warnings;
    lab::LabStats stats;
    {
        py::gil_scoped_release release;
        stats = analyse(inputs);
    }
    warnings.emit();
    py::object doc = json_to_python(report::lab_stats_to_json(stats));
    py::list cubes = doc["cubes"];
    for (std::size_t k = 0; k < stats.cubes.size() && k < cubes.size(); ++k) cubes[k]["curve"] = curve_dict(stats.cubes[k].curve);
    return doc;
}

}  // namespace

void register_lab(py::module_& m) {
    m.def("lab_read", &read, py::arg("inputs"),
          "Lab statistics of a dataset, sieve analyses or export files (gradem lab): lab_results.json with the curves");
}

}  // namespace gradem::py_api
