// `gradem quick-cube`: a bonded cube of a few thousand spheres compressed between platens to
// past its peak, with a stress-strain summary. A smoke run of the whole engine on a quick
// lattice packing (experiments/specimen/quick_packing.hpp); specimens of a measured gradation are
// `gradem compress`'s (docs/genesis.md).
#include <chrono>
#include <memory>
#include <cstdio>
#include <iostream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <vector>

#include "app/cli.hpp"
#include "app/commands.hpp"
#include "common/atomic_file.hpp"
#include "core/parallel.hpp"
#include "experiments/virtual_tests/platen_compression.hpp"
#include "experiments/specimen/quick_packing.hpp"

namespace gradem::app {
namespace {

std::string curve_csv(const exp::PlatenTestResult& r) {
    std::ostringstream out;
    out << "step,time_s,platen_strain,stress_mpa,stress_top_mpa,stress_bottom_mpa,"
           "broken_tension,broken_shear,kinetic_energy_j\n";
    out.precision(9);
    for (const exp::CurvePoint& p : r.curve)
        out << p.step << ',' << p.time << ',' << p.platen_strain << ',' << p.stress * 1e-6 << ','
            << p.stress_top * 1e-6 << ',' << p.stress_bottom * 1e-6 << ',' << p.broken_tension
            << ',' << p.broken_shear << ',' << p.kinetic_energy << '\n';
    return out.str();
}

class QuickCubeCommand final : public Command {
public:
    void declare(CLI::App& app) override {
        particles_ = app.add_option("--particles", particles_wanted_,
                                    "number of spheres: the lattice holds 8 m^3 (216, 512, 1000, 1728, 2744, 4096, ...); "
                                    "another number in [100, 2000000] is rounded to the nearest, with a warning (default 4096)")
                         ->check(CLI::Range(std::int64_t{100}, std::int64_t{2000000}))
                         ->type_name("N");
        app.add_option("--seed", seed_, "packing and strength seed (default 1)")->type_name("S");
        app.add_option("--strain-rate", strain_rate_, "platen strain rate [1/s], 1 to 1000 (default 4)")
            ->check(CLI::Range(1.0, 1000.0))
            ->type_name("R");
        app.add_option("--out", out_, "folder for load_curve.csv (default: no files)")->type_name("DIR");
    }

