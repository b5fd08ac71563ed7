#include "experiments/config/paste_config.hpp"

#include <cmath>
#include <utility>

#include "lab_data/dataset.hpp"
#include "common/input_error.hpp"

namespace gradem::exp {
namespace {

using common::InputError;
using namespace common::toml_io;

constexpr double kMm = 1.0e-3;

// "field = v violates rule" from a validator -> "file:line: key 'table.key' = v violates rule".
// The key is the field with its unit suffix (_mm, _kg_m3) when the config spells it so.
[[noreturn]] void invalid(Context& ctx, const std::string& table, const std::string& reason) {
    std::string field = reason.substr(0, reason.find(" = "));
    if (const auto dot = field.find('.'); dot != std::string::npos) field = field.substr(dot + 1);
    std::string key = table + "." + field;
    for (const char* suffix : {"_mm", "_kg_m3"})
        if (!ctx.keys.count(key) && ctx.keys.count(key + suffix)) key += suffix;
    const auto info = ctx.keys.find(key);
    const int line = info == ctx.keys.end() ? 0 : info->second.line;
    const std::string shown = info == ctx.keys.end() ? "" : info->second.text;
    const auto at = reason.find(" violates ");
    throw InputError(ctx.file, line, "key '" + key + "' = " + shown + " violates " +
                                         (at == std::string::npos ? reason : reason.substr(at + 10)));
}

// The dataset sand's specific gravity, or 0.
double dataset_specific_gravity(const CubeConfig& c) {
    if (c.dataset.empty()) return 0.0;
    for (const lab::SandSpec& s : lab::load_dataset_config(c.dataset, false).sands)
        if (s.name == c.sand) return s.specific_gravity;
    return 0.0;
}

void read_mix(Context& ctx, const toml::table& root, const CubeConfig& c, MixDesign& m) {
    Section s(ctx, root, "mix");
    s.real("sand_to_cementitious_volume", m.sand_to_cementitious_volume);
    s.real("water_cement_ratio", m.water_cement_ratio);
    s.real("cement_specific_gravity", m.cement_specific_gravity);
    s.real("sand_specific_gravity", m.sand_specific_gravity);
    s.real("cement_bulk_density_kg_m3", m.cement_bulk_density);
    s.real("sand_bulk_density_kg_m3", m.sand_bulk_density);
    s.real("air_content", m.air_content);
    s.real("hydration_degree", m.hydration_degree);
    s.finish();
    if (ctx.keys["mix.sand_specific_gravity"].line == 0) {
        m.sand_specific_gravity = dataset_specific_gravity(c);
        if (m.sand_specific_gravity <= 0.0)
            throw InputError(ctx.file, ctx.keys["specimen.representation"].line,
                             "key 'mix.sand_specific_gravity' is missing and " +
                                 (c.dataset.empty() ? std::string("the specimen is a sieve_csv")
                                                    : "the dataset's sand '" + c.sand + "' has no specific_gravity") +
                                 ": expected the sand's specific gravity (ASTM C128, e.g. 2.64)");
        ctx.keys["mix.sand_specific_gravity"].text = std::to_string(m.sand_specific_gravity) + " (dataset)";
    }
    if (auto why = m.invalid_reason()) invalid(ctx, "mix", *why);
}

void read_paste(Context& ctx, const toml::table& root, PasteSpec& p, MaterialParams::FamilyBonds& f) {
    Section s(ctx, root, "paste");
    s.real("min_diameter_mm", p.min_diameter, kMm);
    p.max_diameter = p.min_diameter;
    s.real("max_diameter_mm", p.max_diameter, kMm);
    s.real("solid_fraction", p.solid_fraction);
    s.real("overlap_tolerance", p.overlap_tolerance);
    s.real("rsa_scale", p.rsa_scale);
    s.integer("rsa_attempts", p.rsa_attempts);
    s.integer("growth_stages", p.growth_stages);
    s.integer("relax_iterations", p.relax_iterations);
    s.real("memory_fraction", p.memory_fraction);
    s.real("itz_strength_factor", f.itz_strength_factor);
    s.real("itz_modulus_factor", f.itz_modulus_factor);
    std::string sand_sand = f.sand_sand_bonded ? "bonded" : "frictional";
    s.text("sand_sand", sand_sand);
    s.finish();
    if (sand_sand != "bonded" && sand_sand != "frictional")
        throw InputError(ctx.file, ctx.keys["paste.sand_sand"].line,
                         "key 'paste.sand_sand' = \"" + sand_sand + "\": expected \"frictional\" or \"bonded\"");
    f.sand_sand_bonded = sand_sand == "bonded";
    for (const auto& [key, v] : {std::pair<std::string, double>{"itz_strength_factor", f.itz_strength_factor},
                                 std::pair<std::string, double>{"itz_modulus_factor", f.itz_modulus_factor}}) {
        if (!(v > 0.0 && std::isfinite(v)))
            throw InputError(ctx.file, ctx.keys["paste." + key].line,
                             "key 'paste." + key + "' = " + show(v) + " violates > 0");
    }
    if (auto why = p.invalid_reason()) invalid(ctx, "paste", *why);
}

}  // namespace

void read_paste_config(Context& ctx, const toml::table& root, CubeConfig& c) {
    if (c.representation == Representation::parallel_bonds) {
        for (const char* table : {"mix", "paste"})
            if (const toml::node* n = root.get(table))
                throw InputError(ctx.file, line_of(*n), std::string("[") + table +
                                                            "] applies to specimen.representation = \"explicit_paste\" only (it is \"parallel_bonds\")");
        return;
    }
    PasteSettings settings;
    read_mix(ctx, root, c, settings.mix);
    read_paste(ctx, root, settings.paste, c.material.families);
    c.specimen.paste = settings;
}

}  // namespace gradem::exp
