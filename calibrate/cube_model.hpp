#pragma once
// What the calibration evaluates: one virtual cube test of one sand's packing (seed) with one
// material. A run is a pure function of (sand, packing seed, material) -> outcome, so runs can
// go to threads here and to other machines later. Two models implement it:
//   DemCubeModel      the real thing: cached packings + exp::run_cube_test;
//   AnalyticCubeModel a cheap closed-form stand-in with the DEM model's homogeneity, used by
//                     the twin-experiment tests and for trying out a problem file in seconds.
#include <cstdint>
#include <filesystem>
#include <functional>
#include <initializer_list>
#include <memory>
#include <string>
#include <vector>

#include "common/named_enum.hpp"
#include "experiments/config/cube_config.hpp"
#include "experiments/virtual_tests/cube_test.hpp"

namespace gradem::cal {

/// Which virtual test a model runs: the cube compression test (what the calibration fits) or
/// the direct-tension test of the same specimen (experiments/virtual_tests/tension_test.hpp; its outcome's
/// peak is the tensile strength σt, its modulus the tensile chord modulus, tension positive).
enum class CubeTest { compression, tension };
constexpr EnumNameTable<CubeTest, 2> enum_name_table(CubeTest) {
    return {{{CubeTest::compression, "compression"}, {CubeTest::tension, "direct tension"}}};
}

struct RunRequest {
    std::size_t sand = 0;         ///< index into the problem's sands
    std::uint64_t seed = 1;       ///< packing seed (common random numbers: the same for every material)
    exp::MaterialParams material;
    CubeTest test = CubeTest::compression;  ///< which test of the specimen (the model must run it)
};

/// How a run ended (the ledger's `status` column).
enum class OutcomeStatus { ok, diverged, timeout, failed };
constexpr EnumNameTable<OutcomeStatus, 4> enum_name_table(OutcomeStatus) {
    return {{{OutcomeStatus::ok, "ok"}, {OutcomeStatus::diverged, "diverged"}, {OutcomeStatus::timeout, "timeout"}, {OutcomeStatus::failed, "failed"}}};
}

struct RunOutcome {
    OutcomeStatus status = OutcomeStatus::failed;
    std::string reason;             ///< why not ok (divergence, timeout, reduction failure)
    double modulus_pa = 0.0;        ///< ASTM C469 chord modulus of the gauge-strain curve [Pa]
    double peak_pa = 0.0;           ///< peak stress [Pa]
    double strain_at_peak = 0.0;    ///< gauge strain at the peak [-]
    double poisson = 0.0;           ///< Poisson's ratio (NaN if not measured)
    std::int64_t particles = 0, bonds = 0, steps = 0;
    double wall_seconds = 0.0;
    std::vector<double> curve_strain, curve_stress_pa;  ///< thinned gauge-strain curve for reports
    [[nodiscard]] bool ok() const { return status == OutcomeStatus::ok; }
};

/// `by_sand[sand]` when given and not empty, else `common`.
inline const std::vector<std::uint64_t>& sand_seeds_or(const std::vector<std::vector<std::uint64_t>>& by_sand,
                                                       const std::vector<std::uint64_t>& common, std::size_t sand) {
    return sand < by_sand.size() && !by_sand[sand].empty() ? by_sand[sand] : common;
}

/// The packing seeds a model prepares: the same list for every sand, or a sand's own list
/// (CalibrationProblem::seeds_of). Built implicitly from one list (every sand).
struct PackingSeeds {
    std::vector<std::uint64_t> common;                ///< every sand's, unless it has its own
    std::vector<std::vector<std::uint64_t>> by_sand;  ///< index = sand; an empty list: `common`
    PackingSeeds() = default;
    PackingSeeds(std::vector<std::uint64_t> seeds) : common(std::move(seeds)) {}  // NOLINT: implicit on purpose
    PackingSeeds(std::initializer_list<std::uint64_t> seeds) : common(seeds) {}
    [[nodiscard]] const std::vector<std::uint64_t>& of(std::size_t sand) const { return sand_seeds_or(by_sand, common, sand); }
};

class CubeModel {
public:
    virtual ~CubeModel() = default;
    /// Makes (or loads) everything the runs need, e.g. packings, with `workers` threads.
    /// `log` receives one line per prepared case.
    virtual void prepare(const PackingSeeds& seeds, int workers, const std::function<void(const std::string&)>& log) = 0;
    /// Loads what prepare() made for these seeds (e.g. rank 0's packings from the shared
    /// cache folder) and makes nothing: worker ranks of an MPI job call it. Throws a message
    /// naming what it could not load. Default (nothing to share): prepare on one thread.
    virtual void load_prepared(const PackingSeeds& seeds) { prepare(seeds, 1, {}); }
    /// One test; thread-safe; never throws for a simulation that fails (the status says so).
    /// `timeout_s` <= 0: no time limit.
    [[nodiscard]] virtual RunOutcome run(const RunRequest& request, double timeout_s) const = 0;
    /// Everything that defines the model besides the material (specimens, the tests it can run,
    /// code version): its identity (MPI ranks compare it, the problem fingerprint holds it).
    [[nodiscard]] virtual std::string fingerprint() const = 0;
    /// Everything that defines the runs of `test` besides the material: part of every ledger
    /// key of such a run. A model that cannot run `test` throws std::logic_error.
    [[nodiscard]] virtual std::string run_fingerprint(CubeTest test) const = 0;
};

/// The real model for the named sands of the base cube config's dataset: the compression test,
/// and with `tension` also the direct-tension test with the [tension] table of base.file
/// (InputError if it is bad).
std::unique_ptr<CubeModel> make_dem_model(const exp::CubeConfig& base, const std::vector<std::string>& sands,
                                          bool tension = false);

/// The analytic stand-in (see analytic_model.cpp for its equations); it runs both tests.
/// `diverge_above_gpa` > 0 makes every run with E* above it report a divergence (for the
/// failure tests).
std::unique_ptr<CubeModel> make_analytic_model(std::size_t sands, double noise = 0.003, double diverge_above_gpa = 0.0);

/// The exact text of the material's fields (hex floats), for keys and fingerprints.
std::string material_key(const exp::MaterialParams& m);

}  // namespace gradem::cal
