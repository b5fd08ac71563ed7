#pragma once
// Bond parameters per pair of particle families (explicit paste). Particles carry a
// family tag (ParticleSet::family: 0 sand, 1 paste in experiments/); entry (a, b) = (b, a) of
// the table holds the parameters of bonds between a family-a and a family-b particle, or none:
// such pairs get no bond (frictional contact only). Every entry uses the same bond model and
// the same law shape (side-state size); stiffness, bond radius, moment factor, strengths and
// their scatter, friction angle and strength seed are per entry. The contact law is shared by
// every family (one ContactParams per World). A table of one family is exactly the classic
// single-parameter installation.
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "core/params.hpp"

namespace gradem {

struct BondFamilyTable {
    int families = 1;                                 ///< family tags 0 .. families-1, at most 15
    std::vector<std::optional<BondParams>> entries;   ///< families x families, row major, symmetric

    /// A table of `n` families, no pair bonded.
    static BondFamilyTable empty(int n) {
        BondFamilyTable t;
        t.families = n;
        t.entries.assign(static_cast<std::size_t>(n * n), std::nullopt);
        return t;
    }
    /// Every pair bonded with `params` (one family).
    static BondFamilyTable single(const BondParams& params) {
        BondFamilyTable t = empty(1);
        t.entries[0] = params;
        return t;
    }
    /// Sets (a, b) and (b, a).
    void set(int a, int b, const std::optional<BondParams>& params) {
        entries[static_cast<std::size_t>(a * families + b)] = params;
        entries[static_cast<std::size_t>(b * families + a)] = params;
    }
    [[nodiscard]] const std::optional<BondParams>& at(int a, int b) const {
        return entries[static_cast<std::size_t>(a * families + b)];
    }
    /// Size, symmetry, one model, valid entries: the first violation, or nullopt.
    [[nodiscard]] std::optional<std::string> invalid_reason() const {
        if (families < 1 || families > 15)
            return "BondFamilyTable::families = " + std::to_string(families) + " violates in [1, 15]";
        if (entries.size() != static_cast<std::size_t>(families * families))
            return "BondFamilyTable::entries has " + std::to_string(entries.size()) + " entries, expected families^2";
        const BondParams* first = nullptr;
        for (int a = 0; a < families; ++a)
            for (int b = 0; b < families; ++b) {
                const auto& e = at(a, b);
                if (e.has_value() != at(b, a).has_value()) return std::string("BondFamilyTable is not symmetric");
                if (!e) continue;
                if (auto why = e->invalid_reason()) return "bond family (" + std::to_string(a) + ", " + std::to_string(b) + "): " + *why;
                if (!first) first = &*e;
                if (e->model != first->model) return std::string("BondFamilyTable: every family pair must use the same bond model");
            }
        if (!first) return std::string("BondFamilyTable: no family pair is bonded");
        return std::nullopt;
    }
};

}  // namespace gradem