    int run() override;

private:
    std::int64_t particles_wanted_ = 4096;
    std::uint64_t seed_ = 1;
    double strain_rate_ = 4.0;
    std::string out_;  // empty: no files
    CLI::Option* particles_ = nullptr;
};

std::string summary_json(const exp::PlatenTestResult& r, std::int64_t requested, std::size_t particles, std::size_t bonds,
                         const std::string& curve_file) {
    const exp::CurvePoint& last = r.curve.back();
    const nlohmann::ordered_json j = {{"particles_requested", requested},
                                      {"particles", particles},
                                      {"bonds", bonds},
                                      {"peak_stress_mpa", r.peak_stress * 1e-6},
                                      {"strain_at_peak", r.strain_at_peak},
                                      {"secant_modulus_40_gpa", r.secant_modulus_40 * 1e-9},
                                      {"broken_tension", last.broken_tension},
                                      {"broken_shear", last.broken_shear},
                                      {"stop_reason", r.stop_reason},
                                      {"diverged", r.diverged},
                                      {"steps", r.steps},
                                      {"wall_s", r.wall_seconds},
                                      {"load_curve", curve_file.empty() ? nlohmann::ordered_json() : nlohmann::ordered_json(curve_file)}};
    return j.dump(2);
}

int QuickCubeCommand::run() {
    const Console& con = console();
    exp::QuickPackingSpec spec;
    spec.target_count = particles_wanted_;
    spec.seed = seed_;
    const std::int64_t used = exp::quick_packing_count(particles_wanted_);
    if (used != particles_wanted_ && particles_->count() > 0)
        std::fprintf(con.notes(), "quick-cube: warning: --particles %lld: the rock-salt lattice holds 8 m^3 spheres "
                     "(216, 512, 1000, ...): using %lld, the nearest\n", static_cast<long long>(particles_wanted_),
                     static_cast<long long>(used));
    inputs_checked();
    const exp::QuickPacking packing = exp::make_quick_packing(spec);
    ContactParams contact;
    contact.effective_modulus = 10.0e9;
    World world(packing.particles, contact, SimParams{});
    BondParams bond;
    bond.effective_modulus = 10.0e9;
    bond.tensile_strength_mean = 10.0e6;
    bond.tensile_strength_std = 2.0e6;
    bond.cohesion_mean = 20.0e6;
    bond.cohesion_std = 4.0e6;
    bond.seed = seed_;
    const std::size_t bonds = world.install_bonds(bond, packing.bond_gap);
    std::fprintf(con.text(), "quick-cube: %zu spheres (radius ratio %.0f), cube edge %.2f mm, solid fraction %.3f, "
                "%zu bonds, %d threads\n", world.particles().size(), spec.radius_ratio,
                packing.edge * 1e3, packing.solid_fraction, bonds, thread_count());
    std::fprintf(con.text(), "  E* = Ē* = %.1f GPa, σ̄c = %.1f ± %.1f MPa, c̄ = %.1f ± %.1f MPa, platen μ = 0.5, "
                "time step %.3g s\n", contact.effective_modulus * 1e-9, bond.tensile_strength_mean * 1e-6,
                bond.tensile_strength_std * 1e-6, bond.cohesion_mean * 1e-6, bond.cohesion_std * 1e-6,
                world.time_step());
    exp::PlatenTestSpec test;
    test.strain_rate = strain_rate_;
    const auto progress = [&](const exp::CurvePoint& p, double peak) {
        if (p.step % 5000 == 0)
            std::fprintf(con.notes(), "  step %7lld  strain %.5f  stress %7.3f MPa  (peak %7.3f)  breaks %lld\n",
                         static_cast<long long>(p.step), p.platen_strain, p.stress * 1e-6, peak * 1e-6,
                         static_cast<long long>(p.broken_tension + p.broken_shear));
    };
    const exp::PlatenTestResult r = exp::run_platen_compression(world, test, progress);
    const exp::CurvePoint& last = r.curve.back();
    std::fprintf(con.text(), "stress-strain summary (platen strain; load / initial area):\n");
    std::fprintf(con.text(), "  peak stress          %8.3f MPa\n", r.peak_stress * 1e-6);
    std::fprintf(con.text(), "  strain at peak       %8.5f\n", r.strain_at_peak);
    std::fprintf(con.text(), "  secant modulus (40%%) %8.3f GPa\n", r.secant_modulus_40 * 1e-9);
    std::fprintf(con.text(), "  broken bonds         %lld tension, %lld shear (of %zu)\n",
                static_cast<long long>(last.broken_tension), static_cast<long long>(last.broken_shear), bonds);
    std::fprintf(con.text(), "  stop                 %s at strain %.5f after %lld steps\n", r.stop_reason.c_str(),
                last.platen_strain, static_cast<long long>(r.steps));
    std::fprintf(con.text(), "  wall time            %.2f s (%.3g particle-steps/s)\n", r.wall_seconds,
                static_cast<double>(world.particles().size()) * static_cast<double>(r.steps) / r.wall_seconds);
    std::string curve_file;
    if (!out_.empty()) {
        curve_file = out_ + "/load_curve.csv";
        common::write_file_atomically(curve_file, curve_csv(r));
        std::fprintf(con.text(), "  curve written to     %s\n", curve_file.c_str());
    }
    if (con.json()) Console::print_json(summary_json(r, particles_wanted_, world.particles().size(), bonds, curve_file));
    if (r.diverged) {
        std::fprintf(stderr, "gradem quick-cube: the simulation diverged: %s\n", r.stop_reason.c_str());
        return common::exit_run_failed;
    }
    return common::exit_success;
}

}  // namespace

std::unique_ptr<Command> make_quick_cube_command() { return std::make_unique<QuickCubeCommand>(); }

}  // namespace gradem::app
