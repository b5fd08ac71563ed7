// Phase 5: gather and leap-frog integration with Cundall local damping (docs/model.md
// "Time integration"):
//     v(t+½) = v(t-½) + dt (F(t) + F_d(t)) / m,   x(t+dt) = x(t) + dt v(t+½),
//     w(t+½) = w(t-½) + dt (M(t) + M_d(t)) / I    (spheres: no gyroscopic term),
// plus wall motion, wall reactions and the divergence checks.
#include <algorithm>
#include <cmath>
#include <sstream>

#include "core/parallel.hpp"
#include "core/world.hpp"

namespace gradem {
namespace {

// Branch-free (velocity signs are random, a branch mispredicts half the time): +1, -1 or 0,
// exactly the values of the ternary form, so the damping force is bitwise the same.
inline double sign(double v) { return static_cast<double>(v > 0.0) - static_cast<double>(v < 0.0); }

// Cundall local non-viscous damping, component-wise: F_d,k = -alpha |F_k| sign(v_k)
// (Cundall's local damping; YADE NewtonIntegrator::cundallDamp1st), v the latest half-step velocity.
inline Vec3 local_damping(const Vec3& f, const Vec3& v, double alpha) {
    return {-alpha * std::fabs(f.x) * sign(v.x), -alpha * std::fabs(f.y) * sign(v.y),
            -alpha * std::fabs(f.z) * sign(v.z)};
}

struct BlockSums {
    double kinetic = 0, damping = 0, boundary = 0, max_disp2 = 0;
    std::int64_t runaway = -1;
};

}  // namespace

// Each particle sums the outputs of its pairs and wall contacts, in slot order.
void World::gather_forces() {
    const auto n = static_cast<std::int64_t>(particles_.size());
    ParticleSet& P = particles_;
    for_each_block(n, [&](std::int64_t begin, std::int64_t end, std::int64_t) {
        for (std::int64_t p = begin; p < end; ++p) {
            const auto i = static_cast<std::size_t>(p);
            Vec3 f, t;
            for (std::int32_t e = incidence_start_[i]; e < incidence_start_[i + 1]; ++e) {
                const Incidence inc = incidence_[static_cast<std::size_t>(e)];
                const PairOutput& o = pair_out_[static_cast<std::size_t>(inc.slot)];
                if (inc.partner >= 0) {  // this particle is j
                    f += o.force_j;
                    t += o.torque_j;
                } else {                 // this particle is i
                    const Vec3 d = P.position[static_cast<std::size_t>(~inc.partner)] - P.position[i];
                    f -= o.force_j;
                    t -= o.torque_j + cross(d, o.force_j);
                }
            }
            for (std::int32_t w = wall_start_[i]; w < wall_start_[i + 1]; ++w) {
                f += wall_out_[static_cast<std::size_t>(w)].force;
                t += wall_out_[static_cast<std::size_t>(w)].torque;
            }
            P.force[i] = f;
            P.torque[i] = t;
        }
    });
}

World::IntegrationSums World::integrate() {
    const auto n = static_cast<std::int64_t>(particles_.size());
    std::vector<BlockSums> partial(static_cast<std::size_t>(block_count(n)));
    const double dt = dt_, alpha = sim_.local_damping;
    ParticleSet& P = particles_;
    for_each_block(n, [&](std::int64_t begin, std::int64_t end, std::int64_t blk) {
        BlockSums s;
        for (std::int64_t p = begin; p < end; ++p) {
            const auto i = static_cast<std::size_t>(p);
            const Vec3 f = P.force[i], t = P.torque[i];
            const Vec3 v0 = P.velocity[i], w0 = P.spin[i];
            Vec3 fd, td;
            if (!(P.flags[i] & kFixedVelocity)) {
                fd = local_damping(f, v0, alpha);
                P.velocity[i] = v0 + (dt / P.mass[i]) * (f + fd);
            } else {
                s.boundary -= dt * dot(f, v0);  // the driver holds it against f
            }
            if (!(P.flags[i] & kFixedSpin)) {
                td = local_damping(t, w0, alpha);
                P.spin[i] = w0 + (dt / P.inertia[i]) * (t + td);
            } else {
                s.boundary -= dt * dot(t, w0);
            }
            const Vec3 v1 = P.velocity[i], w1 = P.spin[i];
            P.position[i] += dt * v1;

            s.kinetic += 0.5 * (P.mass[i] * dot(v0, v1) + P.inertia[i] * dot(w0, w1));
            s.damping -= 0.5 * dt * (dot(fd, v0 + v1) + dot(td, w0 + w1));
            const double moved2 = norm2(P.position[i] - position_at_rebuild_[i]);
            s.max_disp2 = std::max(s.max_disp2, moved2);
            const double step_len2 = dt * dt * norm2(v1), limit = 0.5 * P.radius[i];
            if (s.runaway < 0 && (!(step_len2 <= limit * limit) || !is_finite(w1)))
                s.runaway = p;
        }
        partial[static_cast<std::size_t>(blk)] = s;
    });
    IntegrationSums out;
    for (const BlockSums& s : partial) {
        out.kinetic += s.kinetic;
        out.damping += s.damping;
        out.boundary += s.boundary;
        out.max_disp2 = std::max(out.max_disp2, s.max_disp2);
        if (out.runaway < 0) out.runaway = s.runaway;
    }
    max_displacement_ = out.max_disp2;
    return out;
}

// Wall reactions (sum over each wall's contacts, in contact order), the work the walls did on
// the particles over the last step (trapezoid on the reaction), then the prescribed motion.
void World::move_walls(double& boundary_work) {
    const std::size_t nw = walls_.size();
    wall_previous_reaction_.resize(nw);
    wall_last_step_.resize(nw);
    wall_shift_since_rebuild_.resize(nw);
    std::vector<Vec3> reaction(nw);
    for (std::size_t k = 0; k < wall_contacts_.size(); ++k)
        reaction[static_cast<std::size_t>(wall_contacts_[k].wall)] -= wall_out_[k].force;
    for (std::size_t w = 0; w < nw; ++w) {
        Wall& wall = walls_[w];
        if (step_ > 0)
            boundary_work -= 0.5 * dot(wall_previous_reaction_[w] + reaction[w], wall_last_step_[w]);
        wall.reaction = reaction[w];
        wall_previous_reaction_[w] = reaction[w];
        const Vec3 move = dt_ * wall.velocity;
        wall.point += move;
        wall.displacement += move;
        wall_last_step_[w] = move;
        wall_shift_since_rebuild_[w] += move;
    }
}

void World::check_divergence(const IntegrationSums& sums) {
    std::ostringstream why;
    if (sums.runaway >= 0) {
        why << "step " << step_ << ": particle " << sums.runaway
            << " moved more than half its radius in one step or its state is not finite"
            << " (time step " << dt_ << " s too large for the stiffness, or a blow-up)";
    } else if (sim_.track_energy && !std::isfinite(energy_.total())) {
        why << "step " << step_ << ": energy is not finite";
    } else if (sim_.track_energy) {
        const double supplied = std::fabs(energy_.reference) + std::fabs(energy_.boundary_work);
        if (energy_.kinetic > sim_.divergence_energy_factor * supplied && energy_.kinetic > sim_.divergence_energy_floor &&
            energy_.kinetic > 0.0)
            why << "step " << step_ << ": kinetic energy " << energy_.kinetic
                << " J exceeds " << sim_.divergence_energy_factor
                << " x the energy supplied (" << supplied << " J): numerical instability";
    }
    const std::string reason = why.str();
    if (!reason.empty()) {
        status_ = RunStatus::diverged;
        status_reason_ = reason;
    }
}

}  // namespace gradem
