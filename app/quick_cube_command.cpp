// `gradem quick-cube`: a bonded cube of a few thousand spheres compressed between platens to
// past its peak, with a stress-strain summary. A smoke run of the whole engine on a quick
// lattice packing (experiments/quick_packing.hpp); specimens of a measured gradation are
// `gradem compress`'s (docs/genesis.md).
#include <chrono>
#include <cstdio>
#include <iostream>
#include <sstream>
#include <string>
#include <vector>

#include "app/cli.hpp"
#include "app/commands.hpp"
#include "common/atomic_file.hpp"
#include "core/parallel.hpp"
#include "experiments/platen_compression.hpp"
#include "experiments/quick_packing.hpp"

namespace gradem::app {
namespace {

struct QuickCubeOptions {
    std::int64_t particles = 4000;
    std::uint64_t seed = 1;
    double strain_rate = 4.0;
    std::string out;  // empty: no files
};

QuickCubeOptions parse_quick_cube(const std::vector<std::string>& args) {
    QuickCubeOptions o;
    CLI::App app{"A bonded cube of jittered spheres compressed between platens past its peak (engine smoke run).", "gradem quick-cube"};
    app.add_option("--particles", o.particles, "number of spheres")->check(CLI::Range(std::int64_t{100}, std::int64_t{2000000}));
    app.add_option("--seed", o.seed, "packing and strength seed");
    app.add_option("--strain-rate", o.strain_rate, "platen strain rate [1/s]")->check(CLI::Range(1.0, 1000.0));
    app.add_option("--out", o.out, "folder for load_curve.csv (default: no files)");
    parse_command(app, args);
    return o;
}

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

}  // namespace

int run_quick_cube(const std::vector<std::string>& args) {
    const QuickCubeOptions o = parse_quick_cube(args);
    exp::QuickPackingSpec spec;
    spec.target_count = o.particles;
    spec.seed = o.seed;
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
    bond.seed = o.seed;
    const std::size_t bonds = world.install_bonds(bond, packing.bond_gap);
    std::printf("quick-cube: %zu spheres (radius ratio %.0f), cube edge %.2f mm, solid fraction %.3f, "
                "%zu bonds, %d threads\n", world.particles().size(), spec.radius_ratio,
                packing.edge * 1e3, packing.solid_fraction, bonds, thread_count());
    std::printf("  E* = Ē* = %.1f GPa, σ̄c = %.1f ± %.1f MPa, c̄ = %.1f ± %.1f MPa, platen μ = 0.5, "
                "time step %.3g s\n", contact.effective_modulus * 1e-9, bond.tensile_strength_mean * 1e-6,
                bond.tensile_strength_std * 1e-6, bond.cohesion_mean * 1e-6, bond.cohesion_std * 1e-6,
                world.time_step());
    exp::PlatenTestSpec test;
    test.strain_rate = o.strain_rate;
    const auto progress = [&](const exp::CurvePoint& p, double peak) {
        if (p.step % 5000 == 0)
            std::fprintf(stderr, "  step %7lld  strain %.5f  stress %7.3f MPa  (peak %7.3f)  breaks %lld\n",
                         static_cast<long long>(p.step), p.platen_strain, p.stress * 1e-6, peak * 1e-6,
                         static_cast<long long>(p.broken_tension + p.broken_shear));
    };
    const exp::PlatenTestResult r = exp::run_platen_compression(world, test, progress);
    const exp::CurvePoint& last = r.curve.back();
    std::printf("stress-strain summary (platen strain; load / initial area):\n");
    std::printf("  peak stress          %8.3f MPa\n", r.peak_stress * 1e-6);
    std::printf("  strain at peak       %8.5f\n", r.strain_at_peak);
    std::printf("  secant modulus (40%%) %8.3f GPa\n", r.secant_modulus_40 * 1e-9);
    std::printf("  broken bonds         %lld tension, %lld shear (of %zu)\n",
                static_cast<long long>(last.broken_tension), static_cast<long long>(last.broken_shear), bonds);
    std::printf("  stop                 %s at strain %.5f after %lld steps\n", r.stop_reason.c_str(),
                last.platen_strain, static_cast<long long>(r.steps));
    std::printf("  wall time            %.2f s (%.3g particle-steps/s)\n", r.wall_seconds,
                static_cast<double>(world.particles().size()) * static_cast<double>(r.steps) / r.wall_seconds);
    if (!o.out.empty()) {
        common::write_file_atomically(o.out + "/load_curve.csv", curve_csv(r));
        std::printf("  curve written to     %s/load_curve.csv\n", o.out.c_str());
    }
    return r.diverged ? 3 : 0;
}

}  // namespace gradem::app
