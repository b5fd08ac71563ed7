// gradem-bench: throughput of the DEM core on a dense bonded polydisperse packing (radius ratio
// 3, every initial near-contact bonded, ~2.5 bonds per particle) compressed between moving
// platens. Prints, per size and thread count: N, bonds, steps, wall seconds, particle-steps per
// second, per-phase times, bytes per particle (World arrays and peak RSS), and the 1 -> 2 thread
// speed-up. Not a test: numbers depend on the machine; quote medians of several runs. --quiet
// prints nothing but errors and, with --json, the JSON rows.
//
//   gradem-bench [--sizes 20000,200000] [--steps 1000] [--threads 1,2] [--repeat 3] [--json] [--quiet]
//                [--models M1,M2,...]   (one row set per bond law of core/bond_models.hpp; its JSON
//                rows carry every parameter of the law)
//                [--set [model:]key=value]... [--sweep [model:]key=v1,v2,...]   (material keys,
//                bench/material_settings.hpp; a sweep gives one row set per value)
//                [--specimens 20000,200000] [--cache-dir DIR]
//                (rows on genesis packings of the pre-blended sand, bonded as a calibration does:
//                bench/specimen_bench.hpp; without --sizes, only these)
//   gradem-bench --neighbors 200000 [--threads 1,2] [--repeat 3] [--json]   (neighbour search
//                at size ratios 1, 10, 50 instead: bench/neighbor_bench.cpp)
//   gradem-bench --genesis 20000,200000 [--json]   (genesis rows instead: bench/genesis_bench.cpp)
//   gradem-bench --full-cube [--min-diameter-mm 0.149] [--timed 200000] [--steps 100] [--threads 2]
//                [--transits 160] [--time-step S] [--json]   (the full-size cube's N, memory, seconds per 1000
//                steps and whole-test estimate: bench/full_cube_bench.cpp)
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <iostream>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include "bench/bench_args.hpp"
#include "bench/neighbor_bench.hpp"
#include "core/openmp_policy.hpp"
#include "core/parallel.hpp"
#include "bench/full_cube_bench.hpp"
#include "bench/genesis_bench.hpp"
#include "bench/material_settings.hpp"
#include "bench/specimen_bench.hpp"
#include "core/world.hpp"
#include "experiments/virtual_tests/platen_compression.hpp"
#include "experiments/specimen/quick_packing.hpp"

using namespace gradem;

