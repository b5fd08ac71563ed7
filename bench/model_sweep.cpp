// gradem-model-sweep: how a bond model's shape parameters move the cube test's shape index
// D = E ε_peak/σ_peak, with its modulus, peak and strain at peak, one JSON row per
// cube test. The lab's D is 1.71 (pre-blended) and 2.10 (Van Buren); the homogeneity of the
// model (calibrate/README.md) lets the calibration rescale E and the peak freely, so D is the
// one number a shape parameter must move for the strain at peak to be met.
//
//   gradem-model-sweep <cube config.toml> [--model M] [--set key=value]...
//                      [--sweep key=v1,v2,...]... [--sands a,b] [--seeds 1,2] [--edge-mm L] [--tension]
//                      [--quiet]
//
// The base material is the config's [material] with --model and every --set applied (keys and
// units of the material table, experiments/config/material_table.hpp; set as the calibration sets them,
// so a strength keeps its cohesion ratio). Each --sweep key is varied alone around the base (one
// at a time), every value on every sand and seed; the base point itself is run once. Packings come
// from the config's packing cache (generated if missing). Run with OMP_NUM_THREADS=1.
// Output, stdout, one object per line:
//   {"model", "param", "value", "sand", "seed", "modulus_gpa", "peak_mpa", "strain_at_peak",
//    "shape_index_d", "particles", "bonds", "broken", "steps", "wall_s", "particle_steps_per_s",
//    "status"}; with --tension each point also runs the direct-tension test of the same packing
// and material (the config's [tension] table) and adds "tensile_mpa", "strength_ratio" (σc/σt),
// "tension_steps" and "tension_wall_s". --quiet: the rows and errors alone (no warnings, e.g.
// about rows of the config's sieve table).
#include <cstdio>
#include <cstdlib>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "bench/bench_args.hpp"
#include "bench/material_settings.hpp"
#include "experiments/config/cube_config.hpp"
#include "experiments/virtual_tests/cube_test.hpp"
#include "experiments/config/material_table.hpp"
#include "experiments/specimen/packing_cache.hpp"
#include "experiments/config/tension_config.hpp"

using namespace gradem;

