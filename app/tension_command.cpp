// `gradem tension <config.toml> [--out DIR] [--compression MACRO_JSON] [--check-rate] [--vtk]`:
// the virtual direct-tension test of a cube config (the specimen, material and loading of
// `gradem compress`, plus the optional [tension] table). Loads (or generates and caches) the
// packing, runs run_tension_test with a progress line on stderr, writes load_curve.csv,
// cracks.csv and macro.json (tension positive) into <output dir>/tension and prints a summary.
// σc/σt is reported when a compression macro.json of the same config is given with
// --compression (read and checked before genesis, matched to the packing before the run: an
// unusable file is an error, exit 1), or found as
// <output dir>/macro.json (where `gradem compress` writes it; skipped with a note if it does
// not match).
// --check-rate runs the test again at half the strain rate.
// Exit status: 0 ok, 1 bad input, 2 bad usage, 3 a diverged simulation (outputs still written).
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "app/cli.hpp"
#include "app/commands.hpp"
#include "app/progress_line.hpp"
#include "app/test_specimen.hpp"
#include "common/input_error.hpp"
#include "common/text_file.hpp"
#include "experiments/config/cube_config.hpp"
#include "experiments/specimen/packing_cache.hpp"
#include "experiments/config/tension_config.hpp"
#include "experiments/virtual_tests/tension_test.hpp"
#include "reports/cube_output.hpp"
#include "reports/tension_output.hpp"

