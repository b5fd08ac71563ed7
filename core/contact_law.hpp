#pragma once
// Linear contact with Coulomb slip: the "linear" part of PFC's linearpbond (docs/model.md "Linear contact"),
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

/// Whether two spheres at centres xa, xb [m] with radii ra, rb [m] are apart: |xb - xa|² >= (ra + rb)².
/// The contact pass's open test; the slots rebuilt after a pass must use this same expression.
inline bool spheres_apart(const Vec3& xa, const Vec3& xb, double ra, double rb) {
    return norm2(xb - xa) >= (ra + rb) * (ra + rb);
}

/// F_n = k_n max(0, -g) as linear_contact() selects it [N]: -k_n g where the pair touches
/// (g < 0, or NaN: it computes on), else 0.
inline double linear_contact_normal_force(double kn, double gap) {
    const bool touching = !(gap >= 0.0);
    return touching ? -kn * gap : 0.0;
}

/// One step of the linear law. `rotated_shear` is the stored shear force already carried into
/// the current plane; du_shear the shear displacement increment of B relative to A.
/// Branch-free (every term computed, the cases selected after: the loop over pairs vectorises,
/// world_pairs.cpp); the selected values are those of the plain if/else form, bit for bit.
inline LinearContactResult linear_contact(double kn, double ks, double friction, double gap,
                                          const Vec3& rotated_shear, const Vec3& du_shear) {
    const bool touching = !(gap >= 0.0);  // as the old early return: a NaN gap computes on
    const double normal_force = -kn * gap;
    const Vec3 trial = rotated_shear - ks * du_shear;
    const double limit = friction * normal_force;
    const double trial2 = norm2(trial);
    const bool sliding = trial2 > limit * limit;
    const Vec3 slid = (limit / std::sqrt(trial2)) * trial;
    const Vec3 fs = select(sliding, slid, trial);
    // Work of the shear force on dU_s (trapezoid) minus the change of stored shear energy.
    const double work_done_on_spring = -0.5 * dot(rotated_shear + fs, du_shear);
    const double slip_energy = work_done_on_spring - 0.5 * (norm2(fs) - norm2(rotated_shear)) / ks;
    const double strain_energy = 0.5 * normal_force * normal_force / kn + 0.5 * norm2(fs) / ks;
    LinearContactResult out;
    out.normal_force = linear_contact_normal_force(kn, gap);
    out.shear_force = select(touching, fs, Vec3{});
    out.sliding = touching && sliding;
    out.strain_energy = touching ? strain_energy : 0.0;
    out.slip_energy = touching && sliding ? slip_energy : 0.0;
    return out;
}

}  // namespace gradem
