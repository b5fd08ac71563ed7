// What every cube model shares: run status names and the exact keys of a material.
#include "calibrate/cube_model.hpp"

#include <cstdio>

namespace gradem::cal {

const char* to_string(RunStatus s) {
    switch (s) {
        case RunStatus::ok: return "ok";
        case RunStatus::diverged: return "diverged";
        case RunStatus::timeout: return "timeout";
        case RunStatus::failed: return "failed";
    }
    return "failed";
}

RunStatus run_status_from(const std::string& t) {
    if (t == "ok") return RunStatus::ok;
    if (t == "diverged") return RunStatus::diverged;
    if (t == "timeout") return RunStatus::timeout;
    return RunStatus::failed;
}

std::string material_key(const exp::MaterialParams& m) {
    const BondParams& b = m.bond;
    const ContactParams& c = m.contact;
    char buf[1024];
    std::snprintf(buf, sizeof buf,
                  "E*=%a k*=%a mu=%a Eb=%a kb=%a lam=%a beta=%a st=%a sts=%a c=%a cs=%a phi=%a bseed=%llu gapf=%a gapa=%a "
                  "muw=%a damp=%a",
                  c.effective_modulus, c.stiffness_ratio, c.friction, b.effective_modulus, b.stiffness_ratio,
                  b.radius_multiplier, b.moment_factor, b.tensile_strength_mean, b.tensile_strength_std, b.cohesion_mean,
                  b.cohesion_std, b.friction_angle_deg, static_cast<unsigned long long>(b.seed), m.bond_gap_fraction,
                  m.bond_gap_absolute, m.platen_friction, m.damping);
    std::string key = buf;
    // The bond law and its shape parameters; absent for parallel bonds, so ledger keys of
    // parallel-bond runs stay what they were before the other laws existed.
    if (b.model != BondModel::parallel_bond) {
        std::snprintf(buf, sizeof buf, " law=%s soft=%a,%a flat=%d,%d,%a", bond_model_name(b.model), b.soft.softening_factor,
                      b.soft.cut_fraction, static_cast<int>(b.flat.radial_elements), static_cast<int>(b.flat.angular_elements),
                      b.flat.residual_friction);
        key += buf;
    }
    return key;
}

std::string fnv1a_hex(const std::string& text) {
    std::uint64_t h = 1469598103934665603ull;
    for (unsigned char ch : text) {
        h ^= ch;
        h *= 1099511628211ull;
    }
    char buf[17];
    std::snprintf(buf, sizeof buf, "%016llx", static_cast<unsigned long long>(h));
    return buf;
}

}  // namespace gradem::cal
