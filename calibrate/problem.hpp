#pragma once
// A calibration problem, read from a TOML file (calibrate/README.md documents every key):
//
//   [calibration] base (a cube config: specimen size rule, genesis, start material, test),
//                 mode = "joint" | "per_sand" | "study", sands, calibrate_on, seeds, sand_seeds
//                 (a sand's own seeds), model,
//                 bond_model (overrides the base's [material] model; kept in base.material),
//                 edge_mm, paste_diameter_mm (override the base's cube edge and paste size)
//   [targets]     lab_results (the lab_results.json of `gradem lab`), modulus/peak/strain weights,
//                 tension = "none" | "lab" | "assumed_ratio" with tension_ratio, tension_ratio_low/high,
//                 tension_tolerance, tension_weight, tension_basis (the direct-tension target)
//   [parameters.<name>]  free, start, lower, upper, scale = "log" | "linear"
//   [solver]      method, max_runs, tolerance, fd_step, homogeneity_tolerance, penalty, seed
//   [run]         workers, timeout_s
//   [scale_up]    edge_mm, seeds (larger specimens on which the scales are set after the fit)
//   [validation]  edge_mm, seeds (specimens the fit never saw, run at its result)
//   [output]      dir, ledger
//
// Targets are never typed in: they are the per-sand mean and standard deviation of the chord
// modulus, peak stress and strain at peak in the lab results file, and for the direct-tension
// strength either the lab's (tensile tests reduced to a direct-tension equivalent) or the lab's
// peak stress over an assumed σc/σt, marked as assumed wherever it is shown. Every error is a
// common::InputError naming the file, line and key.
#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "calibrate/cube_model.hpp"
#include "calibrate/parameters.hpp"
#include "common/named_enum.hpp"
#include "experiments/config/cube_config.hpp"

