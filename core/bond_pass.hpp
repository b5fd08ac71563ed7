#pragma once
// A bond law's own pass over every bond: a law may give a static
//     BondPassEnergy compute_all(const BondPass& pass, double dt)
// (declared in its header, defined in its own source file), and World::compute_bonds then calls
// it instead of the generic loop over bonds (world_bonds.cpp, compute_bonds_with). The pass gets
// the World's state by reference and must give the generic loop's results: each bond through
// the law's kernel, its force and moment added into its pair's slot, breaks appended in bond
// order, energies summed per block in bond order (so any thread count gives the same bits).
#include <cstddef>
#include <cstdint>
#include <functional>
#include <vector>

#include "core/bond_law.hpp"
#include "core/params.hpp"
#include "core/particles.hpp"
#include "core/world_types.hpp"

namespace gradem {

/// What a pair exerts this step: the force on j, the moment on j and the moment on i; i gets
/// -force_j and
///     torque_i = -(torque_j + (x_j - x_i) x force_j)   (angular momentum balance),
/// set by whoever writes the slot last in the step (set_i_side), so that the gather reads each
/// side's moment instead of computing i's from the partner's position (World::gather_forces).
struct PairOutput {
    Vec3 force_j, torque_j;  ///< [N], [N m]
    Vec3 torque_i;           ///< [N m]
};

/// The moment on i [N m] from the force [N] and moment [N m] on j; d = x_j - x_i [m] at the
/// positions the forces were evaluated at. The one expression every writer of a slot uses (the
/// parallel bond's kernel across its lanes too), so all give the same bits.
inline Vec3 moment_on_i(const Vec3& torque_j, const Vec3& force_j, const Vec3& d) {
    return -(torque_j + cross(d, force_j));
}

/// Sets the slot's moment on i from its force and moment on j (moment_on_i).
inline void set_i_side(PairOutput& out, const Vec3& d) { out.torque_i = moment_on_i(out.torque_j, out.force_j, d); }

/// The moment on j (as_i false) or on i (true), read from its address: no branch on the side.
inline const Vec3& moment_on(const PairOutput& out, bool as_i) {
    static_assert(offsetof(PairOutput, torque_i) == offsetof(PairOutput, torque_j) + sizeof(Vec3));
    const char* on_j = reinterpret_cast<const char*>(&out) + offsetof(PairOutput, torque_j);
    return *reinterpret_cast<const Vec3*>(on_j + static_cast<std::size_t>(as_i) * sizeof(Vec3));
}

/// A pair's force and moments added to those of its particles a pass's thread owns, as
/// World::gather_forces() adds its slot: +1 × F and M_j to j, -1 × F and M_i to i (the same
/// bits, as long as each particle takes its pairs in pair order: World::force_owner_).
inline void add_to_owned_particles(Vec3* force, Vec3* torque, std::size_t i, std::size_t j, bool own_i, bool own_j,
                                   const Vec3& force_j, const Vec3& torque_j, const Vec3& torque_i) {
    if (own_j) {
        force[j] += 1.0 * force_j;
        torque[j] += torque_j;
    }
    if (own_i) {
        force[i] += -1.0 * force_j;
        torque[i] += torque_i;
    }
}

/// Per-bond constants (they depend only on the radii and BondParams): R̄, 1/R̄ and the
/// stiffness, computed once instead of three divisions per bond and step (32 bytes; the
/// rest of the section is rebuilt from R̄ and 1/R̄ by multiplications). Stale after a change
/// of radii or bond parameters.
struct BondConstants {
    double radius = 0, inv_radius = 0;  ///< R̄ [m], 1/R̄ [1/m]
    BondStiffness stiffness;
};

/// Energies of one bond phase [J]: stored after the step, released by breaks, dissipated by
/// damage and by friction of broken elements.
struct BondPassEnergy {
    double stored = 0, released = 0, damage = 0, slip = 0;
    /// A law's own pass: the acting bonds it took in its SIMD lanes and through its scalar
    /// kernel (StepProfile sums them; gradem-bench reports the share).
    std::int64_t lane_bonds = 0, scalar_bonds = 0;
    /// Bonds released this step (they stopped acting): their pairs' contacts act from the next
    /// step on, so the contacts phase collects its pairs again (World::compute_contacts).
    std::int64_t releases = 0;
    /// Bonds whose output the pass added to both particles, no slot written (BondPass::force_owners).
    std::int64_t into_particles = 0;
    BondPassEnergy& operator+=(const BondPassEnergy& o) {
        stored += o.stored;
        released += o.released;
        damage += o.damage;
        slip += o.slip;
        lane_bonds += o.lane_bonds;
        scalar_bonds += o.scalar_bonds;
        releases += o.releases;
        into_particles += o.into_particles;
        return *this;
    }
};

/// How a law's own pass with forces into particles is shared by a team (World::share_pass): the
/// bounds of each thread's bonds and particles (team + 1 each; other sizes: equal shares), each
/// thread's seconds in its share (added to), and the team that ran it (set by the pass).
struct PassShares {
    const std::vector<std::int64_t>* units = nullptr;
    const std::vector<std::int64_t>* particles = nullptr;
    std::vector<double>* seconds = nullptr;
    int team = 1;
};

/// The World's state a law's own pass reads and writes (for one call).
struct BondPass {
    const ParticleSet& particles;
    std::vector<ParallelBond>& bonds;
    std::vector<double>& side;                     ///< per-bond law state, `stride` doubles each
    std::size_t stride;
    const std::vector<BondConstants>& constants;   ///< per bond
    const std::vector<BondParams>& family_params;  ///< per ParallelBond::family_pair
    std::vector<PairOutput>& pair_out;             ///< per pair slot (ParallelBond::slot): bond_output()
    std::vector<BreakEvent>& breaks;               ///< append in bond order
    const SimParams& sim;
    std::int64_t step;
    double time;  ///< [s]
    bool replaces_contact;  ///< the bonds replace their pairs' contacts (BondParams::bond_replaces_contact)
    /// Forces into particles (SimParams::forces_in_pass; null: every bond writes its slot). Called
    /// once per pass with the team's size, it gives each particle's owner: the thread whose share
    /// of the bonds (`shares`) holds all its pairs, every one an acting bond; -1: none.
    /// The pass zeroes `force` and `torque`, adds each bond's output to its owned particles in
    /// bond order (= pair order) and writes the slot only where a particle is not owned.
    std::function<std::int16_t*(int team)> force_owners{};
    /// The particles of the bonds the pass released, appended: force_owners() makes them unowned
    /// from the next pass on (their pairs' contacts act then; this step's gather still takes
    /// their sums from the pass).
    std::vector<std::int32_t>* released_particles = nullptr;
    Vec3* force = nullptr;                  ///< per particle [N]
    Vec3* torque = nullptr;                 ///< per particle [N m]
    std::vector<Vec3>* bond_torque = nullptr;  ///< per bond: its moment on j this step [N m] (the slots rebuilt from it)
    PassShares* shares = nullptr;              ///< with force_owners: the threads' shares
};

/// An acting bond's force and moment on j into its pair's slot, and the moment on i from the
/// total (d = x_j - x_i [m]). A bond that replaces its pair's contact owns the slot (the contact
/// phase leaves it alone: World::compute_contacts) and sets it; one beside the contact adds to
/// the contact's. Setting gives the bits of adding to the +0 the contact phase used to write, but
/// for the sign of a zero, which no particle's sum can see (a sum that starts at +0 never becomes
/// -0, and adding a zero of either sign to it changes no bit).
inline void bond_output(PairOutput& out, const Vec3& force_j, const Vec3& torque_j, bool replaces_contact, const Vec3& d) {
    if (replaces_contact) {
        out.force_j = force_j;
        out.torque_j = torque_j;
    } else {
        out.force_j += force_j;
        out.torque_j += torque_j;
    }
    set_i_side(out, d);
}

/// The slot of a bond released this step: zero if the bond owned it (bond_output); beside the
/// contact, the contact's output (its moment on i included) stays.
inline void released_bond_output(PairOutput& out, bool replaces_contact) {
    if (replaces_contact) out = {};
}

}  // namespace gradem
