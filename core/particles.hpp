#pragma once
// Particles as structure-of-arrays: one std::vector per property, all the same length, grown
// only through add() so the arrays stay in sync. Spheres only. SI units.
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "core/vec3.hpp"

namespace gradem {

/// Per-particle flags (bit set).
enum ParticleFlag : std::uint8_t {
    kFixedVelocity = 1u << 0,  ///< translational velocity prescribed: forces do not move it
    kFixedSpin = 1u << 1,      ///< angular velocity prescribed
};

struct ParticleSet {
    std::vector<Vec3> position;  ///< centre [m]
    std::vector<Vec3> velocity;  ///< [m/s], half a step behind the position (leap-frog)
    std::vector<Vec3> spin;      ///< angular velocity [rad/s], half a step behind
    std::vector<Vec3> force;     ///< resultant contact + bond + wall force of the last step [N]
    std::vector<Vec3> torque;    ///< resultant moment about the centre of the last step [N m]
    std::vector<double> radius;  ///< [m]
    std::vector<double> mass;    ///< [kg]
    std::vector<double> inertia; ///< moment of inertia, 2/5 m R^2 for a solid sphere [kg m^2]
    std::vector<std::uint8_t> flags;  ///< ParticleFlag bits
    std::vector<std::uint8_t> family; ///< bond family (explicit paste: 0 sand, 1 paste); 0 by default

    [[nodiscard]] std::size_t size() const { return radius.size(); }

    /// Adds a solid sphere of the given density [kg/m^3] and bond family; returns its index.
    std::int32_t add(const Vec3& x, double r, double density, std::uint8_t family_tag = 0);

    /// Changes the radius of particle i, keeping its density (mass and inertia follow).
    void set_radius(std::size_t i, double r);

    /// Reorders every array by `order` (new index k holds old particle order[k]).
    void permute(const std::vector<std::int32_t>& order);

    /// Multiplies every mass and inertia by `factor` (density scaling).
    void scale_density(double factor);

    /// First invalid entry (non-positive radius or mass, non-finite state), if any.
    [[nodiscard]] std::optional<std::string> invalid_reason() const;
};

}  // namespace gradem