namespace {

struct Options {
    std::vector<std::int64_t> sizes{20000, 200000};
    std::vector<int> threads{1, 2};
    std::int64_t steps = 1000;
    int repeat = 3;
    bool json = false;
    bool quiet = false;
    std::int64_t neighbors = 0;  ///< > 0: neighbour-search rows for this many particles
    std::vector<std::int64_t> genesis;  ///< genesis rows at these grain counts (then nothing else)
    bool full_cube = false;             ///< the full-size cube's figures (then nothing else)
    bool steps_given = false, sizes_given = false;
    std::vector<BondModel> models{BondModel::parallel_bond};
    std::vector<std::int64_t> specimens;          ///< genesis specimens of about these grain counts
    std::string cache_dir = "out/packing-cache";  ///< their packing cache
    std::vector<bench::MaterialSetting> sets;     ///< --set: material keys of every row
    std::optional<bench::MaterialSetting> sweep;  ///< --sweep: one row set per value
    bench::FullCubeOptions cube;        ///< --full-cube settings
};

/// Every bond model's name, comma separated, in BondModel order.
std::string model_list() {
    std::string out;
    for (const char* name : kBondModelNames) out += (out.empty() ? "" : ",") + std::string(name);
    return out;
}

const std::string kHelp =
    "usage: gradem-bench [--sizes N1,N2,...] [--steps S] [--threads 1,2] [--repeat R] [--json] [--quiet]\n"
    "                    [--models " + model_list() + "]\n"
    "                    [--set [model:]key=value]... [--sweep [model:]key=v1,v2,...]\n"
    "                    [--specimens N1,N2,...] [--cache-dir DIR]\n"
    "       gradem-bench --neighbors N [--threads 1,2] [--repeat R] [--json]\n"
    "       gradem-bench --genesis N1,N2,... [--json]\n"
    "       gradem-bench --full-cube [--min-diameter-mm D] [--timed N] [--steps S] [--threads T]\n"
    "                    [--transits X] [--time-step S] [--json]\n"
    "\n"
    "Throughput of the DEM core on a bonded packing between closing platens (bench/README.md); not a test.\n"
    "\n"
    "options:\n"
    "  --sizes N1,N2,...     packing sizes (default 20000,200000)\n"
    "  --steps S             timed steps per run (default 1000; --full-cube: 100)\n"
    "  --threads 1,2         OpenMP thread counts (--full-cube: the last one)\n"
    "  --repeat R            runs per row, the median is printed (default 3)\n"
    "  --models M1,M2        bond laws, one row set each (default parallel_bond)\n"
    "  --specimens N1,N2     rows on genesis packings of the pre-blended sand of about these grain counts,\n"
    "                        bonded as a calibration does (without --sizes: only these rows)\n"
    "  --cache-dir DIR       packing cache of --specimens (default out/packing-cache)\n"
    "  --set [M:]key=value   a material key (config units, experiments/README.md) on every row, or on\n"
    "                        model M's rows only; e.g. bond_gap_um=20 (specimens: default 70; lattice:\n"
    "                        the packing's own gap), bonded_fraction=0.75; repeatable\n"
    "  --sweep [M:]key=v1,v2 one row set per value of a material key (the rows of models without it: one)\n"
    "  --neighbors N         neighbour-search rows at size ratios 1, 10, 50 instead\n"
    "  --genesis N1,N2,...   genesis rows instead\n"
    "  --full-cube           the full-size cube's N, memory, seconds per 1000 steps and whole-test estimate\n"
    "  --min-diameter-mm D   --full-cube: lower cut of the gradation (default 0.149)\n"
    "  --timed N             --full-cube: spheres of the timed packing (default 200000, at least 1000)\n"
    "  --transits X          --full-cube: wave transits to the stop of a test (default 160)\n"
    "  --time-step S         --full-cube: time step of the real specimen [s] (default: the timed one's)\n"
    "  --json                one JSON object per row instead of the table\n";

template <class T>
std::vector<T> parse_list(const std::string& s, const std::string& option) {
    return bench::parse_number_list<T>(s, option);
}

template <class T>
T parse_one(const std::string& s, const std::string& option) {
    return static_cast<T>(bench::parse_number(s, option));
}

Options parse(int argc, char** argv) {
    Options o;
    for (bench::ArgReader args(argc, argv); args.next();) {
        const std::string a = args.arg();
        auto value = [&] { return args.value(); };
        if (a == "--sizes") o.sizes = parse_list<std::int64_t>(value(), a), o.sizes_given = true;
        else if (a == "--specimens") o.specimens = parse_list<std::int64_t>(value(), a);
        else if (a == "--cache-dir") o.cache_dir = value();
        else if (a == "--set") o.sets.push_back(bench::parse_material_setting(a, value()));
        else if (a == "--sweep") o.sweep = bench::parse_material_setting(a, value());
        else if (a == "--threads") o.threads = parse_list<int>(value(), a);
        else if (a == "--steps") o.steps = parse_one<std::int64_t>(value(), a), o.steps_given = true;
        else if (a == "--full-cube") o.full_cube = true;
        else if (a == "--transits") o.cube.transits_to_stop = parse_one<double>(value(), a);
        else if (a == "--timed") o.cube.timed = parse_one<std::int64_t>(value(), a);
        else if (a == "--time-step") o.cube.time_step = parse_one<double>(value(), a);
        else if (a == "--min-diameter-mm") o.cube.min_diameter = 1e-3 * parse_one<double>(value(), a);
        else if (a == "--repeat") o.repeat = parse_one<int>(value(), a);
        else if (a == "--json") o.json = true;
        else if (a == "--quiet") o.quiet = true;
        else if (a == "--neighbors") o.neighbors = parse_one<std::int64_t>(value(), a);
        else if (a == "--genesis") o.genesis = parse_list<std::int64_t>(value(), a);
        else if (a == "--models") {
            o.models.clear();
            for (const std::string& name : bench::split_list(value())) {
                const auto m = parse_bond_model(name);
                if (!m) throw bench::UsageError("--models: unknown bond model '" + name + "'");
                o.models.push_back(*m);
            }
        }
        else if (a == "--help" || a == "-h") {
            std::cout << kHelp << bench::quiet_help_line("(with --json) the JSON rows") << "  -h, --help            show this text\n\n"
                      << common::exit_status_text("the benchmark run failed");
            std::exit(common::exit_success);
        } else throw bench::UsageError("unknown option '" + a + "'");
    }
    if (o.steps < 1 || o.repeat < 1 || o.sizes.empty() || o.threads.empty())
        throw bench::UsageError("--steps, --repeat, --sizes and --threads must be positive");
    for (std::int64_t n : o.specimens)
        if (n < 100) throw bench::UsageError("--specimens must be at least 100 grains");
    if (!o.specimens.empty() && !o.sizes_given) o.sizes.clear();
    if (!(o.cube.min_diameter > 0.0) || o.cube.timed < 1000 || !(o.cube.transits_to_stop > 0.0) || !(o.cube.time_step >= 0.0))
        throw bench::UsageError("--min-diameter-mm and --transits must be > 0, --time-step >= 0, --timed >= 1000");
    return o;
}

using bench::peak_rss_bytes;

/// One row's set-up: the packing it runs on and the bonds.
struct RowCase {
    const char* packing = "lattice";      ///< "lattice" (quick packing) or "genesis"
    const exp::QuickPacking* lattice = nullptr;
    const exp::Packing* specimen = nullptr;
    bench::BondCase bond;
    std::string swept_key;  ///< the --sweep key this row set has a value of ("" none)
    double swept_value = 0.0;
};

struct Sample {
    RowCase row;
    BondParams bond_params;
    double gap_um = 0.0;  ///< the bonding gap used [um]
    std::int64_t n = 0, bonds = 0, steps = 0;
    int threads = 1;
    double seconds = 0, build_seconds = 0;
    StepProfile profile;
    std::size_t world_bytes = 0, rss = 0;
    std::int64_t contacts = 0, pairs = 0;
};

/// The material of a lattice row: contact and bond E* 10 GPa, k_n/k_s 1.5, μ 0.5, σ̄_c 8 MPa, c̄
/// 16 MPa (cv 0.2), every law's other parameters at their defaults; then the case's settings.
exp::MaterialParams lattice_material(const bench::BondCase& c) {
    const exp::MaterialParams m = bench::bench_material(c.model, 10.0e9, 8.0e6, 16.0e6, 0.0, c.settings);
    if (auto why = m.bond.invalid_reason()) throw bench::UsageError(*why);
    return m;
}

/// The bonding gap of a lattice row [m]: the material's if bond_gap_um is set, else the packing's.
double lattice_gap(const exp::QuickPacking& packing, const exp::MaterialParams& m) {
    return m.bond_gap_absolute > 0.0 ? m.bond_gap_absolute : packing.bond_gap;
}

// A bonded lattice packing between platens closing at a strain rate of 1/s (typical test speed).
World make_world(const exp::QuickPacking& packing, const exp::MaterialParams& m) {
    World world(packing.particles, m.contact, SimParams{});
    world.install_bonds(m.bond, lattice_gap(packing, m));
    exp::add_platens(world, 0.5);
    const double height = world.walls()[1].point.z - world.walls()[0].point.z;
    world.wall(0).velocity = {0, 0, 0.5 * height};
    world.wall(1).velocity = {0, 0, -0.5 * height};
    return world;
}

World make_row_world(const RowCase& row, double& gap_um) {
    if (row.specimen) {
        const exp::MaterialParams m = bench::specimen_material(row.bond);
        gap_um = 1e6 * m.bond_gap_absolute;
        return bench::specimen_world(*row.specimen, m);
    }
    const exp::MaterialParams m = lattice_material(row.bond);
    gap_um = 1e6 * lattice_gap(*row.lattice, m);
    return make_world(*row.lattice, m);
}

Sample run_once(const RowCase& row, int threads, std::int64_t steps) {
#ifdef _OPENMP
    omp_set_num_threads(threads);
#endif
    Sample s;
    s.row = row;
    const auto t0 = std::chrono::steady_clock::now();
    World world = make_row_world(row, s.gap_um);
    world.run(20);  // first neighbour build, time step, caches warm
    const auto t1 = std::chrono::steady_clock::now();
    const StepProfile before = world.profile();
    world.run(steps);
    const auto t2 = std::chrono::steady_clock::now();
    s.bond_params = world.bond_params();
    s.n = static_cast<std::int64_t>(world.particles().size());
    s.bonds = static_cast<std::int64_t>(world.intact_bond_count());
    s.steps = steps;
    s.threads = threads;
    s.build_seconds = std::chrono::duration<double>(t1 - t0).count();
    s.seconds = std::chrono::duration<double>(t2 - t1).count();
    const StepProfile& after = world.profile();
    s.profile.neighbors = after.neighbors - before.neighbors;
    s.profile.contacts = after.contacts - before.contacts;
    s.profile.bonds = after.bonds - before.bonds;
    s.profile.walls = after.walls - before.walls;
    s.profile.integrate = after.integrate - before.integrate;
    s.profile.rebuilds = after.rebuilds - before.rebuilds;
    s.profile.bond_lane_steps = after.bond_lane_steps - before.bond_lane_steps;
    s.profile.bond_scalar_steps = after.bond_scalar_steps - before.bond_scalar_steps;
    s.profile.pair_steps_into_particles = after.pair_steps_into_particles - before.pair_steps_into_particles;
    s.world_bytes = world.memory_bytes();
    s.rss = peak_rss_bytes();
    s.pairs = static_cast<std::int64_t>(world.pair_count());
    s.contacts = static_cast<std::int64_t>(world.active_contact_count());
    if (world.status() != RunStatus::running) bench::warn("gradem-bench", "run diverged: " + world.status_reason());
    return s;
}

Sample median_of(std::vector<Sample> runs) {
    std::sort(runs.begin(), runs.end(), [](const Sample& a, const Sample& b) { return a.seconds < b.seconds; });
    return runs[runs.size() / 2];
}

/// Every parameter of the law as JSON members ("radial_elements": 1, ...).
void print_law_rows(const BondParams& params) {
    visit_bond_law(params.model, [&](auto kernel) {
        using Law = decltype(kernel);
        const typename Law::Params& own = law_params<Law>(params);
        for (const auto& row : Law::kParameters) {
            if (row.field.integer)
                std::printf("\"%.*s\": %lld, ", static_cast<int>(row.key.size()), row.key.data(),
                            static_cast<long long>(row.field.get_int(own)));
            else std::printf("\"%.*s\": %.6g, ", static_cast<int>(row.key.size()), row.key.data(), row.field.get(own));
        }
    });
}

void print_sample(const Sample& s, double speedup, bool json) {
    const double pss = static_cast<double>(s.n) * static_cast<double>(s.steps) / s.seconds;
    const double per = static_cast<double>(s.n);
    // bond-steps of the timed steps by the path of the law's own pass (none: 0 and 0)
    const std::int64_t lane = s.profile.bond_lane_steps, scalar = s.profile.bond_scalar_steps;
    const double scalar_share = lane + scalar > 0 ? static_cast<double>(scalar) / static_cast<double>(lane + scalar) : 0.0;
    // pair-steps whose forces the bond law's pass added to both particles (no slot written)
    const double pair_steps = static_cast<double>(s.pairs) * static_cast<double>(s.steps);
    const double into_particles = pair_steps > 0 ? static_cast<double>(s.profile.pair_steps_into_particles) / pair_steps : 0.0;
    if (json) {
        std::printf("{\"model\": \"%s\", ", bond_model_name(s.bond_params.model));
        print_law_rows(s.bond_params);
        if (!s.row.swept_key.empty()) std::printf("\"sweep\": \"%s\", \"sweep_value\": %.6g, ", s.row.swept_key.c_str(), s.row.swept_value);
        std::printf("\"n\": %lld, \"bonds\": %lld, \"pairs\": %lld, \"contacts\": %lld, \"threads\": %d, "
                    "\"steps\": %lld, \"seconds\": %.4f, \"particle_steps_per_s\": %.4g, "
                    "\"neighbors_s\": %.4f, \"contacts_s\": %.4f, \"bonds_s\": %.4f, \"walls_s\": %.4f, "
                    "\"integrate_s\": %.4f, \"rebuilds\": %lld, \"bytes_per_particle\": %.1f, "
                    "\"peak_rss_bytes_per_particle\": %.1f, \"speedup_vs_1_thread\": %.3f, "
                    "\"packing\": \"%s\", \"bond_gap_um\": %.4g, "
                    "\"bond_steps_lanes\": %lld, \"bond_steps_scalar\": %lld, \"scalar_path_share\": %.4f, "
                    "\"pairs_into_particles_share\": %.4f}\n",
                    static_cast<long long>(s.n), static_cast<long long>(s.bonds),
                    static_cast<long long>(s.pairs), static_cast<long long>(s.contacts), s.threads,
                    static_cast<long long>(s.steps), s.seconds, pss, s.profile.neighbors,
                    s.profile.contacts, s.profile.bonds, s.profile.walls, s.profile.integrate,
                    static_cast<long long>(s.profile.rebuilds), static_cast<double>(s.world_bytes) / per,
                    static_cast<double>(s.rss) / per, speedup, s.row.packing, s.gap_um,
                    static_cast<long long>(lane), static_cast<long long>(scalar), scalar_share, into_particles);
        return;
    }
    char swept[32] = "-";
    if (!s.row.swept_key.empty()) std::snprintf(swept, sizeof swept, "%.4g", s.row.swept_value);
    std::printf("%-13s %-7s %6s %5.0f %9lld %9lld %3d %6lld %8.3f %11.3g | %7.3f %7.3f %7.3f %7.3f %7.3f | %6.0f %6.0f | %5.2f %5.2f\n",
                bond_model_name(s.bond_params.model), s.row.packing, swept, s.gap_um,
                static_cast<long long>(s.n), static_cast<long long>(s.bonds), s.threads,
                static_cast<long long>(s.steps), s.seconds, pss, s.profile.neighbors,
                s.profile.contacts, s.profile.bonds, s.profile.walls, s.profile.integrate,
                static_cast<double>(s.world_bytes) / per, static_cast<double>(s.rss) / per, speedup, scalar_share);
}

/// One row set (every thread count) of one bond case on one packing.
void run_thread_rows(const Options& o, const RowCase& row) {
    double base_seconds = 0.0;
    for (int t : o.threads) {
        std::vector<Sample> runs;
        for (int r = 0; r < o.repeat; ++r) runs.push_back(run_once(row, t, o.steps));
        const Sample m = median_of(runs);
        if (t == o.threads.front()) base_seconds = m.seconds * t / o.threads.front();
        const double speedup = (o.threads.front() == 1 && base_seconds > 0) ? base_seconds / m.seconds : 0.0;
        print_sample(m, speedup, o.json);
        std::fflush(stdout);
    }
}

/// Every model of the options on one packing, with the --set keys that apply to it: one row set,
/// or one per --sweep value where the sweep applies to the model.
void run_rows(const Options& o, RowCase row) {
    for (BondModel model : o.models) {
        row.bond.model = model;
        row.bond.settings.clear();
        for (const bench::MaterialSetting& set : o.sets)
            if (bench::setting_applies(set, model)) row.bond.settings.emplace_back(set.key, set.values.front());
        if (!o.sweep || !bench::setting_applies(*o.sweep, model)) {
            run_thread_rows(o, row);
            continue;
        }
        for (double v : o.sweep->values) {
            RowCase swept = row;
            swept.bond.settings.emplace_back(o.sweep->key, v);
            swept.swept_key = o.sweep->key;
            swept.swept_value = v;
            run_thread_rows(o, swept);
        }
    }
}

/// The genesis specimen of about `grains` grains (cached), with a line saying how it was had.
exp::Packing specimen_for_rows(const Options& o, std::int64_t grains) {
    double seconds = 0.0;
    bool cached = false;
    exp::Packing k = bench::specimen_packing(grains, o.cache_dir, seconds, cached);
    if (o.json)
        std::printf("{\"kind\": \"specimen\", \"n\": %zu, \"edge_mm\": %.4f, \"cached\": %s, \"genesis_seconds\": %.2f, "
                    "\"genesis_threads\": %d, \"porosity\": %.4f, \"cache_dir\": \"%s\"}\n",
                    k.radius.size(), 1e3 * k.edge(), cached ? "true" : "false", cached ? k.seconds : seconds,
                    thread_count(), k.porosity, o.cache_dir.c_str());
    else
        std::printf("specimen: %zu grains of the pre-blended sand, %.3f mm cube, %s (genesis %.1f s)\n", k.radius.size(),
                    1e3 * k.edge(), cached ? "from the packing cache" : "generated and cached", cached ? k.seconds : seconds);
    std::fflush(stdout);
    return k;
}

}  // namespace

