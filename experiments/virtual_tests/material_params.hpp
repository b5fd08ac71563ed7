#pragma once
// The micro-parameters of one virtual test (what calibration varies): the contact and bond
// parameters of the core, the bond installation gap, the platen friction, the damping, and the
// bond families of explicit-paste specimens. Every field is a row of the material table
// (experiments/config/material_table.hpp: config keys, units, ranges, calibration names);
// invalid_reason() is in cube_test.cpp.
#include <optional>
#include <string>

#include "core/params.hpp"

namespace gradem::exp {

/// Micro-parameters of one run (what calibration varies).
struct MaterialParams {
    ContactParams contact;            ///< E*, kappa*, grain friction mu
    BondParams bond;                  ///< Ē*, κ̄, λ̄, β̄, strengths and scatter, φ̄, seed
    double bond_gap_fraction = 0.1;   ///< installation gap / mean grain radius [-]
    double bond_gap_absolute = 0.0;   ///< [m] if > 0, the installation gap for every packing (a
                                      ///< paste-bridge length shared by sands), replacing the fraction
    /// The installation gap [m] for a packing whose mean grain radius is `mean_radius` [m].
    [[nodiscard]] double bond_gap(double mean_radius) const {
        return bond_gap_absolute > 0.0 ? bond_gap_absolute : bond_gap_fraction * mean_radius;
    }
    double platen_friction = 0.5;     ///< mu_w [-]
    double damping = 0.7;             ///< local damping alpha [-]
    /// Explicit-paste specimens only (Packing::family set; [paste] keys): paste-paste bonds use
    /// `bond`; paste-sand (interfacial zone) bonds use `bond` with strengths and modulus scaled
    /// by these factors; sand-sand pairs are bonded with `bond` or frictional only.
    struct FamilyBonds {
        double itz_strength_factor = 1.0;  ///< ITZ σ̄_c, c̄ (means and std) / paste's [-]
        double itz_modulus_factor = 1.0;   ///< ITZ Ē* / paste's [-]
        bool sand_sand_bonded = false;     ///< false: sand-sand contacts frictional only
    } families;
    [[nodiscard]] std::optional<std::string> invalid_reason() const;
};

}  // namespace gradem::exp
