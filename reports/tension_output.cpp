#include "reports/tension_output.hpp"

#include <cmath>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "common/atomic_file.hpp"
#include "common/input_error.hpp"
#include "common/json_file.hpp"
#include "common/json_number.hpp"

namespace gradem::report {

using namespace gradem::exp;  // the virtual tests' types these outputs are written from

namespace {

using json = nlohmann::ordered_json;

constexpr double kMpa = 1.0e-6, kMm = 1.0e3;  // SI -> display unit

constexpr auto num = common::json_number<json>;  // a number, or null when it is not finite

// The compression-format document of the tension result (cube_output's macro_json): the
// blocks both tests share (reduction, run, breaks, warnings, material, specimen, rate check)
// are written by the same code.
json shared_document(const TensionTestResult& r, const CubeConfig& c, const Packing& k, double strain_rate,
                     const std::optional<RateCheck>& rate_check) {
    return json::parse(macro_json(r.cube, c, k, strain_rate, rate_check));
}

double ratio(double numerator, double denominator) {
    return std::isfinite(numerator) && std::isfinite(denominator) && denominator != 0.0 ? numerator / denominator
                                                                                         : std::nan("");
}

json read_compression_document(const std::filesystem::path& file) {
    const std::string name = file.string();
    std::error_code ec;
    if (!std::filesystem::exists(file, ec))
        throw common::InputError(name, 0, "no such file (the compression macro.json: `gradem compress` writes it)");
    const json doc = common::read_json_file<json>(file, "the compression macro.json");
    if (!doc.is_object() || doc.contains("tensile_strength_mpa") || !doc.contains("peak_stress_mpa") ||
        !doc["peak_stress_mpa"].is_number())
        throw common::InputError(name, 0, "not the macro.json of a compression test (`gradem compress`): expected a "
                                       "numeric peak_stress_mpa and no tensile_strength_mpa");
    return doc;
}

}  // namespace

void check_compression_file(const std::filesystem::path& file) { (void)read_compression_document(file); }

CompressionReference read_compression_reference(const std::filesystem::path& file, const CubeConfig& c,
                                                const Packing& k) {
    const std::string name = file.string();
    json doc = read_compression_document(file);
    const json mine = shared_document(TensionTestResult{}, c, k, 0.0, std::nullopt);  // material, specimen: no result needed
    for (const char* block : {"material", "specimen"})
        if (!doc.contains(block) || doc[block] != mine[block])
            throw common::InputError(name, 0, std::string("the compression test was run with another ") + block +
                                               " than this tension test ('" + block +
                                               "' differs): run `gradem compress` on the same config");
    CompressionReference ref;
    ref.file = file;
    ref.peak_stress = doc["peak_stress_mpa"].get<double>() / kMpa;
    ref.chord_modulus = doc.contains("chord_modulus_mpa") && doc["chord_modulus_mpa"].is_number()
                            ? doc["chord_modulus_mpa"].get<double>() / kMpa
                            : std::nan("");
    return ref;
}

std::string tension_macro_json(const TensionTestResult& r, const CubeConfig& c, const TensionTestSpec& spec,
                               const Packing& k, double strain_rate, const std::optional<RateCheck>& rate_check,
                               const std::optional<CompressionReference>& compression) {
    json base = shared_document(r, c, k, strain_rate, rate_check);
    const lab::CurveReduction& m = r.cube.macro;
    json reduction = base["reduction"];
    reduction["chord_lower_strain"] = num(r.chord_lower_strain);
    json compared = nullptr;
    double strength_ratio = std::nan("");
    if (compression) {
        strength_ratio = ratio(compression->peak_stress, m.peak_stress_pa);
        compared = {{"macro_json", compression->file.string()},
                    {"peak_stress_mpa", num(compression->peak_stress * kMpa)},
                    {"chord_modulus_mpa", num(compression->chord_modulus * kMpa)},
                    {"strength_ratio_c_over_t", num(strength_ratio)},
                    {"modulus_ratio_t_over_c", num(ratio(m.chord_modulus_pa, compression->chord_modulus))}};
    }
    json j = {
        {"config", c.file.string()},
        {"test", "direct tension"},
        {"sign_convention", "tension positive: stress, strain at peak, moduli; lateral strain expansion positive"},
        {"tensile_strength_mpa", num(m.peak_stress_pa * kMpa)},
        {"strain_at_peak", num(m.strain_at_peak)},
        {"strain_at_peak_platen", num(r.cube.strain_at_peak_platen)},
        {"tensile_modulus_mpa", num(m.chord_modulus_pa * kMpa)},
        {"tangent_modulus_mpa", num(m.tangent_modulus_pa * kMpa)},
        {"poisson_ratio", num(m.poisson_ratio)},
        {"strength_ratio_c_over_t", num(strength_ratio)},
        {"compression", compared},
        {"reduction", reduction},
        {"grips", {{"depth_fraction", spec.grip_depth_fraction},
                   {"depth_mm", r.grip_depth * kMm},
                   {"reach_mm", r.grip_reach * kMm},
                   {"grains_bottom", r.grip_grains_bottom},
                   {"grains_top", r.grip_grains_top},
                   {"max_slip_m", num(r.grip_slip)},
                   {"max_spin_rad_s", num(r.grip_spin)}}},
        {"run", base["run"]},
        {"broken_bonds", base["broken_bonds"]},
        {"warnings", base["warnings"]},
        {"material", base["material"]},
        {"specimen", base["specimen"]},
    };
    if (base.contains("rate_check")) j["rate_check"] = base["rate_check"];
    return j.dump(2) + "\n";
}

void write_tension_outputs(const std::filesystem::path& dir, const TensionTestResult& r, const CubeConfig& c,
                           const TensionTestSpec& spec, const Packing& k, double strain_rate,
                           const std::optional<RateCheck>& rate_check,
                           const std::optional<CompressionReference>& compression) {
    common::write_file_atomically(dir / "load_curve.csv", load_curve_csv(r.cube));
    common::write_file_atomically(dir / "cracks.csv", cracks_csv(r.cube));
    common::write_file_atomically(dir / "macro.json",
                                  tension_macro_json(r, c, spec, k, strain_rate, rate_check, compression));
}

}  // namespace gradem::report
