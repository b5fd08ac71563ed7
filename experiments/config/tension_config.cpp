#include "experiments/config/tension_config.hpp"
#include "experiments/config/cube_config_source.hpp"

#include <algorithm>
#include <string>
#include <toml++/toml.h>

#include "common/input_error.hpp"
#include "common/toml_section.hpp"
#include "core/bond_models.hpp"

namespace gradem::exp {
namespace {

// "key 'tension.x' = v violates rule" at the key's line, from a validator's "Struct::x = v violates rule".
[[noreturn]] void reject(common::toml_io::Context& ctx, const std::string& key, const std::string& reason) {
    const common::toml_io::KeyInfo& info = ctx.keys[key];
    const auto at = reason.find(" violates ");
    throw common::InputError(ctx.file, info.line,
                          "key '" + key + "' = " + info.text + " violates " +
                              (at == std::string::npos ? reason : reason.substr(at + 10)));
}

TensionConfig read_tension_config(common::toml_io::Context& ctx, const toml::table& root, const CubeConfig& config);

}  // namespace

TensionConfig load_tension_config(const CubeConfig& config) {
    common::toml_io::Context ctx;
    const toml::table root = common::toml_io::parse_toml_file(config.file, ctx);
    return read_tension_config(ctx, root, config);
}

TensionConfig load_tension_config(const CubeConfig& config, const toml::table& root,
                                  std::map<std::string, common::toml_io::KeyInfo>* keys) {
    common::toml_io::Context ctx;
    ctx.file = config.file.string();
    ctx.dir = std::filesystem::absolute(config.file).parent_path();
    TensionConfig t = read_tension_config(ctx, root, config);
    if (keys) *keys = ctx.keys;
    return t;
}

namespace {

TensionConfig read_tension_config(common::toml_io::Context& ctx, const toml::table& root, const CubeConfig& config) {
    using namespace common::toml_io;
    TensionConfig t;
    t.spec.test = config.test;
    Section s(ctx, root, "tension");
    s.real("grip_depth_fraction", t.spec.grip_depth_fraction);
    s.real("auto_peak_strain", t.auto_peak_strain);
    s.real("auto_transits", t.auto_transits);
    s.finish();
    if (auto why = t.spec.invalid_reason()) {
        // config.test was validated by load_cube_config: only the grips can be wrong here.
        if (why->rfind("TensionTestSpec::grip_depth_fraction", 0) != 0) throw common::InputError(ctx.file, 0, *why);
        reject(ctx, "tension.grip_depth_fraction", *why);
    }
    if (ctx.keys["tension.auto_peak_strain"].line > 0 && !(t.auto_peak_strain > 0.0 && t.auto_peak_strain < 0.01))
        reject(ctx, "tension.auto_peak_strain", "in (0, 0.01)");
    if (!(t.auto_transits >= 10.0 && t.auto_transits <= 10000.0)) reject(ctx, "tension.auto_transits", "in [10, 10000]");
    return t;
}

}  // namespace

double expected_tensile_peak_strain(const MaterialParams& material) {
    const PlatenTestCost row = platen_test_cost(material.bond.model).value_or(PlatenTestCost{});
    const double strain =
        row.tension_peak_over_bond_strain * material.bond.tensile_strength_mean / material.bond.effective_modulus;
    return std::clamp(strain, 1.0e-5, 1.0e-2);
}

double tension_strain_rate(const CubeConfig& config, const TensionConfig& tension, const Packing& packing) {
    if (!config.auto_strain_rate) return config.test.loading.strain_rate;
    const double peak = tension.auto_peak_strain > 0.0 ? tension.auto_peak_strain
                                                       : expected_tensile_peak_strain(config.material);
    return quasi_static_strain_rate(packing, config.material, peak, tension.auto_transits);
}

}  // namespace gradem::exp
