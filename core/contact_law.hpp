#pragma once
// Linear contact with Coulomb slip: the "linear" part of PFC's linearpbond (physics.md §1),
// Cundall & Strack (1979). Normal force in absolute mode, compression positive:
//     F_n = k_n max(0, -g);
// shear force incremental, stored as the force on B and carried into the current contact plane:
//     F_s <- rot(F_s) - k_s dU_s,  |F_s| <= mu F_n (slip).
// A contact with a gap carries nothing (F_n = 0 caps F_s at 0), bonded or not.
#include "core/pair_kinematics.hpp"

namespace gradem {

/// Deformability method (PFC 5+): k_n = A E*/L, A = pi min(R)^2, L = R_A + R_B.
inline double contact_normal_stiffness(double effective_modulus, double ra, double rb) {
    const double r = ra < rb ? ra : rb;
    return kPi * r * r * effective_modulus / (ra + rb);
}

/// Ball-facet form: k_n = pi R E* (r = L = R).
inline double wall_normal_stiffness(double effective_modulus, double r) {
    return kPi * r * effective_modulus;
}

struct LinearContactResult {
    double normal_force = 0.0;  ///< F_n >= 0, compression [N]
    Vec3 shear_force;           ///< F_s on B, in the contact plane [N]
    bool sliding = false;
    double strain_energy = 0.0; ///< ½ F_n²/k_n + ½ |F_s|²/k_s [J]
    double slip_energy = 0.0;   ///< energy dissipated by slip over this step [J], >= 0
};

/// One step of the linear law. `rotated_shear` is the stored shear force already carried into
/// the current plane; du_shear the shear displacement increment of B relative to A.
inline LinearContactResult linear_contact(double kn, double ks, double friction, double gap,
                                          const Vec3& rotated_shear, const Vec3& du_shear) {
    LinearContactResult out;
    if (gap >= 0.0) return out;
    out.normal_force = -kn * gap;
    Vec3 fs = rotated_shear - ks * du_shear;
    const double limit = friction * out.normal_force;
    const double fs2 = norm2(fs);
    if (fs2 > limit * limit) {
        fs = (limit / std::sqrt(fs2)) * fs;
        out.sliding = true;
        // Work of the shear force on dU_s (trapezoid) minus the change of stored shear energy.
        const double work_done_on_spring = -0.5 * dot(rotated_shear + fs, du_shear);
        out.slip_energy = work_done_on_spring - 0.5 * (norm2(fs) - norm2(rotated_shear)) / ks;
    }
    out.shear_force = fs;
    out.strain_energy = 0.5 * out.normal_force * out.normal_force / kn + 0.5 * norm2(fs) / ks;
    return out;
}

}  // namespace gradem
