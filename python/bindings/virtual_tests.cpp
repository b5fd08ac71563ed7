// The specimen and the virtual tests of a config: what `gradem specimen`, `gradem compress` and
// `gradem tension` run (app/*_command.cpp), with the results as Python objects instead of
// printed summaries: the macro document (macro.json's own text, made by the same writer), the
// curve and the crack log as numpy arrays, and the run's provenance. The GIL is released while
// genesis and the test run; the test loop's progress hook checks for Ctrl-C (common.hpp).
#include <pybind11/stl.h>

#include <chrono>
#include <ctime>
#include <filesystem>
#include <optional>
#include <string>

#include "calibrate/execution/code_version.hpp"
#include "calibrate/execution/run_executor.hpp"
#include "common/input_error.hpp"
#include "experiments/config/cube_config.hpp"
#include "experiments/paste/paste_cache.hpp"
#include "experiments/specimen/genesis.hpp"
#include "experiments/specimen/packing_cache.hpp"
#include "experiments/virtual_tests/cube_test.hpp"
#include "experiments/virtual_tests/tension_test.hpp"
#include "python/bindings/common.hpp"
#include "python/bindings/config.hpp"
#include "reports/cube_output.hpp"
#include "reports/tension_output.hpp"

namespace gradem::py_api {

namespace {

namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;

constexpr double kMpa = 1.0e-6;

std::string utc_now() {
    const std::time_t t = std::time(nullptr);
    char buf[32];
    std::strftime(buf, sizeof buf, "%Y-%m-%dT%H:%M:%SZ", std::gmtime(&t));
    return buf;
}

/// A config's specimen: the packing from the cache, or made by genesis and cached (as
/// `gradem specimen` / `compress` get it).
struct Specimen {
    exp::Packing packing;
    bool cached = false;
    fs::path path;                         ///< the cache file
    std::optional<exp::PasteReport> paste; ///< explicit paste: the fill's report
};

Specimen specimen_of(const exp::CubeConfig& config) {
    const lab::GradationCurve curve = exp::load_gradation(config);
    Specimen s;
    if (config.specimen.paste) {
        s.paste.emplace();
        s.path = exp::paste_cache_path(curve, config.specimen, config.cache_dir);
        s.packing = exp::load_or_generate_paste(curve, config.specimen, config.cache_dir, &s.cached, &*s.paste);
    } else {
        s.path = exp::packing_cache_path(config.cache_dir, exp::packing_key(curve, config.specimen));
        s.packing = exp::load_or_generate(curve, config.specimen, config.cache_dir, &s.cached);
    }
    return s;
}

py::dict specimen_dict(const Specimen& s, const exp::CubeConfig& config) {
    const exp::Packing& k = s.packing;
    const std::size_t n = k.radius.size();
    py::array_t<double> positions({static_cast<py::ssize_t>(n), py::ssize_t{3}});
    auto p = positions.mutable_unchecked<2>();
    for (std::size_t i = 0; i < n; ++i) {
        p(i, 0) = k.position[i].x;
        p(i, 1) = k.position[i].y;
        p(i, 2) = k.position[i].z;
    }
    py::array_t<std::uint8_t> families(static_cast<py::ssize_t>(n));
    for (std::size_t i = 0; i < n; ++i) families.mutable_data()[i] = i < k.family.size() ? k.family[i] : 0;
    py::dict d;
    d["positions"] = positions;
    d["radii"] = to_array(k.radius);
    d["families"] = families;
    d["box_lo"] = py::make_tuple(k.box_lo.x, k.box_lo.y, k.box_lo.z);
    d["box_hi"] = py::make_tuple(k.box_hi.x, k.box_hi.y, k.box_hi.z);
    d["edge_mm"] = k.edge() * 1e3;
    d["density_kg_m3"] = k.density;
    d["cached"] = s.cached;
    d["path"] = s.path.string();
    d["description"] = exp::describe(k, config.specimen);
    const exp::GrainSample& g = k.grains;
    py::dict gradation;
    gradation["sieve_mm"] = column<double>(g.sieve_sizes, [](double v) { return v * 1e3; });
    gradation["target_percent"] = column<double>(g.target_passing, [](double v) { return 100.0 * v; });
    gradation["achieved_percent"] = column<double>(g.achieved_passing, [](double v) { return 100.0 * v; });
    d["gradation"] = gradation;
    py::dict report;
    report["porosity"] = k.porosity;
    report["mean_coordination"] = k.mean_coordination;
    report["edge_over_d50"] = k.edge_over_d50;
    report["floaters_before"] = k.floaters_before;
    report["floaters_after"] = k.floaters_after;
    report["wall_stress_mpa"] = py::make_tuple(k.wall_stress.x * kMpa, k.wall_stress.y * kMpa, k.wall_stress.z * kMpa);
    report["unbalanced_ratio"] = k.unbalanced_ratio;
    report["radius_growth"] = k.radius_growth;
    report["converged"] = k.converged;
    report["steps"] = k.steps;
    report["relax_iterations"] = k.relax_iterations;
    report["seconds"] = k.seconds;
    d["report"] = report;
    if (s.paste) d["paste"] = exp::describe(*s.paste);
    return d;
}

/// The curve's columns, named and in the units of load_curve.csv.
py::dict curve_dict(const std::vector<exp::CurvePoint>& c) {
    using P = exp::CurvePoint;
    py::dict d;
    d["step"] = column<std::int64_t>(c, [](const P& p) { return p.step; });
    d["time_s"] = column<double>(c, [](const P& p) { return p.time; });
    d["platen_strain"] = column<double>(c, [](const P& p) { return p.platen_strain; });
    d["gauge_strain"] = column<double>(c, [](const P& p) { return p.gauge_strain; });
    d["lateral_strain"] = column<double>(c, [](const P& p) { return p.lateral_strain; });
    d["stress_mpa"] = column<double>(c, [](const P& p) { return p.stress * kMpa; });
    d["stress_top_mpa"] = column<double>(c, [](const P& p) { return p.stress_top * kMpa; });
    d["stress_bottom_mpa"] = column<double>(c, [](const P& p) { return p.stress_bottom * kMpa; });
    d["broken_tension"] = column<std::int64_t>(c, [](const P& p) { return p.broken_tension; });
    d["broken_shear"] = column<std::int64_t>(c, [](const P& p) { return p.broken_shear; });
    d["kinetic_energy_j"] = column<double>(c, [](const P& p) { return p.kinetic_energy; });
    return d;
}

/// The crack log's columns, named and in the units of cracks.csv (without its interpolated
/// platen strain: the step and time place a break on the curve).
py::dict cracks_dict(const std::vector<BreakEvent>& c) {
    using E = BreakEvent;
    py::dict d;
    d["step"] = column<std::int64_t>(c, [](const E& e) { return e.step; });
    d["time_s"] = column<double>(c, [](const E& e) { return e.time; });
    d["x_m"] = column<double>(c, [](const E& e) { return e.position.x; });
    d["y_m"] = column<double>(c, [](const E& e) { return e.position.y; });
    d["z_m"] = column<double>(c, [](const E& e) { return e.position.z; });
    d["nx"] = column<double>(c, [](const E& e) { return e.normal.x; });
    d["ny"] = column<double>(c, [](const E& e) { return e.normal.y; });
    d["nz"] = column<double>(c, [](const E& e) { return e.normal.z; });
    d["shear"] = column<bool>(c, [](const E& e) { return e.mode == BondState::broken_shear; });
    d["i"] = column<std::int32_t>(c, [](const E& e) { return e.i; });
    d["j"] = column<std::int32_t>(c, [](const E& e) { return e.j; });
    d["bond_radius_m"] = column<double>(c, [](const E& e) { return e.bond_radius; });
    d["tensile_stress_mpa"] = column<double>(c, [](const E& e) { return e.tensile_stress * kMpa; });
    d["shear_stress_mpa"] = column<double>(c, [](const E& e) { return e.shear_stress * kMpa; });
    return d;
}

py::dict provenance(const Config& config, const char* test, const Specimen& s, int threads, double strain_rate,
                    const std::string& started, double seconds) {
    py::dict d;
    d["test"] = test;
    d["gradem_version"] = GRADEM_VERSION;
    d["code_version"] = cal::code_version();
    d["config"] = fs::absolute(config.file()).lexically_normal().string();
    py::dict overrides;
    for (const auto& [k, v] : config.overrides()) overrides[py::str(k)] = v;
    d["overrides"] = overrides;
    d["document"] = config.document();
    d["packing"] = s.path.string();
    d["packing_cached"] = s.cached;
    d["threads"] = threads;
    d["strain_rate_per_s"] = strain_rate;
    d["host"] = cal::host_name();
    d["started_utc"] = started;
    d["wall_seconds"] = seconds;
    return d;
}

py::dict point_dict(const exp::CurvePoint& p, double peak) {
    py::dict d;
    d["step"] = p.step;
    d["time_s"] = p.time;
    d["platen_strain"] = p.platen_strain;
    d["gauge_strain"] = p.gauge_strain;
    d["stress_mpa"] = p.stress * kMpa;
    d["peak_mpa"] = peak * kMpa;
    d["broken_tension"] = p.broken_tension;
    d["broken_shear"] = p.broken_shear;
    return d;
}

/// The progress hook of a test run: Ctrl-C, then the Python callback (if any) at every point.
/// It runs without the GIL: it holds the callback by address (copying a Python object needs
/// the GIL), and the callback outlives the run.
exp::ProgressCallback hook(SignalCheck& check, const py::object& progress) {
    const py::object* callback = progress.is_none() ? nullptr : &progress;
    return [&check, callback](const exp::CurvePoint& p, double peak) {
        check();
        if (callback) call_python(*callback, [&] { return point_dict(p, peak); });
    };
}

py::dict specimen(const Config& config, std::optional<int> threads) {
    LabWarnings warnings;
    const RunThreads run_threads(threads);
    std::optional<Specimen> s;
    {
        py::gil_scoped_release release;
        s = specimen_of(config.cube());
    }
    warnings.emit();
    return specimen_dict(*s, config.cube());
}

py::dict compress(const Config& config, std::optional<int> threads, const py::object& progress, const std::string& out,
                  bool check_rate) {
    const std::string started = utc_now();
    const auto start = Clock::now();
    LabWarnings warnings;
    const RunThreads run_threads(threads);
    const exp::CubeConfig& c = config.cube();
    std::optional<Specimen> s;
    std::optional<exp::CubeTestResult> result;
    std::optional<report::RateCheck> rate;
    double strain_rate = 0.0;
    std::string macro;
    {
        py::gil_scoped_release release;
        s = specimen_of(c);
        exp::CubeTestSpec spec = c.test;
        strain_rate = spec.loading.strain_rate = exp::strain_rate_for(c, s->packing);
        SignalCheck check;
        result = exp::run_cube_test(s->packing, c.material, spec, hook(check, progress));
        if (check_rate) {
            exp::CubeTestSpec half = spec;
            half.loading.strain_rate = 0.5 * spec.loading.strain_rate;
            const exp::CubeTestResult slow = exp::run_cube_test(s->packing, c.material, half, hook(check, progress));
            rate = report::compare_rates(*result, slow, strain_rate);
        }
        const exp::PasteReport* paste = s->paste ? &*s->paste : nullptr;
        macro = report::macro_json(*result, c, s->packing, strain_rate, rate, paste);
        if (!out.empty()) report::write_cube_outputs(out, *result, c, s->packing, strain_rate, rate, paste);
    }
    warnings.emit();
    py::dict d;
    d["macro"] = json_to_python(macro);
    d["curve"] = curve_dict(result->test.curve);
    d["cracks"] = cracks_dict(result->cracks);
    d["diverged"] = result->diverged() || (rate && rate->diverged_half);
    d["provenance"] = provenance(config, "compression", *s, run_threads.threads(), strain_rate, started,
                                 std::chrono::duration<double>(Clock::now() - start).count());
    return d;
}

py::dict tension(const Config& config, std::optional<int> threads, const py::object& progress, const std::string& out,
                 const std::string& compression, bool check_rate) {
    const std::string started = utc_now();
    const auto start = Clock::now();
    LabWarnings warnings;
    const RunThreads run_threads(threads);
    const exp::CubeConfig& c = config.cube();
    if (!compression.empty()) report::check_compression_file(compression);  // before genesis, as the command
    std::optional<Specimen> s;
    std::optional<exp::TensionTestResult> result;
    std::optional<report::RateCheck> rate;
    std::optional<report::CompressionReference> reference;
    double strain_rate = 0.0;
    std::string macro;
    {
        py::gil_scoped_release release;
        s = specimen_of(c);
        if (!compression.empty()) reference = report::read_compression_reference(compression, c, s->packing);
        exp::TensionTestSpec spec = config.tension().spec;
        strain_rate = spec.test.loading.strain_rate = exp::tension_strain_rate(c, config.tension(), s->packing);
        SignalCheck check;
        result = exp::run_tension_test(s->packing, c.material, spec, hook(check, progress));
        if (check_rate) {
            exp::TensionTestSpec half = spec;
            half.test.loading.strain_rate = 0.5 * spec.test.loading.strain_rate;
            const exp::TensionTestResult slow = exp::run_tension_test(s->packing, c.material, half, hook(check, progress));
            rate = report::compare_rates(result->cube, slow.cube, strain_rate);
        }
        macro = report::tension_macro_json(*result, c, spec, s->packing, strain_rate, rate, reference);
        if (!out.empty()) report::write_tension_outputs(fs::path(out) / "tension", *result, c, spec, s->packing, strain_rate, rate, reference);
    }
    warnings.emit();
    py::dict d;
    d["macro"] = json_to_python(macro);
    d["curve"] = curve_dict(result->cube.test.curve);
    d["cracks"] = cracks_dict(result->cube.cracks);
    d["diverged"] = result->diverged() || (rate && rate->diverged_half);
    d["provenance"] = provenance(config, "direct tension", *s, run_threads.threads(), strain_rate, started,
                                 std::chrono::duration<double>(Clock::now() - start).count());
    return d;
}

}  // namespace

void register_virtual_tests(py::module_& m) {
    py::register_exception_translator([](std::exception_ptr p) {
        try {
            if (p) std::rethrow_exception(p);
        } catch (const exp::PackingCacheError& e) {
            PyErr_SetString(input_error_class().ptr(), e.what());
        }
    });
    m.def("specimen", &specimen, py::arg("config"), py::arg("threads") = py::none(),
          "The config's packing: from the packing cache, or made by genesis and cached");
    m.def("compress", &compress, py::arg("config"), py::arg("threads") = py::none(), py::arg("progress") = py::none(),
          py::arg("out") = "", py::arg("check_rate") = false, "The virtual C109 cube test of a config (gradem compress)");
    m.def("tension", &tension, py::arg("config"), py::arg("threads") = py::none(), py::arg("progress") = py::none(),
          py::arg("out") = "", py::arg("compression") = "", py::arg("check_rate") = false,
          "The virtual direct-tension test of a config (gradem tension)");
}

}  // namespace gradem::py_api
