#pragma once
// The calibration's unknowns: named micro-parameters of the cube test, each fixed or free with
// bounds and a scaling. Free parameters live in a unit box for the optimisers:
//   linear:  u = (v − lower) / (upper − lower)
//   log:     u = ln(v / lower) / ln(upper / lower)
// and in "natural" coordinates z for uncertainty (z = ln v for log, z = v for linear), so that a
// standard error in z is relative for log parameters and absolute for linear ones.
//
// The names, units, roles, default bounds and scales, and how a value is applied, are the
// material table's (experiments/config/material_table.hpp): every row with a calibration column.
// Names (and the order they are applied in): effective_modulus_gpa (E* and Ē* together),
// stiffness_ratio (κ* and κ̄ together), friction, radius_multiplier, moment_factor,
// friction_angle_deg, bond_gap_um, bond_gap_fraction, tensile_strength_mpa (c̄ keeps its ratio),
// cohesion_ratio, cohesion_mpa, strength_cv, and each bond model's own (softening_factor,
// cut_fraction; radial_elements, angular_elements (fixed only), residual_friction).
// "Scale" parameters are those the model's homogeneity (docs/calibration.md "Homogeneity") acts on: multiplying
// all moduli by a scales E by a; multiplying all strengths by b scales the peak by b.
#include <optional>
#include <string>
#include <vector>

#include "experiments/virtual_tests/cube_test.hpp"
#include "experiments/config/material_table.hpp"

namespace gradem::cal {

/// The homogeneity role of a parameter (the material table's column).
using Role = exp::ParameterRole;

struct ParameterSpec {
    std::string name;
    bool free = false;
    double start = 0.0;   ///< start value (free) or the value (fixed), config units
    double lower = 0.0, upper = 0.0;
    bool log_scale = false;
    int line = 0;         ///< config line of its table (0: a default)
    [[nodiscard]] Role role() const;
    [[nodiscard]] std::string unit() const;
};

/// Known parameter names, in the order they are applied.
const std::vector<std::string>& parameter_names();
bool is_known_parameter(const std::string& name);

/// The parameter's current value in `material` (config units), and its default bounds and
/// scaling; used when a config does not give them.
ParameterSpec default_parameter(const std::string& name, const exp::MaterialParams& material);

/// The free parameters of a problem, and the fixed ones it applies on top of the base material.
class ParameterSpace {
public:
    ParameterSpace() = default;
    ParameterSpace(std::vector<ParameterSpec> specs, exp::MaterialParams base);

    [[nodiscard]] std::size_t size() const { return free_.size(); }
    [[nodiscard]] const std::vector<ParameterSpec>& all() const { return specs_; }
    [[nodiscard]] const ParameterSpec& free(std::size_t k) const { return specs_[free_[k]]; }
    [[nodiscard]] std::vector<double> start() const;                  ///< free values, config units
    [[nodiscard]] std::optional<std::size_t> index_of(const std::string& name) const;  ///< among free
    [[nodiscard]] std::optional<std::size_t> index_of(Role role) const;  ///< first free one with the role

    [[nodiscard]] std::vector<double> to_unit(const std::vector<double>& values) const;
    [[nodiscard]] std::vector<double> from_unit(const std::vector<double>& unit) const;
    [[nodiscard]] double to_natural(std::size_t k, double value) const;
    [[nodiscard]] double from_natural(std::size_t k, double z) const;
    [[nodiscard]] double clamp(std::size_t k, double value) const;

    /// The base material with every parameter (fixed ones, then the free `values`) applied.
    [[nodiscard]] exp::MaterialParams material(const std::vector<double>& values) const;

private:
    std::vector<ParameterSpec> specs_;
    std::vector<std::size_t> free_;
    exp::MaterialParams base_;
};

}  // namespace gradem::cal
