#pragma once
// The settings of an explicit-paste specimen: the mix design and how the paste
// particles are made (experiments/paste/paste_fill.hpp), carried by SpecimenSpec::paste so every
// command that loads a specimen (compress, tension, calibrate, study) gets them unchanged.
#include <cstdint>
#include <optional>
#include <string>

#include "experiments/paste/paste_mix.hpp"

namespace gradem::exp {

inline constexpr std::uint8_t kSandFamily = 0;   ///< ParticleSet::family of sand grains
inline constexpr std::uint8_t kPasteFamily = 1;  ///< ... of paste particles

struct PasteSpec {
    double min_diameter = 0.1e-3;      ///< smallest paste particle [m]
    double max_diameter = 0.1e-3;      ///< largest [m]; = min_diameter: one coarse-grained size
    double solid_fraction = 0.3;       ///< paste particle volume / paste volume, in (0, 0.74] [-]; with
                                       ///< sand at 0.5 the total solid fraction is 0.65, below jamming
    double overlap_tolerance = 0.02;   ///< largest overlap left / smaller radius, in (0, 0.2] [-]
    double rsa_scale = 0.6;            ///< radius scale during RSA, in (0, 1] [-]
    int rsa_attempts = 200;            ///< RSA tries per particle, >= 1
    int growth_stages = 8;             ///< radius growth stages to full size, >= 1
    int relax_iterations = 3000;       ///< relaxation sweeps per stage, >= 1
    double memory_fraction = 0.5;      ///< refuse specimens estimated above this × physical memory, in (0, 1] [-]
    [[nodiscard]] std::optional<std::string> invalid_reason() const;
};

struct PasteSettings {
    MixDesign mix;
    PasteSpec paste;
};

}  // namespace gradem::exp
