#include "experiments/virtual_tests/affine_estimate.hpp"

#include "core/bond_law.hpp"
#include "core/contact_law.hpp"
#include "core/neighbor_search.hpp"

namespace gradem::exp {

AffineModuli affine_moduli(const Packing& k, const MaterialParams& m) {
    double mean_r = 0.0;
    for (double r : k.radius) mean_r += r;
    mean_r /= static_cast<double>(k.radius.size());
    const double bond_gap = m.bond_gap(mean_r);
    std::vector<ParticlePair> pairs;
    make_cell_grid_search()->find_pairs(k.position, k.radius, bond_gap, pairs);
    double sum_normal = 0.0, sum_shear = 0.0;
    AffineModuli out;
    for (const ParticlePair& p : pairs) {
        const auto i = static_cast<std::size_t>(p.i), j = static_cast<std::size_t>(p.j);
        const double ra = k.radius[i], rb = k.radius[j];
        const double l = norm(k.position[j] - k.position[i]);
        double kn = 0.0, kt = 0.0;
        if (l < ra + rb) {
            kn += contact_normal_stiffness(m.contact.effective_modulus, ra, rb);
            kt += kn / m.contact.stiffness_ratio;
            ++out.contacts;
        }
        const BondSection s = bond_section(m.bond.radius_multiplier, ra, rb);
        const BondStiffness b = bond_stiffness(m.bond.effective_modulus, m.bond.stiffness_ratio, ra, rb);
        kn += b.normal * s.area;
        kt += b.shear * s.area;
        ++out.bonded_pairs;
        sum_normal += kn * l * l;
        sum_shear += (2.0 * kn + 3.0 * kt) * l * l;
    }
    const Vec3 e = k.box_hi - k.box_lo;
    const double volume = e.x * e.y * e.z;
    out.bulk = sum_normal / (9.0 * volume);
    out.shear = sum_shear / (30.0 * volume);
    out.youngs = 9.0 * out.bulk * out.shear / (3.0 * out.bulk + out.shear);
    out.poisson = (3.0 * out.bulk - 2.0 * out.shear) / (2.0 * (3.0 * out.bulk + out.shear));
    return out;
}

}  // namespace gradem::exp
