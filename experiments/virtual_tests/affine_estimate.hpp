#pragma once
// Affine (Voigt) estimate of the elastic moduli of a bonded packing (docs/virtual_tests.md
// "A bound on the modulus"), summed
// over its actual pairs instead of assuming equal spheres: with the normal and tangential
// stiffness of every pair (linear contact where the grains overlap, plus the parallel bond where
// one is installed: k_N = k_n + k̄_n Ā, k_T = k_s + k̄_s Ā) and its branch length l,
//     K = (1 / 9V) Σ k_N l²,   G = (1 / 30V) Σ (2 k_N + 3 k_T) l²,   E = 9KG / (3K + G).
// Affine deformation ignores non-affine relaxation, so it is an upper bound for the modulus of
// the real packing; measured moduli typically lie at 0.5-1 of it.
#include "experiments/virtual_tests/cube_test.hpp"

namespace gradem::exp {

struct AffineModuli {
    double bulk = 0.0, shear = 0.0, youngs = 0.0, poisson = 0.0;  ///< [Pa], [Pa], [Pa], [-]
    std::size_t bonded_pairs = 0, contacts = 0;
};

AffineModuli affine_moduli(const Packing& packing, const MaterialParams& material);

}  // namespace gradem::exp