namespace {

struct Sweep {
    std::string key;
    std::vector<double> values;
};

struct Options {
    std::string config;
    std::string model;
    std::vector<std::pair<std::string, double>> sets;
    std::vector<Sweep> sweeps;
    std::vector<std::string> sands;
    std::vector<std::uint64_t> seeds{1};
    double edge = 0.0;  // [m] 0: the config's genesis.edge_mm
    bool tension = false;
    bool quiet = false;
};

constexpr const char* kUsage =
    "usage: gradem-model-sweep <config.toml> [--model M] [--set key=value]... [--sweep key=v1,v2,...]...\n"
    "                          [--sands a,b] [--seeds 1,2] [--edge-mm L] [--tension] [--quiet]\n";

using bench::parse_number;
using bench::split_list;

Options parse(int argc, char** argv) {
    Options o;
    for (bench::ArgReader args(argc, argv); args.next();) {
        const std::string a = args.arg();
        if (a == "--help" || a == "-h") {
            std::printf("%s\n"
                        "The shape index D = E eps_peak / sigma_peak of the cube test against a bond model's shape parameters:\n"
                        "one JSON row per cube test on stdout (calibrate/README.md \"Shape index D per model\").\n\n"
                        "arguments:\n"
                        "  <config.toml>         cube config TOML; its packing cache is used (generated if missing)\n"
                        "options:\n"
                        "  --model M             bond model of the base material (default: the config's)\n"
                        "  --set key=value       a [material] key of the base (experiments/README.md), repeatable\n"
                        "  --sweep key=v1,v2,... vary one key alone around the base, repeatable\n"
                        "  --sands a,b           sands of the config's dataset (default: the config's sand)\n"
                        "  --seeds 1,2           packing seeds (default 1)\n"
                        "  --edge-mm L           cube edge [mm] of every packing (default: the config's genesis.edge_mm)\n"
                        "  --tension             also run the direct-tension test of each point\n"
                        "%s"
                        "  -h, --help            show this text\n\n%s",
                        kUsage, bench::quiet_help_line("the JSON rows").c_str(), common::exit_status_text("a cube test run failed").c_str());
            std::exit(common::exit_success);
        }
        if (a == "--model") o.model = args.value();
        else if (a == "--set" || a == "--sweep") {
            const std::string v = args.value();
            const auto eq = v.find('=');
            if (eq == std::string::npos) throw bench::UsageError(a + " " + v + ": expected key=value");
            const std::string key = v.substr(0, eq);
            (void)bench::material_row(key);
            if (a == "--set") o.sets.emplace_back(key, parse_number(v.substr(eq + 1), a + " " + key));
            else {
                Sweep s{key, {}};
                s.values = bench::parse_number_list<double>(v.substr(eq + 1), a + " " + key);
                o.sweeps.push_back(s);
            }
        } else if (a == "--sands") o.sands = split_list(args.value());
        else if (a == "--seeds") o.seeds = bench::parse_number_list<std::uint64_t>(args.value(), a);
        else if (a == "--edge-mm") {
            o.edge = parse_number(args.value(), a) * 1e-3;
            if (!(o.edge > 0.0)) throw bench::UsageError("--edge-mm: expected a positive cube edge [mm]");
        } else if (a == "--tension") o.tension = true;
        else if (a == "--quiet") o.quiet = true;
        else if (o.config.empty() && a.rfind("--", 0) != 0) o.config = a;
        else throw bench::UsageError("unknown argument '" + a + "'");
    }
    if (o.config.empty()) throw bench::UsageError(std::string("no cube config given: ") + kUsage);
    return o;
}

std::string json_string(const std::string& s) { return "\"" + s + "\""; }

/// `, "tensile_mpa": ..` for the direct-tension test of this packing and material.
std::string tension_fields(const exp::CubeConfig& c, const exp::Packing& packing, const exp::MaterialParams& material,
                           double peak) {
    exp::CubeConfig config = c;
    config.material = material;
    const exp::TensionConfig tension = exp::load_tension_config(config);
    exp::TensionTestSpec spec = tension.spec;
    spec.test.snapshot = {};
    spec.test.loading.platen_friction = material.platen_friction;
    spec.test.loading.strain_rate = exp::tension_strain_rate(config, tension, packing);
    const exp::TensionTestResult t = exp::run_tension_test(packing, material, spec);
    const double st = t.cube.macro.peak_stress_pa;
    char buf[256];
    std::snprintf(buf, sizeof buf, ", \"tensile_mpa\": %.5g, \"strength_ratio\": %.4g, \"tension_steps\": %lld, \"tension_wall_s\": %.3f",
                  st * 1e-6, st > 0.0 ? peak / st : 0.0, static_cast<long long>(t.cube.test.steps), t.cube.test.wall_seconds);
    return buf;
}

void run_point(const exp::CubeConfig& base, const exp::MaterialParams& material, const std::string& param,
               double value, const Options& o) {
    if (auto why = material.invalid_reason()) throw bench::UsageError(param + " = " + std::to_string(value) + ": " + *why);
    for (const std::string& sand : o.sands) {
        exp::CubeConfig c = base;
        c.sand = sand;
        const lab::GradationCurve curve = exp::load_gradation(c);
        for (std::uint64_t seed : o.seeds) {
            exp::SpecimenSpec spec = c.specimen;
            spec.seed = seed;
            const exp::Packing packing = exp::load_or_generate(curve, spec, c.cache_dir);
            exp::CubeTestSpec test = c.test;
            test.snapshot = {};
            test.loading.platen_friction = material.platen_friction;
            test.loading.strain_rate = c.auto_strain_rate ? exp::quasi_static_strain_rate(packing, material)
                                                          : c.test.loading.strain_rate;
            const exp::CubeTestResult r = exp::run_cube_test(packing, material, test);
            const double e = r.macro.chord_modulus_pa, peak = r.macro.peak_stress_pa, eps = r.macro.strain_at_peak;
            const double wall = r.test.wall_seconds;
            std::printf(
                "{\"model\": %s, \"param\": %s, \"value\": %.6g, \"sand\": %s, \"seed\": %llu, \"modulus_gpa\": %.5g, "
                "\"peak_mpa\": %.5g, \"strain_at_peak\": %.5g, \"shape_index_d\": %.4f, \"particles\": %zu, "
                "\"bonds\": %zu, \"broken\": %zu, \"steps\": %lld, \"wall_s\": %.3f, \"particle_steps_per_s\": %.4g, "
                "\"status\": %s%s}\n",
                json_string(bond_model_name(material.bond.model)).c_str(), json_string(param).c_str(), value,
                json_string(sand).c_str(), static_cast<unsigned long long>(seed), e * 1e-9, peak * 1e-6, eps,
                peak > 0.0 ? e * eps / peak : 0.0, r.particles, r.bonds, r.cracks.size(),
                static_cast<long long>(r.test.steps), wall,
                wall > 0.0 ? static_cast<double>(r.particles) * static_cast<double>(r.test.steps) / wall : 0.0,
                json_string(r.diverged() ? "diverged" : r.test.stop_reason).c_str(),
                o.tension ? tension_fields(c, packing, material, peak).c_str() : "");
            std::fflush(stdout);
        }
    }
}

}  // namespace

int main(int argc, char** argv) {
    return bench::run_main("gradem-model-sweep", [&] {
        Options o = parse(argc, argv);
        if (o.quiet) bench::be_quiet(true);
        exp::CubeConfig base = exp::load_cube_config(o.config);
        if (o.edge > 0.0) {
            base.specimen.genesis.edge = o.edge;
            if (const auto why = base.specimen.invalid_reason()) throw bench::UsageError("--edge-mm: " + *why);
        }
        if (o.sands.empty()) o.sands = {base.sand};
        exp::MaterialParams material = base.material;
        if (!o.model.empty()) {
            const auto m = parse_bond_model(o.model);
            if (!m) throw bench::UsageError("--model " + o.model + ": unknown (known: " + exp::bond_model_names() + ")");
            material.bond.model = *m;
        }
        for (const auto& [key, v] : o.sets) bench::apply_material_value(material, key, v);
        run_point(base, material, "base", 0.0, o);
        for (const Sweep& s : o.sweeps)
            for (double v : s.values) {
                exp::MaterialParams m = material;
                bench::apply_material_value(m, s.key, v);
                run_point(base, m, s.key, v, o);
            }
        return 0;
    });
}
