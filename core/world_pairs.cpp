// Phases 2 and 3 in one pass over the Verlet pairs, for the parallel bond (issue 10). With the
// parallel bond the linear contact acts beside the bond (PFC linearpbond), so a bonded pair
// that overlaps needs the same pair kinematics twice: once in the contact phase, once in the
// bond phase. In a compression test about 55 % of the bonded pairs overlap, and almost every
// pair is bonded; this pass loads each pair's particle state and evaluates pair_kinematics()
// once, then applies the contact law and the bond law in the order of the two separate phases.
//
// Bitwise the same as compute_contacts() followed by compute_bonds_with<ParallelBondLaw>():
//   - per pair: the contact output is written first, the bond's force and moment added after,
//     with the same expressions on the same kinematics (pair_kinematics is a pure function);
//   - contact energies: summed per fixed pair block in pair order, as before;
//   - bond energies: the old loop summed them per fixed BOND block in bond order. Pairs and
//     bonds are both sorted by (i, j), so bonded pairs meet their bonds in bond order, but the
//     blocks differ; the stored energy of each bond is therefore kept in bond_stored_ and
//     summed per bond block afterwards, and the released energies (breaks only, in bond order)
//     per bond block from the break list. A bond that did not break adds +0 to the released
//     sum and a broken one +0 to the stored sum: both sums start at +0 and only add values
//     >= 0, so these additions never changed a bit;
//   - break events: per pair block in pair order, merged in block order = bond order.
// Soft bonds and flat joints keep the two separate phases (world_step.cpp, world_bonds.cpp).
#include "core/contact_law.hpp"
#include "core/parallel.hpp"
#include "core/parallel_bond_law.hpp"
#include "core/world.hpp"

namespace gradem {

World::BondEnergy World::compute_contacts_and_parallel_bonds(double dt, double& strain, double& slip) {
    if (bond_const_stale_) refresh_bond_constants();
    const auto m = static_cast<std::int64_t>(pairs_.size());
    const auto nb = static_cast<std::int64_t>(bonds_.size());
    bond_stored_.resize(bonds_.size(), 0.0);
    std::vector<ParallelBondLaw::Context> contexts;  // one per bond family pair
    for (const BondParams& p : bond_family_params_) contexts.push_back(ParallelBondLaw::context(p, sim_.track_energy));

    struct Released {
        std::int64_t bond;
        double energy;  ///< [J]
    };
    struct BlockOut {
        double contact_strain = 0, contact_slip = 0;
        std::vector<BreakEvent> breaks;
        std::vector<Released> released;
    };
    std::vector<BlockOut> blocks(static_cast<std::size_t>(block_count(m)));
    for_each_block(m, [&](std::int64_t begin, std::int64_t end, std::int64_t blk) {
        BlockOut& bo = blocks[static_cast<std::size_t>(blk)];
        double strain_sum = 0, slip_sum = 0;
        std::vector<BondBreak> breaks;
        for (std::int64_t k = begin; k < end; ++k) {
            Pair& p = pairs_[static_cast<std::size_t>(k)];
            const auto i = static_cast<std::size_t>(p.i), j = static_cast<std::size_t>(p.j);
            const PairState s{particles_.position[i], particles_.position[j],
                              particles_.velocity[i], particles_.velocity[j], particles_.spin[i],
                              particles_.spin[j], particles_.radius[i], particles_.radius[j]};
            PairOutput& out = pair_out_[static_cast<std::size_t>(k)];
            const Vec3 d = s.xb - s.xa;
            const auto bk = static_cast<std::size_t>(p.bond);
            const bool bonded = p.bond >= 0 && bonds_[bk].state == BondState::intact;
            const bool open = norm2(d) >= (s.ra + s.rb) * (s.ra + s.rb);
            if (open) {  // the contact carries nothing
                p.shear_force = {};
                out = {};
                if (!bonded) continue;
            }
            const PairKinematics kin = pair_kinematics(s, dt);
            if (!open) {  // linear contact (compute_contacts)
                const double kn = contact_normal_stiffness(contact_.effective_modulus, s.ra, s.rb);
                const LinearContactResult r =
                    linear_contact(kn, kn / contact_.stiffness_ratio, contact_.friction, kin.gap,
                                   rotate_into_plane(p.shear_force, kin), kin.du_shear);
                p.shear_force = r.shear_force;
                out.force_j = r.normal_force * kin.normal + r.shear_force;
                out.torque_j = cross(kin.arm_b, out.force_j);
                strain_sum += r.strain_energy;
                slip_sum += r.slip_energy;
            }
            if (!bonded) continue;
            // parallel bond (compute_bonds_with<ParallelBondLaw>)
            ParallelBond& b = bonds_[bk];
            const BondConstants& bc = bond_const_[bk];
            const BondSection sec = bond_section_of_radius(bc.radius, bc.inv_radius);
            const BondStepResult r =
                ParallelBondLaw::step(contexts[b.family_pair], b, nullptr, sec, bc.stiffness, kin, breaks);
            bond_stored_[bk] = r.stored;
            if (r.failure != BondState::intact) {
                for (const BondBreak& x : breaks)
                    bo.breaks.push_back({step_, time_, p.bond, b.i, b.j, x.mode, s.xa + kin.arm_a + x.offset,
                                         kin.normal, sec.radius, x.tensile_stress, x.shear_stress, x.element});
                breaks.clear();
                bo.released.push_back({p.bond, r.released});
                continue;
            }
            out.force_j += r.force_j;
            out.torque_j += cross(kin.arm_b, r.force_j) + r.moment_j;
        }
        bo.contact_strain = strain_sum;
        bo.contact_slip = slip_sum;
    });

    double contact_strain = 0, contact_slip = 0;
    std::vector<BondEnergy> bond_partial(static_cast<std::size_t>(block_count(nb)));
    for (const BlockOut& bo : blocks) {
        contact_strain += bo.contact_strain;
        contact_slip += bo.contact_slip;
        breaks_.insert(breaks_.end(), bo.breaks.begin(), bo.breaks.end());
        for (const Released& x : bo.released)
            bond_partial[static_cast<std::size_t>(x.bond / kBlockSize)].released += x.energy;
    }
    strain = contact_strain;
    slip = contact_slip;
    if (sim_.track_energy)
        for_each_block(nb, [&](std::int64_t begin, std::int64_t end, std::int64_t blk) {
            double stored = 0;
            for (std::int64_t k = begin; k < end; ++k) stored += bond_stored_[static_cast<std::size_t>(k)];
            bond_partial[static_cast<std::size_t>(blk)].stored = stored;
        });
    return ordered_sum(bond_partial);
}

}  // namespace gradem
