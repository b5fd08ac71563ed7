// Phase 5: gather and leap-frog integration with Cundall local damping (docs/model.md
// "Time integration"):
//     v(t+½) = v(t-½) + dt (F(t) + F_d(t)) / m,   x(t+dt) = x(t) + dt v(t+½),
//     w(t+½) = w(t-½) + dt (M(t) + M_d(t)) / I    (spheres: no gyroscopic term),
// plus wall motion, wall reactions and the divergence checks.
#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>
#include <vector>

#include "core/pair_kinematics.hpp"  // select
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

/// A block's tail (BlockPart): its block and each particle's terms, in particle order, added
/// to the head's sums after the pass; its largest displacement and first runaway.
struct TailTerms {
    struct Terms {
        double kinetic, damping, boundary_v, boundary_w;
    };
    std::int64_t block = -1;
    std::vector<Terms> terms;
    double max_disp2 = 0;
    std::int64_t runaway = -1;
};

}  // namespace

// Each particle sums the outputs of its pairs and wall contacts, in slot order: as j it adds F
// and M_j, as i it adds -F and M_i (PairOutput::torque_i = -(M_j + d x F), d = x_j - x_i, set by
// the pass that wrote the slot: the same bits as subtracting F and M_j + d x F here).
// Branch-free (whether the particle is a pair's i or j is a coin flip in a packing in Morton
// order, and a branch on it mispredicted): the sign of F is a factor ±1 (exact), the moment read
// from the side's address. A particle whose pairs the pass has already added in this order
// (forces_from_pass_ and a force owner: SimParams::forces_in_pass) gets only its walls' outputs
// added after them.
void World::gather_forces() {
    const auto n = static_cast<std::int64_t>(particles_.size());
    ParticleSet& P = particles_;
    const Incidence* const incidence = incidence_.data();
    const PairOutput* const out = pair_out_.data();
    const std::int16_t* const owner = forces_from_pass_ ? force_owner_.data() : nullptr;
#pragma omp parallel
    {
        const auto [begin, end] = item_share(particle_share_, n, team_size(), thread_index());
        for (std::int64_t p = begin; p < end; ++p) {
            const auto i = static_cast<std::size_t>(p);
            if (owner && owner[i] >= 0) {
                for (std::int32_t w = wall_start_[i]; w < wall_start_[i + 1]; ++w) {
                    P.force[i] += wall_out_[static_cast<std::size_t>(w)].force;
                    P.torque[i] += wall_out_[static_cast<std::size_t>(w)].torque;
                }
                continue;
            }
            Vec3 f, t;
            for (std::int32_t e = incidence_start_[i]; e < incidence_start_[i + 1]; ++e) {
                const Incidence inc = incidence[e];
                const PairOutput& o = out[inc.slot];
                const bool as_i = inc.partner < 0;
                const double sign = 1.0 - 2.0 * static_cast<double>(as_i);  // +1 as j, -1 as i
                f += sign * o.force_j;
                t += moment_on(o, as_i);
            }
            for (std::int32_t w = wall_start_[i]; w < wall_start_[i + 1]; ++w) {
                f += wall_out_[static_cast<std::size_t>(w)].force;
                t += wall_out_[static_cast<std::size_t>(w)].torque;
            }
            P.force[i] = f;
            P.torque[i] = t;
        }
    }
}

