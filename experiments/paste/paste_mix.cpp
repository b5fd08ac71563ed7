#include "experiments/paste/paste_mix.hpp"

#include <cmath>
#include <stdexcept>

namespace gradem::exp {
namespace {

constexpr double kPowersWaterPerHydration = 0.359;  // w/c consumed (chemically + gel) per unit α (Powers & Brownyard)

std::string violates(const char* field, double v, const char* rule) {
    return std::string(field) + " = " + std::to_string(v) + " violates " + rule;
}

bool positive(double v) { return std::isfinite(v) && v > 0.0; }

}  // namespace

std::optional<std::string> MixDesign::invalid_reason() const {
    if (!positive(sand_to_cementitious_volume)) return violates("sand_to_cementitious_volume", sand_to_cementitious_volume, "> 0");
    if (!positive(water_cement_ratio)) return violates("water_cement_ratio", water_cement_ratio, "> 0");
    if (!positive(cement_specific_gravity)) return violates("cement_specific_gravity", cement_specific_gravity, "> 0");
    if (!positive(sand_specific_gravity))
        return violates("sand_specific_gravity", sand_specific_gravity,
                        "> 0 (give [mix] sand_specific_gravity or the dataset sand's specific_gravity)");
    if (!positive(cement_bulk_density)) return violates("cement_bulk_density", cement_bulk_density, "> 0");
    if (!positive(sand_bulk_density)) return violates("sand_bulk_density", sand_bulk_density, "> 0");
    if (cement_bulk_density >= cement_specific_gravity * kWaterDensity)
        return violates("cement_bulk_density", cement_bulk_density, "< cement_specific_gravity x 1000 kg/m3 (a bulk density below the particle density)");
    if (sand_bulk_density >= sand_specific_gravity * kWaterDensity)
        return violates("sand_bulk_density", sand_bulk_density, "< sand_specific_gravity x 1000 kg/m3 (a bulk density below the particle density)");
    if (!(air_content >= 0.0 && air_content < 0.5)) return violates("air_content", air_content, "in [0, 0.5)");
    if (!(hydration_degree >= 0.0 && hydration_degree <= 1.0)) return violates("hydration_degree", hydration_degree, "in [0, 1]");
    if (water_cement_ratio < kPowersWaterPerHydration * hydration_degree)
        return violates("hydration_degree", hydration_degree,
                        "<= water_cement_ratio / 0.359 (Powers: not enough water to hydrate that far)");
    return std::nullopt;
}

MixFractions mix_fractions(const MixDesign& mix) {
    if (auto why = mix.invalid_reason()) throw std::invalid_argument(*why);
    // Per unit loose bulk volume of cementitious material.
    const double m_c = mix.cement_bulk_density;
    const double m_s = mix.sand_bulk_density * mix.sand_to_cementitious_volume;
    const double m_w = mix.water_cement_ratio * m_c;
    const double v_c = m_c / (mix.cement_specific_gravity * kWaterDensity);
    const double v_s = m_s / (mix.sand_specific_gravity * kWaterDensity);
    const double v_w = m_w / kWaterDensity;
    const double scale = (1.0 - mix.air_content) / (v_c + v_s + v_w);
    MixFractions f;
    f.sand = v_s * scale;
    f.cement = v_c * scale;
    f.water = v_w * scale;
    f.paste = f.cement + f.water;
    f.air = mix.air_content;
    // Powers: per unit mass of cement the paste holds w/c + 1/SG_c of volume (in units of ρ_w).
    const double wc = mix.water_cement_ratio, alpha = mix.hydration_degree;
    const double paste_per_cement = wc + 1.0 / mix.cement_specific_gravity;
    f.paste_capillary = (wc - kPowersWaterPerHydration * alpha) / paste_per_cement;
    f.paste_unhydrated = (1.0 - alpha) / mix.cement_specific_gravity / paste_per_cement;
    f.paste_hydrates = 1.0 - f.paste_capillary - f.paste_unhydrated;
    f.sand_to_cement_mass = m_s / m_c;
    f.paste_density = (m_c + m_w) / (v_c + v_w);
    return f;
}

}  // namespace gradem::exp
