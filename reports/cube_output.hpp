#pragma once
// Result files of one cube test (`gradem compress`), each written atomically into `dir`:
//   load_curve.csv  one row per recorded curve point: step, time_s, platen_strain, gauge_strain,
//                   lateral_strain, stress_mpa, stress_top_mpa, stress_bottom_mpa,
//                   broken_tension, broken_shear, kinetic_energy_j
//   cracks.csv      one row per bond break: step, time_s, platen_strain (interpolated on the
//                   curve by step), x_m, y_m, z_m, nx, ny, nz, mode (tension|shear), i, j,
//                   bond_radius_m, tensile_stress_mpa, shear_stress_mpa
//   macro.json      the macro response (peak stress, strain at peak on the gauge and the
//                   platens, ASTM C469 chord modulus, tangent modulus, Poisson's ratio, Popovics
//                   fit), the run (particles, bonds, steps, time step, wall time, stop reason,
//                   warnings, breaks by mode), the material in SI and display units, the
//                   specimen summary and the rate check if one was run; for an explicit-paste
//                   specimen, "paste": counts, size ratio, volume fractions placed vs the mix
//                   design, bonds per family pair. NaN is written as null.
#include <filesystem>
#include <optional>
#include <string>

#include "experiments/config/cube_config.hpp"
#include "experiments/virtual_tests/cube_test.hpp"
#include "experiments/specimen/genesis.hpp"
#include "experiments/paste/paste_fill.hpp"

namespace gradem::report {

/// The quasi-static check: the same test at half the strain rate.
struct RateCheck {
    double strain_rate = 0.0, half_rate = 0.0;            ///< [1/s]
    double peak_stress = 0.0, peak_stress_half = 0.0;     ///< [Pa]
    double chord_modulus = 0.0, chord_modulus_half = 0.0; ///< [Pa] (NaN if not reduced)
    double peak_change = 0.0;     ///< (half - configured) / configured [-]
    double modulus_change = 0.0;  ///< [-]
    double imbalance = 0.0, imbalance_half = 0.0;  ///< the runs' platen imbalance (CubeTestResult) [-]
    std::string stop_reason_half;
    bool diverged_half = false;
    /// Whether halving the rate cut the platen imbalance to at most kInertialImbalanceShare of
    /// it: a difference of the end stresses that comes from the specimen's inertia scales with
    /// the loading rate (half at half the rate); one that comes from cracks ahead of the peak
    /// (a tension cube's microcracking from about 70 % of its peak) does not move.
    [[nodiscard]] bool imbalance_falls() const;
};
inline constexpr double kInertialImbalanceShare = 0.75;

/// With the configured run's imbalance over `limit` (CubeTestSpec::imbalance_warning): what
/// the rate check says of it, for the summary; empty otherwise.
std::string imbalance_verdict(const RateCheck& check, double limit);

/// Compares a run at the configured rate with one at half of it.
RateCheck compare_rates(const exp::CubeTestResult& at_rate, const exp::CubeTestResult& at_half_rate, double strain_rate);

/// The three CSV/JSON texts (exposed for tests) and the writer.
std::string load_curve_csv(const exp::CubeTestResult& result);
std::string cracks_csv(const exp::CubeTestResult& result);
std::string macro_json(const exp::CubeTestResult& result, const exp::CubeConfig& config, const exp::Packing& packing,
                       double strain_rate, const std::optional<RateCheck>& rate_check = {},
                       const exp::PasteReport* paste = nullptr);

/// A CubeTestSpec::snapshot that writes ParaView files into `dir` at the first recorded point
/// and then every `every`-th one (0: every 20th): particles_NNNNNN.vtp (with displacement since
/// the first snapshot), bonds_NNNNNN.vtp, cracks_NNNNNN.vtp, and cube.pvd tying them together
/// (rewritten after each snapshot, so an interrupted run keeps a valid series).
exp::SnapshotCallback vtk_snapshots(const std::filesystem::path& dir, int every);

/// Writes load_curve.csv, cracks.csv and macro.json into `dir` (created), each atomically.
/// `strain_rate` [1/s] is the rate the test ran at (resolved from "auto").
void write_cube_outputs(const std::filesystem::path& dir, const exp::CubeTestResult& result, const exp::CubeConfig& config,
                        const exp::Packing& packing, double strain_rate, const std::optional<RateCheck>& rate_check = {},
                        const exp::PasteReport* paste = nullptr);

}  // namespace gradem::report
