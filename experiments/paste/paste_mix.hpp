#pragma once
// Mix design -> volume fractions of a mortar (docs/genesis.md "Mix design"). The study's Type S mortar
// is batched by LOOSE BULK volume (ASTM C270 proportions, cementitious : sand = 1 : 2.6) with
// w/c = 0.53 by mass. Per unit bulk volume of cementitious material:
//     m_c = ρ_bulk,c · 1,          m_s = ρ_bulk,s · r,          m_w = (w/c) · m_c          [kg]
//     V_c = m_c / (SG_c ρ_w),      V_s = m_s / (SG_s ρ_w),      V_w = m_w / ρ_w            [m³]
// (absolute volumes), and with an air content a (volume fraction of the mortar) every
// fraction is V_x (1 - a) / (V_c + V_s + V_w). The fresh paste is cement + water.
// Powers' model (Powers & Brownyard) splits the paste at a
// degree of hydration α:  capillary pores φ_cap = (w/c - 0.359 α) / (w/c + 1/SG_c),
// unhydrated cement (1 - α)(1/SG_c) / (w/c + 1/SG_c), hydrates = the rest.
// Simplifications (stated): the cementitious material is treated as portland cement (the
// study's hydrated lime, ≈ 1/3 of the cementitious bulk volume, is not split out); bulk densities
// default to ASTM C270's 94 lb/ft³ (cement) and 80 lb/ft³ (damp loose sand).
#include <optional>
#include <string>

namespace gradem::exp {

inline constexpr double kWaterDensity = 1000.0;  ///< ρ_w [kg/m³]

struct MixDesign {
    double sand_to_cementitious_volume = 2.6;  ///< r, loose bulk volumes (the study: 1 : 2.6) [-]
    double water_cement_ratio = 0.53;          ///< w/c by mass (the study) [-]
    double cement_specific_gravity = 3.15;     ///< SG_c [-]
    double sand_specific_gravity = 0.0;        ///< SG_s [-]; 0: not given (an error)
    double cement_bulk_density = 1506.0;       ///< loose bulk density of cement [kg/m³] (94 lb/ft³)
    double sand_bulk_density = 1280.0;         ///< damp loose bulk density of sand [kg/m³] (80 lb/ft³)
    double air_content = 0.0;                  ///< entrapped air, volume fraction of the mortar [-]
    double hydration_degree = 0.0;             ///< α for Powers' split of the paste, in [0, 1] [-]
    /// "field = v violates rule" (field names as the [mix] keys without units), or nullopt.
    [[nodiscard]] std::optional<std::string> invalid_reason() const;
};

/// Volume fractions of the mortar (sand + paste + air = 1) and of the paste's phases.
struct MixFractions {
    double sand = 0.0;     ///< sand grains [-]
    double cement = 0.0;   ///< cement (absolute volume) [-]
    double water = 0.0;    ///< mixing water [-]
    double paste = 0.0;    ///< cement + water [-]
    double air = 0.0;      ///< voids [-]
    // Powers' split, as fractions of the PASTE volume (sum 1).
    double paste_capillary = 0.0;    ///< capillary pores [-]
    double paste_unhydrated = 0.0;   ///< unhydrated cement [-]
    double paste_hydrates = 0.0;     ///< hydration products (gel incl. gel pores) [-]
    double sand_to_cement_mass = 0.0;  ///< m_s / m_c [-]
    double paste_density = 0.0;      ///< fresh paste (m_c + m_w)/(V_c + V_w) [kg/m³]
};

/// The fractions of a valid design; throws std::invalid_argument with invalid_reason().
MixFractions mix_fractions(const MixDesign& mix);

}  // namespace gradem::exp
