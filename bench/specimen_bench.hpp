#pragma once
// gradem-bench --specimens: the bonded rows on a real specimen instead of the lattice packing.
// The specimen is a genesis packing of the study's pre-blended sand (Table 2) under the
// calibration cube's size rule (0.149 - 0.8 mm), its edge scaled from the 3.5 mm calibration
// cube (~4350 grains) so that about N grains are sampled, seed 1, in the order genesis gives it
// (Morton), cached in the packing cache (experiments/specimen/packing_cache.hpp). Bonds are installed as
// a calibration's cube test installs them (exp::bonded_cube_specimen: the bonding gap as a
// length, bond_gap_um), then the two platens close at a strain rate of 1/s.
#include <cstdint>
#include <filesystem>
#include <string>
#include <utility>
#include <vector>

#include "core/world.hpp"
#include "experiments/specimen/genesis.hpp"
#include "experiments/virtual_tests/material_params.hpp"

namespace gradem::bench {

/// One bonded set-up of a row: the law and the material keys set on it (config units, as
/// `--set` gives them), applied after the row's base material.
struct BondCase {
    BondModel model = BondModel::parallel_bond;
    std::vector<std::pair<std::string, double>> settings;  ///< material-table key, value
};

/// The bonding gap of the specimen rows unless bond_gap_um is set [um]: the parallel-bond
/// calibration's gap, for every law.
inline constexpr double kSpecimenGapUm = 70.0;

/// The genesis packing of about `grains` grains, from `cache_dir` or generated and saved there;
/// `seconds` receives the genesis time (0 when it came from the cache), `cached` whether it did.
exp::Packing specimen_packing(std::int64_t grains, const std::filesystem::path& cache_dir, double& seconds,
                              bool& cached);

/// The material of a specimen row: contact and bond E* 11 GPa, k_n/k_s 1.5, μ 0.5, σ̄_c 17 MPa,
/// c̄ 8.5 MPa (cv 0.2: the parallel-bond calibration's start point), every law's other
/// parameters at their defaults, a 70 um bonding gap; then the case's settings. Invalid: a
/// UsageError naming the rule.
exp::MaterialParams specimen_material(const BondCase& c);

/// The packing bonded as a cube test does with material `m`, between the platens, closing at a
/// strain rate of 1/s.
World specimen_world(const exp::Packing& packing, const exp::MaterialParams& m);

}  // namespace gradem::bench
