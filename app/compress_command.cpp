// `gradem compress <config.toml> [--out DIR] [--check-rate] [--vtk]`: the virtual C109 cube test
// of a config. Loads (or generates and caches) the packing, runs run_cube_test with a progress
// line on stderr, writes load_curve.csv, cracks.csv and macro.json (and ParaView files with
// --vtk) into the output folder, and prints a summary. --check-rate runs the test again at half
// the strain rate and reports the relative change of peak stress and chord modulus.
// Exit status: 0 ok, 1 bad input, 2 bad usage, 3 a diverged simulation (outputs still written).
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <iostream>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "app/cli.hpp"
#include "app/commands.hpp"
#include "app/progress_line.hpp"
#include "app/test_specimen.hpp"
#include "common/clock_text.hpp"
#include "common/text_file.hpp"
#include "experiments/config/cube_config.hpp"
#include "experiments/virtual_tests/cube_test.hpp"
#include "experiments/specimen/packing_cache.hpp"
#include "experiments/paste/paste_cache.hpp"
#include "reports/cube_output.hpp"
#include "reports/html_report.hpp"

namespace gradem::app {
namespace {

using common::clock_text;

using Clock = std::chrono::steady_clock;

class CompressCommand final : public Command {
public:
    void declare(CLI::App& app) override {
        app.add_option("config", config_, "cube config TOML (experiments/README.md lists its keys)")->required()->type_name("config.toml");
        app.add_option("--out", out_, "result folder (default: the config's output.dir)")->type_name("DIR");
        app.add_flag("--check-rate", check_rate_, "run again at half the strain rate and report the change (quasi-static check)");
        app.add_flag("--vtk", vtk_, "write ParaView files (vtk/cube.pvd) as well");
    }
    int run() override;

private:
    std::string config_, out_;
    bool check_rate_ = false, vtk_ = false;
};

exp::CubeTestResult run_with_progress(const exp::Packing& packing, const exp::CubeConfig& c, const exp::CubeTestSpec& spec,
                                      const std::string& label) {
    std::fprintf(console().notes(), "%s: strain rate %.4g 1/s, bonding and settling ...\n", label.c_str(), spec.loading.strain_rate);
    ProgressLine line(label, spec.loading.max_strain);
    exp::CubeTestResult r = exp::run_cube_test(packing, c.material, spec, line.callback());
    line.finish();
    return r;
}

void print_summary(const exp::CubeTestResult& r, const std::optional<report::RateCheck>& check, double imbalance_limit,
                   const std::string& out) {
    std::FILE* text = console().text();
    std::int64_t tension = 0, shear = 0;
    for (const BreakEvent& e : r.cracks) ++(e.mode == BondState::broken_shear ? shear : tension);
    const lab::CurveReduction& m = r.macro;
    std::fprintf(text, "cube test (%zu particles, %zu bonds):\n", r.particles, r.bonds);
    std::fprintf(text, "  peak stress          %9.3f MPa\n", m.peak_stress_pa * 1e-6);
    std::fprintf(text, "  strain at peak       %9.5f gauge, %.5f platen\n", m.strain_at_peak, r.strain_at_peak_platen);
    std::fprintf(text, "  chord modulus (C469) %9.3f GPa%s\n", m.chord_modulus_pa * 1e-9,
                m.status == lab::ReductionStatus::ok ? "" : ("  (" + m.message + ")").c_str());
    std::fprintf(text, "  Poisson's ratio      %9.3f\n", m.poisson_ratio);
    std::fprintf(text, "  broken bonds         %lld tension, %lld shear (of %zu)\n", static_cast<long long>(tension),
                static_cast<long long>(shear), r.bonds);
    std::fprintf(text, "  stop                 %s after %lld steps, wall time %.1f s\n", r.test.stop_reason.c_str(),
                static_cast<long long>(r.test.steps), r.test.wall_seconds);
    if (check)
        std::fprintf(text, "  rate check (half rate %.4g 1/s): peak %+.2f %%, chord modulus %+.2f %%%s\n", check->half_rate,
                    100.0 * check->peak_change, 100.0 * check->modulus_change, check->diverged_half ? " (half-rate run diverged)" : "");
    if (check)
        if (const std::string verdict = report::imbalance_verdict(*check, imbalance_limit); !verdict.empty())
            std::fprintf(text, "  rate check: %s\n", verdict.c_str());
    for (const std::string& w : r.warnings) std::fprintf(text, "  warning: %s\n", w.c_str());
    std::fprintf(text, "  results in           %s\n", out.c_str());
}

void print_paste_summary(const exp::PasteReport& p, const exp::CubeTestResult& r) {
    std::FILE* text = console().text();
    std::fprintf(text, "%s\n", exp::describe(p).c_str());
    std::fprintf(text, "  bonds per family     %zu sand-sand, %zu sand-paste, %zu paste-paste\n", r.bonds_sand_sand, r.bonds_itz,
                r.bonds_paste_paste);
}

}  // namespace

int CompressCommand::run() {
    const Console& con = console();
    exp::CubeConfig config = load_test_config(config_, out_, vtk_);
    const lab::GradationCurve curve = exp::load_gradation(config);
    inputs_checked();
    std::optional<exp::PasteReport> paste;  // explicit paste: the fill's report
    if (config.specimen.paste) paste.emplace();
    const exp::Packing packing = load_test_packing(config, curve, "compress", paste ? &*paste : nullptr);

    exp::CubeTestSpec spec = config.test;
    spec.loading.strain_rate = exp::strain_rate_for(config, packing);
    if (config.vtk) spec.snapshot = report::vtk_snapshots(config.out_dir / "vtk", config.vtk_every);
    const exp::CubeTestResult result = run_with_progress(packing, config, spec, "compress");

    std::optional<report::RateCheck> check;
    bool half_diverged = false;
    if (check_rate_) {
        exp::CubeTestSpec half = spec;
        half.loading.strain_rate = 0.5 * spec.loading.strain_rate;
        half.snapshot = {};
        const exp::CubeTestResult slow = run_with_progress(packing, config, half, "compress (half rate)");
        check = report::compare_rates(result, slow, spec.loading.strain_rate);
        half_diverged = slow.diverged();
    }
    report::write_cube_outputs(config.out_dir, result, config, packing, spec.loading.strain_rate, check,
                            paste ? &*paste : nullptr);
    print_summary(result, check, spec.imbalance_warning, config.out_dir.string());
    if (paste) print_paste_summary(*paste, result);
    report::write_html_report_or_warn(report::ReportKind::compress, config.out_dir, con.announce(), con.notes_stream());
    if (con.json()) Console::print_json(common::read_file_bytes(config.out_dir / "macro.json"));
    if (result.diverged() || half_diverged) {
        std::fprintf(stderr, "gradem compress: the simulation diverged: %s\n",
                     (result.diverged() ? result.test.stop_reason : check->stop_reason_half).c_str());
        return common::exit_run_failed;
    }
    return common::exit_success;
}

std::unique_ptr<Command> make_compress_command() { return std::make_unique<CompressCommand>(); }

}  // namespace gradem::app
