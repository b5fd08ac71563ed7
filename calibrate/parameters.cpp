#include "calibrate/parameters.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace gradem::cal {
namespace {

constexpr double kGpa = 1.0e9, kMpa = 1.0e6, kUm = 1.0e-6;

double cv_of(double std_dev, double mean) { return mean > 0.0 ? std_dev / mean : 0.0; }

/// Sets one named parameter (config units) on `m`. Strength scatter and the cohesion ratio are
/// applied relative to the current means, so the order of parameter_names() matters.
void apply(const std::string& name, double v, exp::MaterialParams& m) {
    BondParams& b = m.bond;
    if (name == "effective_modulus_gpa") {
        m.contact.effective_modulus = b.effective_modulus = v * kGpa;
    } else if (name == "stiffness_ratio") {
        m.contact.stiffness_ratio = b.stiffness_ratio = v;
    } else if (name == "friction") {
        m.contact.friction = v;
    } else if (name == "radius_multiplier") {
        b.radius_multiplier = v;
    } else if (name == "moment_factor") {
        b.moment_factor = v;
    } else if (name == "friction_angle_deg") {
        b.friction_angle_deg = v;
    } else if (name == "bond_gap_um") {
        m.bond_gap_absolute = v * kUm;
    } else if (name == "bond_gap_fraction") {
        m.bond_gap_fraction = v;
    } else if (name == "tensile_strength_mpa") {
        const double cv = cv_of(b.tensile_strength_std, b.tensile_strength_mean);
        const double ratio = b.tensile_strength_mean > 0.0 ? b.cohesion_mean / b.tensile_strength_mean : 2.0;
        const double cv_c = cv_of(b.cohesion_std, b.cohesion_mean);
        b.tensile_strength_mean = v * kMpa;
        b.tensile_strength_std = cv * b.tensile_strength_mean;
        b.cohesion_mean = ratio * b.tensile_strength_mean;  // keeps c̄/σ̄c: the strength scale moves both
        b.cohesion_std = cv_c * b.cohesion_mean;
    } else if (name == "cohesion_ratio") {
        const double cv_c = cv_of(b.cohesion_std, b.cohesion_mean);
        b.cohesion_mean = v * b.tensile_strength_mean;
        b.cohesion_std = cv_c * b.cohesion_mean;
    } else if (name == "cohesion_mpa") {
        const double cv_c = cv_of(b.cohesion_std, b.cohesion_mean);
        b.cohesion_mean = v * kMpa;
        b.cohesion_std = cv_c * b.cohesion_mean;
    } else if (name == "strength_cv") {
        b.tensile_strength_std = v * b.tensile_strength_mean;
        b.cohesion_std = v * b.cohesion_mean;
    } else {
        throw std::invalid_argument("unknown calibration parameter '" + name + "'");
    }
}

}  // namespace

Role ParameterSpec::role() const {
    if (name == "effective_modulus_gpa") return Role::stiffness_scale;
    if (name == "tensile_strength_mpa" || name == "cohesion_mpa") return Role::strength_scale;
    return Role::shape;
}

std::string ParameterSpec::unit() const {
    if (name.ends_with("_gpa")) return "GPa";
    if (name.ends_with("_mpa")) return "MPa";
    if (name.ends_with("_um")) return "um";
    if (name.ends_with("_deg")) return "deg";
    return "-";
}

const std::vector<std::string>& parameter_names() {
    static const std::vector<std::string> names = {
        "effective_modulus_gpa", "stiffness_ratio",   "friction",     "radius_multiplier", "moment_factor",
        "friction_angle_deg",    "bond_gap_um",       "bond_gap_fraction", "tensile_strength_mpa",
        "cohesion_ratio",        "cohesion_mpa",      "strength_cv"};
    return names;
}

bool is_known_parameter(const std::string& name) {
    const auto& n = parameter_names();
    return std::find(n.begin(), n.end(), name) != n.end();
}

