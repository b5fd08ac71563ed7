#pragma once
// Rigid planar walls (platens). A wall is the plane {x : n.(x - p) = 0}; particles live on the
// side n.(x - p) > 0. It moves with a prescribed velocity and reports the reaction: the sum of
// the forces the particles exert on it. Wall-particle contacts use the linear law with the
// ball-facet stiffness k_n = pi R E*_w (docs/model.md "Linear contact"), the wall playing particle A.
#include <cstdint>
#include <string>

#include "core/params.hpp"
#include "core/vec3.hpp"

namespace gradem {

struct Wall {
    std::string name;         ///< for output ("top", "bottom", ...)
    Vec3 normal{0, 0, 1};     ///< unit normal pointing towards the particles
    Vec3 point;               ///< a point of the plane [m]
    Vec3 velocity;            ///< prescribed velocity [m/s]
    WallContactParams contact;
    Vec3 reaction;            ///< force exerted by the particles on the wall, last step [N]
    Vec3 displacement;        ///< total displacement since creation [m]
};

/// Contact of particle `particle` with wall `wall`; persistent shear history.
struct WallContact {
    std::int32_t particle = -1;
    std::int32_t wall = -1;
    Vec3 shear_force;         ///< on the particle [N]
};

}  // namespace gradem