namespace gradem::cal {

/// [calibration] mode. Names: common/named_enum.hpp (to_string, parse_enum).
enum class Mode { joint, per_sand, study };
constexpr EnumNameTable<Mode, 3> enum_name_table(Mode) {
    return {{{Mode::joint, "joint"}, {Mode::per_sand, "per_sand"}, {Mode::study, "study"}}};
}

/// [calibration] model: what answers a run. dem: a cube test in the engine; analytic: a
/// closed-form stand-in with the DEM model's homogeneity, in milliseconds (calibrate/analytic_model.cpp:
/// for trying a problem file and for tests).
enum class RunModel { dem, analytic };
constexpr EnumNameTable<RunModel, 2> enum_name_table(RunModel) {
    return {{{RunModel::dem, "dem"}, {RunModel::analytic, "analytic"}}};
}

/// [solver] method (calibrate/solvers/solver.cpp dispatches on it).
enum class Method { scaling, bobyqa, sbplx, cobyla, crs2, direct, ceres };
constexpr EnumNameTable<Method, 7> enum_name_table(Method) {
    return {{{Method::scaling, "scaling"},
             {Method::bobyqa, "bobyqa"},
             {Method::sbplx, "sbplx"},
             {Method::cobyla, "cobyla"},
             {Method::crs2, "crs2"},
             {Method::direct, "direct"},
             {Method::ceres, "ceres"}}};
}

/// Mean and standard deviation of one lab quantity over a sand's cubes (SI).
struct TargetStat {
    double mean = 0.0, std = 0.0;
    int n = 0;
};

struct SandTargets {
    std::string name;
    TargetStat modulus, peak, strain;  ///< chord modulus [Pa], peak stress [Pa], strain at peak [-]
    TargetStat tension;                ///< direct-tension strength σt [Pa] (n = 0: assumed or not fitted)
};

/// A sand's targets, in this order everywhere (residual vectors, tables): the compression
/// test's three, then the direct-tension strength when the problem fits it.
enum class Quantity { modulus, peak, strain, tension };
inline constexpr Quantity kQuantities[] = {Quantity::modulus, Quantity::peak, Quantity::strain};
inline constexpr int kQuantityCount = 4;  ///< slots of per-quantity arrays (the tension one may stay empty)
/// The quantity's key in summary.json, study.json and the ledger.
constexpr EnumNameTable<Quantity, 4> enum_name_table(Quantity) {
    return {{{Quantity::modulus, "modulus"},
             {Quantity::peak, "peak_stress"},
             {Quantity::strain, "strain_at_peak"},
             {Quantity::tension, "tensile_strength"}}};
}
const TargetStat& target_of(const SandTargets& t, Quantity q);

/// Where the direct-tension target comes from ([targets] tension).
enum class TensionSource { none, lab, assumed_ratio };
constexpr EnumNameTable<TensionSource, 3> enum_name_table(TensionSource) {
    return {{{TensionSource::none, "none"}, {TensionSource::lab, "lab"}, {TensionSource::assumed_ratio, "assumed_ratio"}}};
}

/// The direct-tension target: the lab's strength (lab_results.json `tensile_strength_mpa`,
/// splitting or flexural tests converted to direct tension by `gradem lab`), or σt = σc,lab / ratio
/// with an assumed ratio. Met: lab, |σt_sim/σt_lab − 1| <= tolerance; assumed, the simulated
/// ratio σc,sim/σt,sim within [ratio_low, ratio_high].
struct TensionTarget {
    TensionSource source = TensionSource::none;
    double ratio = 10.0, ratio_low = 8.0, ratio_high = 12.0;  ///< σc/σt assumed, and the band that counts as met [-]
    double tolerance = 0.10;                                  ///< lab source: relative error that counts as met [-]
    std::string basis;                                        ///< where the assumed ratio comes from (shown as such)
    [[nodiscard]] bool fitted() const { return source != TensionSource::none; }
    [[nodiscard]] bool assumed() const { return source == TensionSource::assumed_ratio; }
};

struct Weights {
    double modulus = 1.0, peak = 1.0, strain = 0.2, tension = 1.0;
    [[nodiscard]] double of(Quantity q) const {
        return q == Quantity::modulus ? modulus : q == Quantity::peak ? peak : q == Quantity::strain ? strain : tension;
    }
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

/// A set of specimens besides the fitted ones: a cube edge and packing seeds.
///   [validation]  after the fit, its result is run on cubes of another edge and on packing
///                 seeds the fit never saw; their errors are reported first;
///   [scale_up]    after the fit, its result is run once on (larger) cubes and E* and the
///                 strengths are set there by the homogeneity (docs/calibration.md "Scales set on
///                 larger specimens"): the shape is searched where runs are cheap, the scales
///                 where the specimen is closer to converged.
/// Neither is part of the problem's identity (describe()): changing them keeps the ledger's
/// fitted runs (their own runs are keyed by their own specimens).
struct SpecimenSetSpec {
    double edge = 0.0;                 ///< [m] cube edge of the set's specimens (0: the fit's)
    std::vector<std::uint64_t> seeds;  ///< their packing seeds (empty: no such set)
    /// The seeds whose compression test has its direct-tension companion ([validation]
    /// tension_seeds; empty: every seed): σt scatters a few per cent between cubes, so fewer
    /// cubes test it than the strain at peak needs.
    std::vector<std::uint64_t> tension_seeds;
    [[nodiscard]] bool enabled() const { return !seeds.empty(); }
    /// The seeds whose direct-tension test runs (when tension is a target): tension_seeds, or every seed.
    [[nodiscard]] const std::vector<std::uint64_t>& seeds_with_tension() const { return tension_seeds.empty() ? seeds : tension_seeds; }
};
using ValidationSpec = SpecimenSetSpec;

struct CalibrationProblem {
    std::filesystem::path file;
    std::filesystem::path base_file;      ///< the base cube config ([calibration] base)
    exp::CubeConfig base;
    RunModel model = RunModel::dem;       ///< what answers a run: the DEM, or the analytic stand-in
    Mode mode = Mode::joint;
    std::vector<std::string> sands;
    std::string calibrate_on;             ///< study mode: the sand calibrated on
    std::vector<std::uint64_t> seeds = {1, 2};   ///< packing seeds of every sand without its own
    std::vector<std::vector<std::uint64_t>> sand_seeds;  ///< a sand's own seeds (index = sand; empty: `seeds`)
    /// The seeds whose compression runs have their tension companion when tension is a target
    /// (empty: every seed; [calibration] tension_seeds, each a seed of every sand; a
    /// validation's tension_seeds: validation_problem()).
    std::vector<std::uint64_t> tension_seeds;
    std::vector<ParameterSpec> parameters;
    std::filesystem::path lab_results;
    std::vector<SandTargets> targets;     ///< same order as sands
    TensionTarget tension;                ///< the direct-tension target (none by default)
    SpecimenSetSpec scale_up;             ///< where the scales are set after the fit (none by default)
    ValidationSpec validation;            ///< the validation specimens (none by default)
    bool representative = false;          ///< the lab data say they are representative, not measured
    std::string lab_note;
    Weights weights;
    SolverSettings solver;
    int workers = 2;
    double timeout_s = 600.0;
    std::filesystem::path out_dir, ledger;