namespace {

constexpr std::int64_t kIntegrateChunk = 64;  ///< particles per vectorised chunk

/// Per-particle terms of one chunk, summed afterwards in particle order (so the sums keep
/// their rounding): kinetic energy, damping work, boundary work of prescribed velocity and
/// spin [J], squared displacement since the rebuild [m²], and whether the particle ran away.
struct ChunkTerms {
    double kinetic[kIntegrateChunk], damping[kIntegrateChunk], boundary_v[kIntegrateChunk], boundary_w[kIntegrateChunk];
    double moved2[kIntegrateChunk];
    double runaway[kIntegrateChunk];  ///< 1: ran away (a double: the vectoriser keeps every lane 64-bit)
    double fixed_v[kIntegrateChunk], fixed_w[kIntegrateChunk];  ///< 1: prescribed velocity / spin
};

/// The particle arrays integrate() reads and writes (restrict: they never overlap).
struct IntegrateArrays {
    Vec3* __restrict position;
    Vec3* __restrict velocity;
    Vec3* __restrict spin;
    const Vec3* __restrict force;
    const Vec3* __restrict torque;
    const Vec3* __restrict at_rebuild;
    const double* __restrict mass;
    const double* __restrict inertia;
    const double* __restrict radius;
    const std::uint8_t* __restrict flags;
};

// Component by component: an aggregate load or store of a Vec3 blocks the vectoriser.
inline Vec3 load3(const Vec3* __restrict a, std::int64_t i) { return {a[i].x, a[i].y, a[i].z}; }
inline void store3(Vec3* __restrict a, std::int64_t i, const Vec3& v) {
    a[i].x = v.x;
    a[i].y = v.y;
    a[i].z = v.z;
}

#if defined(__x86_64__) && defined(__GNUC__) && !defined(__clang__) && !defined(GRADEM_NO_CLONES)
#define GRADEM_INTEGRATE_CLONES __attribute__((target_clones("avx512f", "avx2", "default")))
#else
#define GRADEM_INTEGRATE_CLONES
#endif

// The leap-frog of particles [p0, p0 + count), branch-free (a prescribed velocity or spin is
// selected, not branched on: T.fixed_v, T.fixed_w unless `all_free`), vectorised across
// particles: the same IEEE operations as the per-particle form, so the same bits (a select of
// the damping term gives the +0 vector the branch left in place; subtracting a +0 boundary term
// changes no sum).
template <bool all_free>
__attribute__((always_inline)) inline void integrate_body(const IntegrateArrays& A, std::int64_t p0,
                                                          std::int64_t count, double dt, double alpha, ChunkTerms& T) {
#pragma GCC ivdep
    for (std::int64_t q = 0; q < count; ++q) {
        const std::int64_t i = p0 + q;
        const Vec3 f = load3(A.force, i), t = load3(A.torque, i);
        const Vec3 v0 = load3(A.velocity, i), w0 = load3(A.spin, i);
        const bool free_v = all_free | (T.fixed_v[q] == 0.0), free_w = all_free | (T.fixed_w[q] == 0.0);
        const Vec3 fd = select(free_v, local_damping(f, v0, alpha), Vec3{});
        const Vec3 td = select(free_w, local_damping(t, w0, alpha), Vec3{});
        const Vec3 v1 = select(free_v, v0 + (dt / A.mass[i]) * (f + fd), v0);
        const Vec3 w1 = select(free_w, w0 + (dt / A.inertia[i]) * (t + td), w0);
        store3(A.velocity, i, v1);
        store3(A.spin, i, w1);
        const Vec3 x1 = load3(A.position, i) + dt * v1;
        store3(A.position, i, x1);
        T.boundary_v[q] = free_v ? 0.0 : dt * dot(f, v0);  // the driver holds it against f
        T.boundary_w[q] = free_w ? 0.0 : dt * dot(t, w0);
        T.kinetic[q] = 0.5 * (A.mass[i] * dot(v0, v1) + A.inertia[i] * dot(w0, w1));
        T.damping[q] = 0.5 * dt * (dot(fd, v0 + v1) + dot(td, w0 + w1));
        T.moved2[q] = norm2(x1 - load3(A.at_rebuild, i));
        const double step_len2 = dt * dt * norm2(v1), limit = 0.5 * A.radius[i];
        constexpr double big = std::numeric_limits<double>::max();  // |x| <= big: x is finite (not NaN, not inf)
        const bool finite = (std::fabs(w1.x) <= big) & (std::fabs(w1.y) <= big) & (std::fabs(w1.z) <= big);
        const bool bad = !(step_len2 <= limit * limit) | !finite;
        T.runaway[q] = bad ? 1.0 : 0.0;
    }
}

GRADEM_INTEGRATE_CLONES bool integrate_chunk(const IntegrateArrays& A, std::int64_t p0, std::int64_t count, double dt,
                                             double alpha, ChunkTerms& T) {
    std::uint8_t any_fixed = 0;
    for (std::int64_t q = 0; q < count; ++q) any_fixed |= A.flags[p0 + q];
    if (any_fixed == 0) {
        integrate_body<true>(A, p0, count, dt, alpha, T);
        return false;
    }
    for (std::int64_t q = 0; q < count; ++q) {
        T.fixed_v[q] = (A.flags[p0 + q] & kFixedVelocity) ? 1.0 : 0.0;
        T.fixed_w[q] = (A.flags[p0 + q] & kFixedSpin) ? 1.0 : 0.0;
    }
    integrate_body<false>(A, p0, count, dt, alpha, T);
    return true;
}

/// Each block's tails (in thread order, which is particle order) added to its head's sums, as
/// if one thread had run the whole block.
void add_tails(std::vector<BlockSums>& partial, const std::vector<TailTerms>& tails) {
    for (const TailTerms& tail : tails) {
        if (tail.block < 0) continue;
        BlockSums& s = partial[static_cast<std::size_t>(tail.block)];
        for (const TailTerms::Terms& x : tail.terms) {
            s.boundary -= x.boundary_v;  // x - (+0) is x: a chunk without prescribed motion
            s.boundary -= x.boundary_w;
            s.kinetic += x.kinetic;
            s.damping -= x.damping;
        }
        s.max_disp2 = std::max(s.max_disp2, tail.max_disp2);
        if (s.runaway < 0) s.runaway = tail.runaway;
    }
}

}  // namespace

