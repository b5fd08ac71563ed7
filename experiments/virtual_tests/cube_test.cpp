#include "experiments/virtual_tests/cube_test.hpp"

#include <cmath>
#include <sstream>
#include <stdexcept>

#include "core/world.hpp"
#include "experiments/config/material_table.hpp"
#include "experiments/virtual_tests/cube_specimen.hpp"
#include "experiments/paste/paste_spec.hpp"

namespace gradem::exp {

std::optional<std::string> MaterialParams::invalid_reason() const {
    // The table's ranges (config units) first, then core's own rules as a backstop.
    if (auto why = material_range_violation(*this)) return why;
    if (auto why = contact.invalid_reason()) return why;
    if (auto why = bond.invalid_reason()) return why;
    return std::nullopt;
}

std::optional<std::string> CubeTestSpec::invalid_reason() const {
    if (auto why = loading.invalid_reason()) return why;
    std::ostringstream out;
    if (!(gauge_length_fraction > 0.0 && gauge_length_fraction < 0.9))
        out << "CubeTestSpec::gauge_length_fraction = " << gauge_length_fraction << " violates in (0, 0.9)";
    else if (!(slab_fraction > 0.0 && slab_fraction < 0.5)) out << "CubeTestSpec::slab_fraction = " << slab_fraction << " violates in (0, 0.5)";
    else if (!(core_fraction > 0.0 && core_fraction <= 1.0)) out << "CubeTestSpec::core_fraction = " << core_fraction << " violates in (0, 1]";
    else if (!(settle_ratio > 0.0)) out << "CubeTestSpec::settle_ratio = " << settle_ratio << " violates > 0";
    else if (max_settle_steps < 0) out << "CubeTestSpec::max_settle_steps = " << max_settle_steps << " violates >= 0";
    else if (!(imbalance_warning > 0.0)) out << "CubeTestSpec::imbalance_warning = " << imbalance_warning << " violates > 0";
    if (out.str().empty()) return std::nullopt;
    return out.str();
}

CubeTestResult run_cube_test(const Packing& packing, const MaterialParams& material,
                             const CubeTestSpec& spec, const ProgressCallback& progress) {
    CubeTestResult r;
    World world = settled_cube_specimen(packing, material, spec, r);
    const Gauges gauges = cube_gauges(world, packing, spec);
    r.time_step = world.time_step();
    r.test = run_platen_compression(world, spec.loading, progress, &gauges, spec.snapshot);
    r.cracks = world.break_events();
    reduce_cube_result(r, spec);
    return r;
}

double mean_particle_density(const Packing& packing) {
    // Paste particles carry the paste they stand for (density paste_density, not the sand's).
    double mass = 0.0, volume = 0.0;
    for (std::size_t i = 0; i < packing.radius.size(); ++i) {
        const double r = packing.radius[i];
        const double v = 4.0 / 3.0 * M_PI * r * r * r;
        const bool paste = i < packing.family.size() && packing.family[i] == kPasteFamily;
        mass += v * (paste ? packing.paste_density : packing.density);
        volume += v;
    }
    return volume > 0.0 ? mass / volume : packing.density;
}

double quasi_static_strain_rate(const Packing& packing, const MaterialParams& material,
                                double expected_peak_strain, double transits) {
    const double wave_speed = std::sqrt(material.contact.effective_modulus / mean_particle_density(packing));
    const double transit = packing.edge() / wave_speed;
    return expected_peak_strain / (transits * transit);
}

}  // namespace gradem::exp
