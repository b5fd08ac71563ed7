#pragma once
// A calibration problem, read from a TOML file (calibrate/README.md documents every key):
//
//   [calibration] base (a cube config: specimen size rule, genesis, start material, test),
//                 mode = "joint" | "per_sand" | "study", sands, calibrate_on, seeds, model,
//                 bond_model (overrides the base's [material] model; kept in base.material),
//                 edge_mm, paste_diameter_mm (override the base's cube edge and paste size)
//   [targets]     lab_results (the lab_results.json of `gradem lab`), modulus/peak/strain weights
//   [parameters.<name>]  free, start, lower, upper, scale = "log" | "linear"
//   [solver]      method, max_runs, tolerance, fd_step, homogeneity_tolerance, penalty, seed
//   [run]         workers, timeout_s
//   [output]      dir, ledger
//
// Targets are never typed in: they are the per-sand mean and standard deviation of the chord
// modulus, peak stress and strain at peak in the lab results file. Every error is a
// common::InputError naming the file, line and key.
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include "calibrate/parameters.hpp"
#include "experiments/cube_config.hpp"

namespace gradem::cal {

enum class Mode { joint, per_sand, study };
enum class Method { scaling, bobyqa, sbplx, cobyla, crs2, direct, ceres };
const char* to_string(Mode m);
const char* to_string(Method m);

/// Mean and standard deviation of one lab quantity over a sand's cubes (SI).
struct TargetStat {
    double mean = 0.0, std = 0.0;
    int n = 0;
};

struct SandTargets {
    std::string name;
    TargetStat modulus, peak, strain;  ///< chord modulus [Pa], peak stress [Pa], strain at peak [-]
};

/// The three targets of a sand, in this order everywhere (residual vectors, tables).
enum class Quantity { modulus, peak, strain };
inline constexpr Quantity kQuantities[] = {Quantity::modulus, Quantity::peak, Quantity::strain};
const char* to_string(Quantity q);
const TargetStat& target_of(const SandTargets& t, Quantity q);

struct Weights {
    double modulus = 1.0, peak = 1.0, strain = 0.2;
    [[nodiscard]] double of(Quantity q) const { return q == Quantity::modulus ? modulus : q == Quantity::peak ? peak : strain; }
};

struct SolverSettings {
    Method method = Method::scaling;
    int max_runs = 50;                    ///< budget of cube test runs (ledger hits count too)
    double tolerance = 0.01;              ///< relative x tolerance in the unit box / objective scale
    double fd_step = 0.05;                ///< finite-difference step: relative (log) or of the range (linear)
    double homogeneity_tolerance = 0.05;  ///< max |predicted/actual − 1| of E and peak for the scaling path
    double penalty = 3.0;                 ///< residual of every target of a failed evaluation
    std::uint64_t seed = 1;               ///< for the stochastic global method (CRS2)
};

struct CalibrationProblem {
    std::filesystem::path file;
    std::filesystem::path base_file;      ///< the base cube config ([calibration] base)
    exp::CubeConfig base;
    std::string model = "dem";            ///< "dem" or "analytic" (the stand-in, for trials and tests)
    Mode mode = Mode::joint;
    std::vector<std::string> sands;
    std::string calibrate_on;             ///< study mode: the sand calibrated on
    std::vector<std::uint64_t> seeds = {1, 2};
    std::vector<ParameterSpec> parameters;
    std::filesystem::path lab_results;
    std::vector<SandTargets> targets;     ///< same order as sands
    bool representative = false;          ///< the lab data say they are representative, not measured
    std::string lab_note;
    Weights weights;
    SolverSettings solver;
    int workers = 2;
    double timeout_s = 600.0;
    std::filesystem::path out_dir, ledger;

    /// The bond law every run uses ([calibration] bond_model, or the base's [material] model).
    [[nodiscard]] BondModel bond_model() const { return base.material.bond.model; }

    /// Canonical text of everything that defines the problem's answer (not budget, workers
    /// or paths); its hash is the ledger's problem fingerprint.
    [[nodiscard]] std::string describe() const;
};

CalibrationProblem load_calibration_problem(const std::filesystem::path& toml_file);

/// Reads the targets of `sands` from a lab_results.json; InputError naming the file otherwise.
std::vector<SandTargets> read_lab_targets(const std::filesystem::path& json_file, const std::vector<std::string>& sands,
                                          bool* representative = nullptr, std::string* note = nullptr);

}  // namespace gradem::cal