namespace gradem::bench {

std::size_t peak_rss_bytes() {
    std::ifstream status("/proc/self/status");
    std::string line;
    while (std::getline(status, line))
        if (line.rfind("VmHWM:", 0) == 0) return std::stoull(line.substr(6)) * 1024;
    return 0;
}

TimedRun time_bonded_run(const exp::QuickPacking& packing, int threads, std::int64_t steps) {
    RowCase row;
    row.lattice = &packing;
    const Sample s = run_once(row, threads, steps);
#ifdef _OPENMP
    omp_set_num_threads(threads);
#endif
    World world = make_world(packing, lattice_material({}));  // the time step of the same set-up (cheap next to the run)
    return {s.seconds, world.time_step(), s.n, s.bonds, s.rss, s.world_bytes};
}

}  // namespace gradem::bench

int main(int argc, char** argv) {
    use_sleeping_openmp_threads(argv);
    return bench::run_main("gradem-bench", [&] {
        const Options o = parse(argc, argv);
        if (o.quiet) bench::be_quiet(o.json);
        if (o.full_cube) {
            bench::FullCubeOptions c = o.cube;
            c.threads = o.threads.back();
            if (o.steps_given) c.steps = o.steps;
            c.json = o.json;
            bench::run_full_cube_bench(c);
            return 0;
        }
        if (!o.genesis.empty()) {
            bench::run_genesis_bench(o.genesis, o.json);
            return 0;
        }
        if (o.neighbors > 0) {
            bench::run_neighbor_bench(o.neighbors, o.threads, o.repeat, o.json);
            return 0;
        }
        if (!o.json) {
            std::printf("gradem-bench: bonded packings (lattice: radius ratio 3; genesis: the pre-blended sand) "
                        "between closing platens; median of %d runs\n", o.repeat);
            std::printf("%-13s %-7s %6s %5s %9s %9s %3s %6s %8s %11s | %7s %7s %7s %7s %7s | %6s %6s | %5s %5s\n", "model",
                        "packing", "sweep", "gapum", "N", "bonds", "thr", "steps", "seconds", "p-steps/s", "neigh",
                        "contact", "bonds", "walls", "integr", "B/p", "RSS/p", "speedup", "scalar");
        }
        for (std::int64_t n : o.sizes) {
            exp::QuickPackingSpec spec;
            spec.target_count = n;
            const exp::QuickPacking packing = exp::make_quick_packing(spec);
            RowCase row;
            row.lattice = &packing;
            run_rows(o, row);
        }
        for (std::int64_t n : o.specimens) {
            const exp::Packing specimen = specimen_for_rows(o, n);
            RowCase row;
            row.packing = "genesis";
            row.specimen = &specimen;
            run_rows(o, row);
        }
        return 0;
    });
}
