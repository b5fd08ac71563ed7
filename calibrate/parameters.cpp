#include "calibrate/parameters.hpp"

#include "experiments/config/material_table.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace gradem::cal {
namespace {

/// The table row of a calibration parameter; throws for an unknown name.
const exp::MaterialParameter& row_of(const std::string& name) {
    const exp::MaterialParameter* p = exp::find_material_parameter(name);
    if (!p || p->calibration == exp::Calibration::none)
        throw std::invalid_argument("unknown calibration parameter '" + name + "'");
    return *p;
}

}  // namespace

Role ParameterSpec::role() const { return row_of(name).role; }

std::string ParameterSpec::unit() const { return std::string(row_of(name).unit); }

const std::vector<std::string>& parameter_names() {
    static const std::vector<std::string> names = [] {
        std::vector<std::string> out;
        for (const exp::MaterialParameter& p : exp::material_table())
            if (p.calibration != exp::Calibration::none) out.emplace_back(p.key);
        return out;
    }();
    return names;
}

bool is_known_parameter(const std::string& name) {
    const auto& n = parameter_names();
    return std::find(n.begin(), n.end(), name) != n.end();
}

ParameterSpec default_parameter(const std::string& name, const exp::MaterialParams& m) {
    const exp::MaterialParameter& row = row_of(name);
    ParameterSpec p;
    p.name = name;
    p.start = row.integer ? static_cast<double>(row.get_int(m)) : exp::config_value(row, m);
    p.lower = row.lower;
    p.upper = row.upper;
    p.log_scale = row.log_scale;
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
    for (const ParameterSpec& s : specs_)
        exp::apply_calibration_value(row_of(s.name), m, s.free ? values.at(next_free++) : s.start);
    return m;
}

}  // namespace gradem::cal