namespace gradem::app {
namespace {

namespace fs = std::filesystem;


class TensionCommand final : public Command {
public:
    void declare(CLI::App& app) override {
        app.add_option("config", config_, "cube config TOML (an optional [tension] table; experiments/README.md)")
            ->required()
            ->type_name("config.toml");
        app.add_option("--out", out_, "result folder (default: the config's output.dir); files go to DIR/tension")->type_name("DIR");
        app.add_option("--compression", compression_,
                       "macro.json of the compression test of the same config, for sigma_c/sigma_t (checked before the run)")
            ->type_name("MACRO_JSON");
        app.add_flag("--check-rate", check_rate_, "run again at half the strain rate and report the change");
        app.add_flag("--vtk", vtk_, "write ParaView files as well");
    }
    int run() override;

private:
    std::string config_, out_, compression_;
    bool check_rate_ = false, vtk_ = false;
};

exp::TensionTestResult run_with_progress(const exp::Packing& packing, const exp::CubeConfig& c,
                                         const exp::TensionTestSpec& spec, const std::string& label) {
    std::fprintf(console().notes(), "%s: strain rate %.4g 1/s, bonding and settling ...\n", label.c_str(),
                 spec.test.loading.strain_rate);
    ProgressLine line(label, spec.test.loading.max_strain);
    exp::TensionTestResult r = exp::run_tension_test(packing, c.material, spec, line.callback());
    line.finish();
    return r;
}

// The compression macro.json of the same output folder, if there is a matching one.
std::optional<report::CompressionReference> compression_beside(const exp::CubeConfig& c, const exp::Packing& packing) {
    const fs::path beside = c.out_dir / "macro.json";
    if (!fs::exists(beside)) return std::nullopt;
    try {
        return report::read_compression_reference(beside, c, packing);
    } catch (const common::InputError& e) {
        std::fprintf(console().notes(), "tension: no σc/σt: %s\n", e.what());
        return std::nullopt;
    }
}

void print_summary(const exp::TensionTestResult& t, const std::optional<report::RateCheck>& check, double imbalance_limit,
                   const std::optional<report::CompressionReference>& compression, const std::string& out) {
    std::FILE* text = console().text();
    const exp::CubeTestResult& r = t.cube;
    std::int64_t tension = 0, shear = 0;
    for (const BreakEvent& e : r.cracks) ++(e.mode == BondState::broken_shear ? shear : tension);
    const lab::CurveReduction& m = r.macro;
    std::fprintf(text, "direct tension test (%zu particles, %zu bonds, grips of %zu + %zu grains):\n", r.particles, r.bonds,
                t.grip_grains_bottom, t.grip_grains_top);
    std::fprintf(text, "  tensile strength     %9.3f MPa\n", m.peak_stress_pa * 1e-6);
    std::fprintf(text, "  strain at peak       %9.6f gauge, %.6f grips\n", m.strain_at_peak, r.strain_at_peak_platen);
    std::fprintf(text, "  tensile modulus      %9.3f GPa (chord from %.0f µε to 40 %% of the peak)%s\n", m.chord_modulus_pa * 1e-9,
                t.chord_lower_strain * 1e6, m.status == lab::ReductionStatus::ok ? "" : ("  (" + m.message + ")").c_str());
    if (compression)
        std::fprintf(text, "  σc / σt              %9.2f  (σc %.3f MPa from %s)\n", compression->peak_stress / m.peak_stress_pa,
                    compression->peak_stress * 1e-6, compression->file.string().c_str());
    std::fprintf(text, "  broken bonds         %lld tension, %lld shear (of %zu)\n", static_cast<long long>(tension),
                static_cast<long long>(shear), r.bonds);
    std::fprintf(text, "  stop                 %s after %lld steps, wall time %.1f s\n", r.test.stop_reason.c_str(),
                static_cast<long long>(r.test.steps), r.test.wall_seconds);
    if (check)
        std::fprintf(text, "  rate check (half rate %.4g 1/s): peak %+.2f %%, modulus %+.2f %%%s\n", check->half_rate,
                    100.0 * check->peak_change, 100.0 * check->modulus_change,
                    check->diverged_half ? " (half-rate run diverged)" : "");
    if (check)
        if (const std::string verdict = report::imbalance_verdict(*check, imbalance_limit); !verdict.empty())
            std::fprintf(text, "  rate check: %s\n", verdict.c_str());
    for (const std::string& w : r.warnings) std::fprintf(text, "  warning: %s\n", w.c_str());
    std::fprintf(text, "  results in           %s\n", out.c_str());
}

}  // namespace

int TensionCommand::run() {
    const Console& con = console();
    exp::CubeConfig config = load_test_config(config_, out_, vtk_);
    const exp::TensionConfig tension = exp::load_tension_config(config);
    exp::TensionTestSpec spec = tension.spec;
    const fs::path out_dir = config.out_dir / "tension";

    const lab::GradationCurve curve = exp::load_gradation(config);
    if (!compression_.empty()) report::check_compression_file(compression_);  // before genesis; matched to it below
    inputs_checked();
    const exp::Packing packing = load_test_packing(config, curve, "tension");

    std::optional<report::CompressionReference> compression;  // --compression: matched to the packing before the long run
    if (!compression_.empty()) compression = report::read_compression_reference(compression_, config, packing);
    spec.test.loading.strain_rate = exp::tension_strain_rate(config, tension, packing);
    if (config.vtk) spec.test.snapshot = report::vtk_snapshots(out_dir / "vtk", config.vtk_every);
    const exp::TensionTestResult result = run_with_progress(packing, config, spec, "tension");

    std::optional<report::RateCheck> check;
    bool half_diverged = false;
    if (check_rate_) {
        exp::TensionTestSpec half = spec;
        half.test.loading.strain_rate = 0.5 * spec.test.loading.strain_rate;
        half.test.snapshot = {};
        const exp::TensionTestResult slow = run_with_progress(packing, config, half, "tension (half rate)");
        check = report::compare_rates(result.cube, slow.cube, spec.test.loading.strain_rate);
        half_diverged = slow.diverged();
    }
    if (!compression) compression = compression_beside(config, packing);
    report::write_tension_outputs(out_dir, result, config, spec, packing, spec.test.loading.strain_rate, check, compression);
    print_summary(result, check, spec.test.imbalance_warning, compression, out_dir.string());
    if (con.json()) Console::print_json(common::read_file_bytes(out_dir / "macro.json"));
    if (result.diverged() || half_diverged) {
        std::fprintf(stderr, "gradem tension: the simulation diverged: %s\n",
                     (result.diverged() ? result.cube.test.stop_reason : check->stop_reason_half).c_str());
        return common::exit_run_failed;
    }
    return common::exit_success;
}

std::unique_ptr<Command> make_tension_command() { return std::make_unique<TensionCommand>(); }

}  // namespace gradem::app
