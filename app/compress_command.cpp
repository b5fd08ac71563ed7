// `gradem compress <config.toml> [--out DIR] [--check-rate] [--vtk]`: the virtual C109 cube test
// of a config. Loads (or generates and caches) the packing, runs run_cube_test with a progress
// line on stderr, writes load_curve.csv, cracks.csv and macro.json (and ParaView files with
// --vtk) into the output folder, and prints a summary. --check-rate runs the test again at half
// the strain rate and reports the relative change of peak stress and chord modulus.
// Exit codes: 0 ok, 2 bad usage or input, 3 a diverged simulation (outputs still written).
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <iostream>
#include <optional>
#include <string>
#include <vector>

#include "app/cli.hpp"
#include "app/commands.hpp"
#include "app/progress_line.hpp"
#include "common/clock_text.hpp"
#include "experiments/cube_config.hpp"
#include "experiments/cube_test.hpp"
#include "experiments/packing_cache.hpp"
#include "experiments/paste_cache.hpp"
#include "reports/cube_output.hpp"
#include "reports/html_report.hpp"

namespace gradem::app {
namespace {

using common::clock_text;

using Clock = std::chrono::steady_clock;

struct CompressOptions {
    std::string config, out;
    bool check_rate = false, vtk = false;
};

CompressOptions parse_compress(const std::vector<std::string>& args) {
    CompressOptions o;
    CLI::App app{"The virtual ASTM C109 cube test of a cube config: load_curve.csv, cracks.csv, macro.json.", "gradem compress"};
    app.add_option("config", o.config, "cube config TOML (experiments/README.md lists its keys)")->required();
    app.add_option("--out", o.out, "result folder (default: the config's output.dir)");
    app.add_flag("--check-rate", o.check_rate, "run again at half the strain rate and report the change (quasi-static check)");
    app.add_flag("--vtk", o.vtk, "write ParaView files (vtk/cube.pvd) as well");
    parse_command(app, args);
    return o;
}

exp::CubeTestResult run_with_progress(const exp::Packing& packing, const exp::CubeConfig& c, const exp::CubeTestSpec& spec,
                                      const std::string& label) {
    std::fprintf(stderr, "%s: strain rate %.4g 1/s, bonding and settling ...\n", label.c_str(), spec.loading.strain_rate);
    ProgressLine line(label, spec.loading.max_strain);
    exp::CubeTestResult r = exp::run_cube_test(packing, c.material, spec, line.callback());
    line.finish();
    return r;
}

void print_summary(const exp::CubeTestResult& r, const std::optional<exp::RateCheck>& check, const std::string& out) {
    std::int64_t tension = 0, shear = 0;
    for (const BreakEvent& e : r.cracks) ++(e.mode == BondState::broken_shear ? shear : tension);
    const lab::CurveReduction& m = r.macro;
    std::printf("cube test (%zu particles, %zu bonds):\n", r.particles, r.bonds);
    std::printf("  peak stress          %9.3f MPa\n", m.peak_stress_pa * 1e-6);
    std::printf("  strain at peak       %9.5f gauge, %.5f platen\n", m.strain_at_peak, r.strain_at_peak_platen);
    std::printf("  chord modulus (C469) %9.3f GPa%s\n", m.chord_modulus_pa * 1e-9,
                m.status == lab::ReductionStatus::ok ? "" : ("  (" + m.message + ")").c_str());
    std::printf("  Poisson's ratio      %9.3f\n", m.poisson_ratio);
    std::printf("  broken bonds         %lld tension, %lld shear (of %zu)\n", static_cast<long long>(tension),
                static_cast<long long>(shear), r.bonds);
    std::printf("  stop                 %s after %lld steps, wall time %.1f s\n", r.test.stop_reason.c_str(),
                static_cast<long long>(r.test.steps), r.test.wall_seconds);
    if (check)
        std::printf("  rate check (half rate %.4g 1/s): peak %+.2f %%, chord modulus %+.2f %%%s\n", check->half_rate,
                    100.0 * check->peak_change, 100.0 * check->modulus_change, check->diverged_half ? " (half-rate run diverged)" : "");
    for (const std::string& w : r.warnings) std::printf("  warning: %s\n", w.c_str());
    std::printf("  results in           %s\n", out.c_str());
}

void print_paste_summary(const exp::PasteReport& p, const exp::CubeTestResult& r) {
    std::printf("%s\n", exp::describe(p).c_str());
    std::printf("  bonds per family     %zu sand-sand, %zu sand-paste, %zu paste-paste\n", r.bonds_sand_sand, r.bonds_itz,
                r.bonds_paste_paste);
}

}  // namespace

int run_compress(const std::vector<std::string>& args) {
    const CompressOptions o = parse_compress(args);
    exp::CubeConfig config = exp::load_cube_config(o.config);
    if (!o.out.empty()) config.out_dir = o.out;
    if (o.vtk) config.vtk = true;

    const lab::GradationCurve curve = exp::load_gradation(config);
    bool cached = false;
    if (!std::filesystem::exists(exp::packing_cache_path(config.cache_dir, exp::packing_key(curve, config.specimen))))
        std::fprintf(stderr, "compress: generating the packing (genesis) ...\n");
    std::optional<exp::PasteReport> paste;  // explicit paste: the fill's report
    if (config.specimen.paste) paste.emplace();
    const exp::Packing packing =
        paste ? exp::load_or_generate_paste(curve, config.specimen, config.cache_dir, &cached, &*paste)
              : exp::load_or_generate(curve, config.specimen, config.cache_dir, &cached);
    std::fprintf(stderr, "compress: packing of %zu grains (%s)\n", packing.radius.size(), cached ? "cached" : "generated");

    exp::CubeTestSpec spec = config.test;
    spec.loading.strain_rate = exp::strain_rate_for(config, packing);
    if (config.vtk) spec.snapshot = exp::vtk_snapshots(config.out_dir / "vtk", config.vtk_every);
    const exp::CubeTestResult result = run_with_progress(packing, config, spec, "compress");

    std::optional<exp::RateCheck> check;
    bool half_diverged = false;
    if (o.check_rate) {
        exp::CubeTestSpec half = spec;
        half.loading.strain_rate = 0.5 * spec.loading.strain_rate;
        half.snapshot = {};
        const exp::CubeTestResult slow = run_with_progress(packing, config, half, "compress (half rate)");
        check = exp::compare_rates(result, slow, spec.loading.strain_rate);
        half_diverged = slow.diverged();
    }
    exp::write_cube_outputs(config.out_dir, result, config, packing, spec.loading.strain_rate, check,
                            paste ? &*paste : nullptr);
    print_summary(result, check, config.out_dir.string());
    if (paste) print_paste_summary(*paste, result);
    report::write_html_report_or_warn(report::ReportKind::compress, config.out_dir, std::cout);
    if (result.diverged() || half_diverged) {
        std::fprintf(stderr, "gradem: the simulation diverged: %s\n",
                     (result.diverged() ? result.test.stop_reason : check->stop_reason_half).c_str());
        return 3;
    }
    return 0;
}

}  // namespace gradem::app
