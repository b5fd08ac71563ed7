// What every cube model shares: the exact keys of a material.
#include "calibrate/cube_model.hpp"

#include <cstdio>

#include "experiments/config/material_table.hpp"

namespace gradem::cal {

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
    // Another bond law than the parallel bond: its name and every table row of its own, so a
    // parallel-bond run is never served for another model (parallel-bond keys are unchanged).
    std::string key = buf;
    // Explicit paste: the interfacial-zone factors (calibration parameters); appended only when
    // they differ from 1, so a paste run with factors 1 has the key it has without them (paste
    // ledgers written before the factors joined the key stay valid).
    const auto& f = m.families;
    if (f.itz_strength_factor != 1.0 || f.itz_modulus_factor != 1.0) {
        std::snprintf(buf, sizeof buf, " itz_s=%a itz_m=%a", f.itz_strength_factor, f.itz_modulus_factor);
        key += buf;
    }
    if (b.model == BondModel::parallel_bond) return key;
    key += std::string(" model=") + bond_model_name(b.model);
    for (const exp::MaterialParameter& p : exp::material_table()) {
        if (!p.in_config || !p.applies_to(b.model) || p.applies_to(BondModel::parallel_bond)) continue;
        if (p.integer) std::snprintf(buf, sizeof buf, " %.*s=%lld", static_cast<int>(p.key.size()), p.key.data(),
                                     static_cast<long long>(p.get_int(m)));
        else std::snprintf(buf, sizeof buf, " %.*s=%a", static_cast<int>(p.key.size()), p.key.data(), p.get(m));
        key += buf;
    }
    return key;
}

}  // namespace gradem::cal