    /// The packing seeds of sand `sand` ([calibration] sand_seeds, else seeds).
    [[nodiscard]] const std::vector<std::uint64_t>& seeds_of(std::size_t sand) const;
    /// Every sand's seeds, as CubeModel::prepare takes them.
    [[nodiscard]] PackingSeeds packing_seeds() const;
    /// The runs of one test at one point: the seeds of `of_sands` (default: every sand) summed.
    [[nodiscard]] int runs_per_test(const std::vector<std::size_t>& of_sands) const;
    [[nodiscard]] int runs_per_test() const;

    /// Whether the compression run of packing seed `seed` has its tension companion (tension_seeds).
    [[nodiscard]] bool runs_tension_on(std::uint64_t seed) const;
    /// The seeds of sand `sand` whose tension test runs (runs_tension_on).
    [[nodiscard]] std::vector<std::uint64_t> tension_seeds_of(std::size_t sand) const;
    /// The tension runs at one point: tension_seeds_of summed over `of_sands`.
    [[nodiscard]] int tension_runs_per_test(const std::vector<std::size_t>& of_sands) const;
    [[nodiscard]] int tension_runs_per_test() const;
    /// 0, 1, ..., sands.size() - 1: every sand of the problem.
    [[nodiscard]] std::vector<std::size_t> sand_indices() const;

    /// The quantities each sand's residuals hold: kQuantities, then tension when it is fitted.
    [[nodiscard]] std::vector<Quantity> fitted_quantities() const;

    /// A tension target that is reported but does not move the fit (tension_weight 0): the
    /// solver's evaluations run compression alone, and the tension tests run once, at the result.
    [[nodiscard]] bool tension_at_result_only() const { return tension.fitted() && weights.tension == 0.0; }

    /// The bond law every run uses ([calibration] bond_model, or the base's [material] model).
    [[nodiscard]] BondModel bond_model() const { return base.material.bond.model; }

    /// Canonical text of everything that defines the problem's answer (not budget, workers
    /// or paths); its hash is the ledger's problem fingerprint.
    [[nodiscard]] std::string describe() const;
};

CalibrationProblem load_calibration_problem(const std::filesystem::path& toml_file);

/// The problem as its validation runs see it: the validation edge and seeds, no validation of
/// its own (the same targets, parameters, ledger and output folder).
CalibrationProblem validation_problem(const CalibrationProblem& problem);
/// The problem as its scale-up runs see it: the scale-up edge and seeds, likewise.
CalibrationProblem scale_up_problem(const CalibrationProblem& problem);

/// Reads the targets of `sands` from a lab_results.json; InputError naming the file otherwise.
std::vector<SandTargets> read_lab_targets(const std::filesystem::path& json_file, const std::vector<std::string>& sands,
                                          bool* representative = nullptr, std::string* note = nullptr);

/// The direct-tension strength of each of `sands` in a lab_results.json (`tensile_strength_mpa`,
/// SI), nullopt for a sand without tensile tests; InputError naming the file otherwise.
std::vector<std::optional<TargetStat>> read_lab_tensile_targets(const std::filesystem::path& json_file,
                                                                const std::vector<std::string>& sands);

}  // namespace gradem::cal