World::IntegrationSums World::integrate() {
    const auto n = static_cast<std::int64_t>(particles_.size());
    std::vector<BlockSums> partial(static_cast<std::size_t>(block_count(n)));  // per block: its head's
    std::vector<TailTerms> tails(static_cast<std::size_t>(thread_count()));    // per thread
    const double dt = dt_, alpha = sim_.local_damping;
    ParticleSet& P = particles_;
    const IntegrateArrays arrays{P.position.data(), P.velocity.data(), P.spin.data(),   P.force.data(),
                                 P.torque.data(),   position_at_rebuild_.data(), P.mass.data(), P.inertia.data(),
                                 P.radius.data(),   P.flags.data()};
#pragma omp parallel
    {
        const int t = thread_index();
        const auto [first, last] = item_share(particle_share_, n, team_size(), t);
        for_each_block_part(first, last, [&](const BlockPart& part) {
            BlockSums s;
            TailTerms& tail = tails[static_cast<std::size_t>(t)];
            if (!part.head()) tail.block = part.block;
            ChunkTerms T;
            for (std::int64_t p0 = part.begin; p0 < part.end; p0 += kIntegrateChunk) {
                const std::int64_t count = std::min(kIntegrateChunk, part.end - p0);
                // A chunk without a prescribed velocity or spin has no boundary work: its terms are +0,
                // and x - (+0) is x, so they are not subtracted (the longest chain of the sums).
                const bool any_prescribed = integrate_chunk(arrays, p0, count, dt, alpha, T);
                if (!part.head()) {  // a tail: its terms kept for the head's sums
                    for (std::int64_t q = 0; q < count; ++q) {
                        tail.terms.push_back({T.kinetic[q], T.damping[q], any_prescribed ? T.boundary_v[q] : 0.0,
                                              any_prescribed ? T.boundary_w[q] : 0.0});
                        s.max_disp2 = std::max(s.max_disp2, T.moved2[q]);
                        if (s.runaway < 0 && T.runaway[q] != 0.0) s.runaway = p0 + q;
                    }
                    continue;
                }
                for (std::int64_t q = 0; q < count; ++q) {  // the sums in particle order
                    if (any_prescribed) {
                        s.boundary -= T.boundary_v[q];
                        s.boundary -= T.boundary_w[q];
                    }
                    s.kinetic += T.kinetic[q];
                    s.damping -= T.damping[q];
                    s.max_disp2 = std::max(s.max_disp2, T.moved2[q]);
                    if (s.runaway < 0 && T.runaway[q] != 0.0) s.runaway = p0 + q;
                }
            }
            if (part.head()) {
                partial[static_cast<std::size_t>(part.block)] = s;
            } else {
                tail.max_disp2 = s.max_disp2;
                tail.runaway = s.runaway;
            }
        });
    }
    add_tails(partial, tails);
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
