#pragma once
// The small specimen of the experiments tests: Van Buren sand (its Table 2 curve), grains of
// 0.3–1.18 mm in a 3.6 mm cube, packing seed 5 (a few hundred grains: small and fast), made
// once per test executable; and the material the cube and tension tests bond it with.
#include "experiments/virtual_tests/cube_test.hpp"
#include "experiments/specimen/genesis.hpp"
#include "study_curves.hpp"

namespace gradem::test {

inline exp::SpecimenSpec small_spec() {
    exp::SpecimenSpec spec;
    spec.size_rule.min_diameter = 0.3e-3;
    spec.size_rule.max_diameter = 1.18e-3;
    spec.genesis.edge = 3.6e-3;
    spec.genesis.max_steps = 60000;
    spec.seed = 5;
    return spec;
}

inline const exp::Packing& small_packing() {
    static const exp::Packing packing = exp::generate_packing(van_buren_curve(), small_spec());
    return packing;
}

/// E* = Ē* = 10 GPa × modulus_scale; σ̄c = 5 ± 1 MPa and c̄ = 10 ± 2 MPa, × strength_scale.
inline exp::MaterialParams small_material(double modulus_scale = 1.0, double strength_scale = 1.0) {
    exp::MaterialParams m;
    m.contact.effective_modulus = m.bond.effective_modulus = 10.0e9 * modulus_scale;
    m.bond.tensile_strength_mean = 5.0e6 * strength_scale;
    m.bond.tensile_strength_std = 1.0e6 * strength_scale;
    m.bond.cohesion_mean = 10.0e6 * strength_scale;
    m.bond.cohesion_std = 2.0e6 * strength_scale;
    return m;
}

}  // namespace gradem::test
