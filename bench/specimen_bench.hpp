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

#include "core/world.hpp"
#include "experiments/specimen/genesis.hpp"

namespace gradem::bench {

/// One bonded set-up of a row: the law, its bonding gap and (flat joint) the bonded fraction
/// (the rest slit: no gapped joints).
struct BondCase {
    BondModel model = BondModel::parallel_bond;
    double gap_um = 0.0;            ///< bonding gap [um]; 0: the packing's own (lattice: its coordination gap)
    double bonded_fraction = 1.0;   ///< flat joint φ_B [-]
};

/// The default bonding gap of a law on a specimen [um], as the calibrated configs use it:
/// 70 for the parallel and soft bond, 20 for the flat joint.
double default_gap_um(BondModel model);

/// The genesis packing of about `grains` grains, from `cache_dir` or generated and saved there;
/// `seconds` receives the genesis time (0 when it came from the cache), `cached` whether it did.
exp::Packing specimen_packing(std::int64_t grains, const std::filesystem::path& cache_dir, double& seconds,
                              bool& cached);

/// The bond parameters of a bench row (E-bar 11 GPa, sigma-bar_c 17 MPa, c-bar 8.5 MPa, cv 0.2:
/// the parallel-bond calibration's start point; flat joint N_r 1, N_alpha 4, the rest slit).
BondParams bench_bond_params(const BondCase& c);

/// The packing bonded as a cube test does, between the platens, closing at a strain rate of 1/s.
World specimen_world(const exp::Packing& packing, const BondCase& c);

}  // namespace gradem::bench
