#include "core/particles.hpp"

#include <cmath>
#include <sstream>

namespace gradem {

std::int32_t ParticleSet::add(const Vec3& x, double r, double density, std::uint8_t family_tag) {
    const double m = density * (4.0 / 3.0) * kPi * r * r * r;
    position.push_back(x);
    velocity.push_back({});
    spin.push_back({});
    force.push_back({});
    torque.push_back({});
    radius.push_back(r);
    mass.push_back(m);
    inertia.push_back(0.4 * m * r * r);
    flags.push_back(0);
    family.push_back(family_tag);
    return static_cast<std::int32_t>(radius.size() - 1);
}

void ParticleSet::set_radius(std::size_t i, double r) {
    const double ratio = r / radius[i];
    const double mass_ratio = ratio * ratio * ratio;
    radius[i] = r;
    mass[i] *= mass_ratio;
    inertia[i] *= mass_ratio * ratio * ratio;
}

namespace {
template <class T>
void apply_order(std::vector<T>& v, const std::vector<std::int32_t>& order) {
    std::vector<T> out(order.size());
    for (std::size_t k = 0; k < order.size(); ++k) out[k] = v[static_cast<std::size_t>(order[k])];
    v.swap(out);
}
}  // namespace

void ParticleSet::permute(const std::vector<std::int32_t>& order) {
    apply_order(position, order);
    apply_order(velocity, order);
    apply_order(spin, order);
    apply_order(force, order);
    apply_order(torque, order);
    apply_order(radius, order);
    apply_order(mass, order);
    apply_order(inertia, order);
    apply_order(flags, order);
    apply_order(family, order);
}

void ParticleSet::scale_density(double factor) {
    for (std::size_t i = 0; i < size(); ++i) {
        mass[i] *= factor;
        inertia[i] *= factor;
    }
}

std::optional<std::string> ParticleSet::invalid_reason() const {
    for (std::size_t i = 0; i < size(); ++i) {
        std::ostringstream out;
        if (!(radius[i] > 0.0 && std::isfinite(radius[i]))) {
            out << "particle " << i << ": radius = " << radius[i] << " violates > 0";
            return out.str();
        }
        if (!(mass[i] > 0.0 && std::isfinite(mass[i])) || !(inertia[i] > 0.0)) {
            out << "particle " << i << ": mass = " << mass[i] << " violates > 0";
            return out.str();
        }
        if (!is_finite(position[i]) || !is_finite(velocity[i]) || !is_finite(spin[i])) {
            out << "particle " << i << ": position/velocity/spin is not finite";
            return out.str();
        }
    }
    return std::nullopt;
}

}  // namespace gradem
