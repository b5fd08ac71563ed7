#pragma once
// THE table of bond laws: BondModel -> kernel. Adding a law = one kernel header (the
// interface is described in bond_law.hpp), one parameter struct in params.hpp, one row here.
// The World calls visit_bond_law once per phase, so each law's loop is compiled with its kernel
// inlined (no per-bond dispatch in the hot loop).
#include <stdexcept>
#include <string>

#include "core/flat_joint_law.hpp"
#include "core/parallel_bond_law.hpp"
#include "core/soft_bond_law.hpp"

namespace gradem {

/// Calls visitor(Law{}) with the kernel of `model`; returns what the visitor returns.
template <class Visitor>
decltype(auto) visit_bond_law(BondModel model, Visitor&& visitor) {
    switch (model) {
        case BondModel::parallel_bond: return visitor(ParallelBondLaw{});
        case BondModel::soft_bond: return visitor(SoftBondLaw{});
        case BondModel::flat_joint: return visitor(FlatJointLaw{});
    }
    throw std::invalid_argument("visit_bond_law: unknown BondModel");
}

}  // namespace gradem