ParameterSpec default_parameter(const std::string& name, const exp::MaterialParams& m) {
    const BondParams& b = m.bond;
    ParameterSpec p;
    p.name = name;
    auto set = [&](double value, double lo, double hi, bool log) {
        p.start = value;
        p.lower = lo;
        p.upper = hi;
        p.log_scale = log;
    };
    if (name == "effective_modulus_gpa") set(m.contact.effective_modulus / kGpa, 1.0, 100.0, true);
    else if (name == "stiffness_ratio") set(m.contact.stiffness_ratio, 1.0, 3.0, false);
    else if (name == "friction") set(m.contact.friction, 0.1, 1.0, false);
    else if (name == "radius_multiplier") set(b.radius_multiplier, 0.3, 1.0, false);
    else if (name == "moment_factor") set(b.moment_factor, 0.0, 1.0, false);
    else if (name == "friction_angle_deg") set(b.friction_angle_deg, 0.0, 60.0, false);
    else if (name == "bond_gap_um") set(m.bond_gap_absolute / kUm, 0.0, 100.0, false);
    else if (name == "bond_gap_fraction") set(m.bond_gap_fraction, 0.0, 0.5, false);
    else if (name == "tensile_strength_mpa") set(b.tensile_strength_mean / kMpa, 0.5, 100.0, true);
    else if (name == "cohesion_ratio")
        set(b.tensile_strength_mean > 0.0 ? b.cohesion_mean / b.tensile_strength_mean : 2.0, 0.5, 5.0, true);
    else if (name == "cohesion_mpa") set(b.cohesion_mean / kMpa, 0.5, 200.0, true);
    else if (name == "strength_cv") set(cv_of(b.tensile_strength_std, b.tensile_strength_mean), 0.0, 0.5, false);
    else throw std::invalid_argument("unknown calibration parameter '" + name + "'");
    return p;
}

ParameterSpace::ParameterSpace(std::vector<ParameterSpec> specs, exp::MaterialParams base)
    : base_(base) {
    // Apply in the canonical order whatever order the config used.
    for (const std::string& name : parameter_names())
        for (auto& s : specs)
            if (s.name == name) specs_.push_back(s);
    for (std::size_t k = 0; k < specs_.size(); ++k)
        if (specs_[k].free) free_.push_back(k);
}

std::vector<double> ParameterSpace::start() const {
    std::vector<double> v;
    for (std::size_t k : free_) v.push_back(specs_[k].start);
    return v;
}

std::optional<std::size_t> ParameterSpace::index_of(const std::string& name) const {
    for (std::size_t k = 0; k < free_.size(); ++k)
        if (specs_[free_[k]].name == name) return k;
    return std::nullopt;
}

std::optional<std::size_t> ParameterSpace::index_of(Role role) const {
    for (std::size_t k = 0; k < free_.size(); ++k)
        if (specs_[free_[k]].role() == role) return k;
    return std::nullopt;
}

std::vector<double> ParameterSpace::to_unit(const std::vector<double>& values) const {
    std::vector<double> u(values.size());
    for (std::size_t k = 0; k < values.size(); ++k) {
        const ParameterSpec& p = free(k);
        u[k] = p.log_scale ? std::log(values[k] / p.lower) / std::log(p.upper / p.lower)
                           : (values[k] - p.lower) / (p.upper - p.lower);
    }
    return u;
}

std::vector<double> ParameterSpace::from_unit(const std::vector<double>& unit) const {
    std::vector<double> v(unit.size());
    for (std::size_t k = 0; k < unit.size(); ++k) {
        const ParameterSpec& p = free(k);
        const double u = std::clamp(unit[k], 0.0, 1.0);
        v[k] = p.log_scale ? p.lower * std::exp(u * std::log(p.upper / p.lower)) : p.lower + u * (p.upper - p.lower);
        v[k] = clamp(k, v[k]);  // exp/log round-off must not leave the box
    }
    return v;
}

double ParameterSpace::to_natural(std::size_t k, double value) const {
    return free(k).log_scale ? std::log(value) : value;
}

double ParameterSpace::from_natural(std::size_t k, double z) const {
    return free(k).log_scale ? std::exp(z) : z;
}

double ParameterSpace::clamp(std::size_t k, double value) const {
    return std::clamp(value, free(k).lower, free(k).upper);
}

exp::MaterialParams ParameterSpace::material(const std::vector<double>& values) const {
    exp::MaterialParams m = base_;
    std::size_t next_free = 0;
    for (const ParameterSpec& s : specs_) apply(s.name, s.free ? values.at(next_free++) : s.start, m);
    return m;
}

}  // namespace gradem::cal
