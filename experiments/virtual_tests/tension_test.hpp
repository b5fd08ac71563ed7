#pragma once
// The virtual direct-tension test of the cube specimen (the same packing, material, bonds and
// settling as the compression test, cube_test.hpp; docs/virtual_tests.md "Direct tension",
// tension positive). As PFC's direct-tension test, the ends are held by grips of grains instead of
// glued platens:
//   1. the packing is bonded and settled between the fixed platens exactly as for compression
//      (cube_specimen.hpp);
//   2. the grips: at each end face, every grain whose centre lies within the grip depth of the
//      face, and every grain touching the face (it carried the platen), is given a prescribed
//      velocity (kFixedVelocity) and zero spin (kFixedSpin): each grip moves as one rigid body
//      with its platen, with no rotation. The platen walls are then removed (only grip grains
//      touched them, so the free specimen is not disturbed);
//   3. the grips move apart at the test strain rate after the half-cosine ramp (the loading loop
//      and stop rules of axial_loading.hpp); the end load is the reaction on each grip, the sum
//      of the forces its grains carry (internal grip pairs cancel, so this is the force the free
//      specimen exerts on the grip); stress = load / initial cross-section, tension positive;
//      gauge strain = the extensometer's, extension positive; lateral strain expansion positive
//      (negative in tension);
//   4. the tension curve is reduced by the lab's reduce_curve (peak = tensile strength σt, strain
//      at peak, chord and tangent moduli, Poisson's ratio; no Popovics fit: that is a
//      compression model). The chord is ASTM C469's (50 µε to 40 % of the peak) while the 40 %
//      point lies above 200 µε; below, ε1 = ε(S2)/4 (about 10 % of the peak on a linear curve),
//      since a tensile curve may reach 40 % of its peak before 50 µε.
// Physics expected: bonds carry tension and compression alike, contacts only compression. In
// compression the touching bonded pairs stiffen twice (bond + contact); in tension the contacts
// along the axis open at strains of the order (locked-in stress)/E, so the tensile modulus lies
// below the compression chord modulus, near the bond-only value; with negligible contact
// stiffness the two moduli agree.
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "experiments/virtual_tests/cube_test.hpp"

namespace gradem::exp {

struct TensionTestSpec {
    CubeTestSpec test;                  ///< loading (rate, ramp, stop rule), gauges and settling: as in compression
    double grip_depth_fraction = 0.1;   ///< grains with centres within this x edge of an end face are gripped [-]
    [[nodiscard]] std::optional<std::string> invalid_reason() const;
};

struct TensionTestResult {
    CubeTestResult cube;                 ///< curve, reduction, cracks and run facts, all tension positive
    double grip_depth = 0.0;             ///< [m]
    std::size_t grip_grains_bottom = 0, grip_grains_top = 0;
    double grip_reach = 0.0;             ///< deepest grip-grain centre from its end face [m]
    double grip_slip = 0.0;              ///< max over recorded points and grip grains of |displacement - its grip's| [m]
    double grip_spin = 0.0;              ///< max |spin| of a grip grain over recorded points [rad/s]
    double chord_lower_strain = 50e-6;   ///< ε1 of the chord modulus used [-]
    [[nodiscard]] bool diverged() const { return cube.diverged(); }
};

/// Runs the whole test. `progress` (optional) sees every recorded curve point. Throws
/// std::invalid_argument for invalid inputs, and when a grip reaches into a gauge slab.
TensionTestResult run_tension_test(const Packing& packing, const MaterialParams& material, const TensionTestSpec& spec,
                                   const ProgressCallback& progress = {});

/// The grip grains of a packing: indices of the grains at the bottom and top end faces.
struct GripSelection {
    std::vector<std::int32_t> bottom, top;
    double depth = 0.0;  ///< [m]
    double reach = 0.0;  ///< deepest grip-grain centre from its end face [m]
};
GripSelection select_grips(const Packing& packing, double grip_depth_fraction);

}  // namespace gradem::exp
