#include "experiments/paste/paste_fill.hpp"

#include <algorithm>
#include <array>
#include <limits>
#include <chrono>
#include <cmath>
#include <memory>
#include <sstream>
#include <cstdio>
#include <cstdlib>

#include <unistd.h>

#include "core/neighbor_search.hpp"
#include "core/random.hpp"
#include "experiments/specimen/grain_sampler.hpp"
#include "experiments/specimen/morton_order.hpp"

namespace gradem::exp {
namespace {

constexpr double kPi = 3.14159265358979323846;
// Rosin-Rammler fit of NIST SRM 114p (8.9 / 14.9 / 24.9 % passing 1 / 2 / 4 µm):
// F(d) = 1 - exp(-(d/d')^n) gives 8.4 / 15.0 / 26.2 % and 98.6 % passing 75 µm.
constexpr double kCementSizeParameter = 15.0e-6;  // d' [m]
constexpr double kCementSpread = 0.9;             // n [-]
// Bytes per particle of a bonded specimen at its peak: the World's arrays (particles, Verlet
// pairs with their 72-byte output slots and incidences, bonds and their side state) hold 2.0 kB
// per particle on the small paste cube of tests/experiments/test_paste_specimen.cpp and 2.8 /
// 3.0 kB per grain on 2·10⁴-grain genesis specimens with parallel bonds / flat joints
// (`gradem-bench --specimens 20000`, "bytes_per_particle"); the neighbour grid, the packing and
// the lane buffers bring the process to 3.4 kB there ("peak_rss_bytes_per_particle"): 3.5 kB.
constexpr double kBytesPerParticle = 3500.0;

double& component(Vec3& v, int a) { return a == 0 ? v.x : (a == 1 ? v.y : v.z); }

double sphere_volume(double r) { return 4.0 / 3.0 * kPi * r * r * r; }

double cement_passing(double d) { return 1.0 - std::exp(-std::pow(d / kCementSizeParameter, kCementSpread)); }

bool monodisperse(const PasteSpec& s) { return s.max_diameter <= s.min_diameter; }

std::string fmt(double v, int precision = 4) {
    std::ostringstream os;
    os.precision(precision);
    os << v;
    return os.str();
}

/// Uniform grid over the box of cell edge >= `reach`; a point's candidates lie in its 27 cells.
class PointGrid {
public:
    PointGrid(const Vec3& lo, const Vec3& hi, double reach) : lo_(lo) {
        for (int a = 0; a < 3; ++a) {
            const double len = hi[a] - lo[a];
            n_[a] = std::max(1, std::min(256, static_cast<int>(len / reach)));
            h_[a] = len / n_[a];
        }
        cells_.resize(static_cast<std::size_t>(n_[0]) * n_[1] * n_[2]);
    }
    void insert(const Vec3& x, std::int32_t id) { cells_[index(cell_of(x))].push_back(id); }
    template <class F>
    bool any(const Vec3& x, F&& hit) const {
        const auto c = cell_of(x);
        for (int dx = -1; dx <= 1; ++dx)
            for (int dy = -1; dy <= 1; ++dy)
                for (int dz = -1; dz <= 1; ++dz) {
                    const std::array<int, 3> q{c[0] + dx, c[1] + dy, c[2] + dz};
                    if (q[0] < 0 || q[1] < 0 || q[2] < 0 || q[0] >= n_[0] || q[1] >= n_[1] || q[2] >= n_[2]) continue;
                    for (std::int32_t id : cells_[index(q)])
                        if (hit(id)) return true;
                }
        return false;
    }

private:
    std::array<int, 3> cell_of(const Vec3& x) const {
        std::array<int, 3> c{};
        for (int a = 0; a < 3; ++a) c[a] = std::clamp(static_cast<int>((x[a] - lo_[a]) / h_[a]), 0, n_[a] - 1);
        return c;
    }
    std::size_t index(const std::array<int, 3>& c) const {
        return (static_cast<std::size_t>(c[2]) * n_[1] + c[1]) * n_[0] + c[0];
    }
    Vec3 lo_;
    std::array<int, 3> n_{};
    std::array<double, 3> h_{};
    std::vector<std::vector<std::int32_t>> cells_;
};

// Step 1: centres and box scaled about the box centre by `s`.
void dilate(Packing& k, double s) {
    const Vec3 c = 0.5 * (k.box_lo + k.box_hi);
    for (Vec3& x : k.position) x = c + s * (x - c);
    k.box_lo = c + s * (k.box_lo - c);
    k.box_hi = c + s * (k.box_hi - c);
}

// Step 2: diameters, largest first.
std::vector<double> paste_diameters(const PasteSpec& spec, double volume, std::uint64_t seed) {
    std::vector<double> d;
    if (monodisperse(spec)) {
        const auto n = static_cast<std::size_t>(std::llround(volume / sphere_volume(0.5 * spec.min_diameter)));
        d.assign(n, spec.min_diameter);
    } else {
        SizeRule rule;
        rule.min_diameter = spec.min_diameter;
        rule.max_diameter = spec.max_diameter;
        d = sample_grains(cement_size_curve(), rule, volume, seed ^ 0x70a57e0000000001ull).diameters;
    }
    std::stable_sort(d.begin(), d.end(), std::greater<>());
    return d;
}

struct Arrays {
    std::vector<Vec3> x;
    std::vector<double> r, full_r, weight;  // weight: 1 / volume (the lighter moves more)
    std::vector<std::uint8_t> family;
    Vec3 lo, hi;
};

// Step 3: random sequential addition at rsa_scale; returns the failures.
std::size_t place_rsa(Arrays& a, std::size_t sand_count, const std::vector<double>& diameters, const PasteSpec& spec,
                      std::uint64_t seed) {
    double r_sand_max = 0.0;
    for (std::size_t i = 0; i < sand_count; ++i) r_sand_max = std::max(r_sand_max, a.r[i]);
    const double r_paste_max = diameters.empty() ? 0.0 : 0.5 * diameters.front() * spec.rsa_scale;
    PointGrid sand_grid(a.lo, a.hi, r_sand_max + r_paste_max);
    for (std::size_t i = 0; i < sand_count; ++i) sand_grid.insert(a.x[i], static_cast<std::int32_t>(i));
    PointGrid paste_grid(a.lo, a.hi, 2.0 * r_paste_max);
    SplitMix64 rng(mix64(seed ^ 0x5ea7ed9a57e5ull));
    std::size_t failures = 0;
    for (double d : diameters) {
        const double r = 0.5 * d * spec.rsa_scale;
        Vec3 x;
        bool free = false;
        for (int attempt = 0; attempt < spec.rsa_attempts && !free; ++attempt) {
            for (int c = 0; c < 3; ++c) component(x, c) = rng.uniform(a.lo[c] + r, a.hi[c] - r);
            const auto overlaps = [&](std::int32_t id) {
                const double reach = a.r[static_cast<std::size_t>(id)] + r;
                return norm2(a.x[static_cast<std::size_t>(id)] - x) < reach * reach;
            };
            free = !sand_grid.any(x, overlaps) && !paste_grid.any(x, overlaps);
        }
        failures += free ? 0 : 1;
        const auto id = static_cast<std::int32_t>(a.x.size());
        a.x.push_back(x);
        a.r.push_back(r);
        a.full_r.push_back(0.5 * d);
        a.weight.push_back(1.0 / sphere_volume(0.5 * d));
        a.family.push_back(kPasteFamily);
        paste_grid.insert(x, id);
    }
    return failures;
}

struct Overlaps {
    double any = 0.0, paste_sand = 0.0;  // largest overlap / smaller radius
};

Overlaps measure(const Arrays& a, const std::vector<ParticlePair>& pairs) {
    Overlaps o;
    for (const ParticlePair& p : pairs) {
        const auto i = static_cast<std::size_t>(p.i), j = static_cast<std::size_t>(p.j);
        const double ov = (a.r[i] + a.r[j] - norm(a.x[j] - a.x[i])) / std::min(a.r[i], a.r[j]);
        o.any = std::max(o.any, ov);
        if (a.family[i] != a.family[j]) o.paste_sand = std::max(o.paste_sand, ov);
    }
    return o;
}

// One Jacobi sweep: every overlapping pair pushed apart (split by inverse volume: a sand grain
// moves little), then every particle projected back into the box. Returns the largest displacement.
double relax_sweep(Arrays& a, const std::vector<ParticlePair>& pairs, std::vector<Vec3>& disp) {
    constexpr double kRelaxation = 0.6;  // under-relaxation of the Jacobi update (crowded particles)
    std::fill(disp.begin(), disp.end(), Vec3{});
    for (const ParticlePair& p : pairs) {
        const auto i = static_cast<std::size_t>(p.i), j = static_cast<std::size_t>(p.j);
        const Vec3 d = a.x[j] - a.x[i];
        const double dist = norm(d);
        const double ov = a.r[i] + a.r[j] - dist;
        if (ov <= 0.0) continue;
        const Vec3 n = dist > 0.0 ? (1.0 / dist) * d : Vec3{1.0, 0.0, 0.0};
        const double share_i = a.weight[i] / (a.weight[i] + a.weight[j]);
        disp[i] -= (kRelaxation * ov * share_i) * n;
        disp[j] += (kRelaxation * ov * (1.0 - share_i)) * n;
    }
    double moved = 0.0;
    for (std::size_t i = 0; i < a.x.size(); ++i) {
        const Vec3 before = a.x[i];
        a.x[i] += disp[i];
        for (int c = 0; c < 3; ++c) component(a.x[i], c) = std::clamp(a.x[i][c], a.lo[c] + a.r[i], a.hi[c] - a.r[i]);
        moved = std::max(moved, norm(a.x[i] - before));
    }
    return moved;
}

// Step 4: growth in stages, each relaxed to the tolerance; returns the scale reached.
double grow_and_relax(Arrays& a, std::size_t sand_count, const PasteSpec& spec, PasteReport& report) {
    auto search = make_neighbor_search();
    double r_min = std::numeric_limits<double>::infinity();
    for (std::size_t i = sand_count; i < a.r.size(); ++i) r_min = std::min(r_min, a.full_r[i]);
    const double skin = 0.2 * r_min;
    std::vector<ParticlePair> pairs;
    std::vector<Vec3> disp(a.x.size()), saved = a.x;
    double reached = spec.rsa_scale;
    for (int stage = 1; stage <= spec.growth_stages; ++stage) {
        const double scale = spec.rsa_scale + (1.0 - spec.rsa_scale) * stage / spec.growth_stages;
        for (std::size_t i = sand_count; i < a.r.size(); ++i) a.r[i] = scale * a.full_r[i];
        bool converged = false;
        double drift = 2.0 * skin;  // forces a search first
        for (int it = 0; it < spec.relax_iterations; ++it) {
            if (2.0 * drift > skin) {
                search->find_pairs(a.x, a.r, skin, pairs);
                drift = 0.0;
            }
            if (measure(a, pairs).any < spec.overlap_tolerance) {
                converged = true;
                break;
            }
            drift += relax_sweep(a, pairs, disp);
            ++report.relax_sweeps;
        }
        if (!converged) {  // back to the last stage that relaxed
            a.x = saved;
            for (std::size_t i = sand_count; i < a.r.size(); ++i) a.r[i] = reached * a.full_r[i];
            return reached;
        }
        saved = a.x;
        reached = scale;
    }
    return reached;
}

// Step 4b: the overlaps left (<= overlap_tolerance) would load the bonded specimen far above the
// genesis' locked-in stress (E* x 1 % strain is 100 MPa at 10 GPa), so each particle shrinks by
// the largest share of overlap of its pairs: a paste particle all of a paste-sand overlap, each
// partner half of a paste-paste or sand-sand one (sand grains moved a little in the relaxation).
// Afterwards no pair overlaps. Returns the largest relative shrink.
double shrink_overlapping_paste(Arrays& a, const std::vector<ParticlePair>& pairs) {
    std::vector<double> cut(a.r.size(), 0.0);
    for (const ParticlePair& p : pairs) {
        const auto i = static_cast<std::size_t>(p.i), j = static_cast<std::size_t>(p.j);
        const double ov = a.r[i] + a.r[j] - norm(a.x[j] - a.x[i]);
        if (ov <= 0.0) continue;
        const bool pi = a.family[i] == kPasteFamily, pj = a.family[j] == kPasteFamily;
        const double share = pi == pj ? 0.5 : 1.0;  // same family: halves; else the paste one
        if (pi || !pj) cut[i] = std::max(cut[i], share * ov);
        if (pj || !pi) cut[j] = std::max(cut[j], share * ov);
    }
    double worst = 0.0;
    for (std::size_t i = 0; i < a.r.size(); ++i) {
        if (cut[i] == 0.0) continue;
        worst = std::max(worst, cut[i] / a.r[i]);
        a.r[i] -= cut[i];
    }
    return worst;
}

}  // namespace

std::optional<std::string> PasteSpec::invalid_reason() const {
    const auto bad = [](const char* field, double v, const char* rule) {
        return std::string("paste.") + field + " = " + fmt(v, 6) + " violates " + rule;
    };
    if (!(min_diameter > 0.0 && std::isfinite(min_diameter))) return bad("min_diameter", min_diameter, "> 0");
    if (!(max_diameter >= min_diameter && std::isfinite(max_diameter)))
        return bad("max_diameter", max_diameter, ">= min_diameter (equal: one coarse-grained size)");
    if (!(solid_fraction > 0.0 && solid_fraction <= 0.74)) return bad("solid_fraction", solid_fraction, "in (0, 0.74]");
    if (!(overlap_tolerance > 0.0 && overlap_tolerance <= 0.2)) return bad("overlap_tolerance", overlap_tolerance, "in (0, 0.2]");
    if (!(rsa_scale > 0.0 && rsa_scale <= 1.0)) return bad("rsa_scale", rsa_scale, "in (0, 1]");
    if (rsa_attempts < 1) return bad("rsa_attempts", rsa_attempts, ">= 1");
    if (growth_stages < 1) return bad("growth_stages", growth_stages, ">= 1");
    if (relax_iterations < 1) return bad("relax_iterations", relax_iterations, ">= 1");
    if (!(memory_fraction > 0.0 && memory_fraction <= 1.0)) return bad("memory_fraction", memory_fraction, "in (0, 1]");
    return std::nullopt;
}

lab::GradationCurve cement_size_curve() {
    std::vector<double> size, passing;
    for (int k = 0; k <= 30; ++k) {  // 0.3 µm .. 300 µm, ten points per decade
        const double d = 0.3e-6 * std::pow(10.0, k / 10.0);
        size.push_back(d);
        passing.push_back(k == 30 ? 1.0 : cement_passing(d));
    }
    return lab::GradationCurve::from_points(size, passing);
}

double expected_paste_count(const PasteSpec& spec, double volume) {
    if (monodisperse(spec)) return volume / sphere_volume(0.5 * spec.min_diameter);
    // Mass fraction w_k in log bins of [min, max]; count = volume Σ (w_k / Σw) / v(d_k).
    constexpr int kBins = 400;
    const double ratio = std::log(spec.max_diameter / spec.min_diameter);
    double count = 0.0, mass = 0.0;
    for (int k = 0; k < kBins; ++k) {
        const double d0 = spec.min_diameter * std::exp(ratio * k / kBins);
        const double d1 = spec.min_diameter * std::exp(ratio * (k + 1) / kBins);
        const double w = cement_passing(d1) - cement_passing(d0);
        mass += w;
        count += w / sphere_volume(0.5 * std::sqrt(d0 * d1));
    }
    return mass > 0.0 ? volume * count / mass : 0.0;
}

double estimated_specimen_bytes(double particles) { return particles * kBytesPerParticle; }

double physical_memory_bytes() {
    return static_cast<double>(sysconf(_SC_PHYS_PAGES)) * static_cast<double>(sysconf(_SC_PAGE_SIZE));
}

namespace {

double box_volume(const Packing& k) {
    const Vec3 e = k.box_hi - k.box_lo;
    return e.x * e.y * e.z;
}

/// The sand's volume [m^3]; its diameter range and packed fraction into the report.
double measure_sand(const Packing& sand, PasteReport& report) {
    double sand_volume = 0.0;
    report.sand_d_min = std::numeric_limits<double>::infinity();
    for (double r : sand.radius) {
        sand_volume += sphere_volume(r);
        report.sand_d_min = std::min(report.sand_d_min, 2.0 * r);
        report.sand_d_max = std::max(report.sand_d_max, 2.0 * r);
    }
    report.packed_sand_fraction = sand_volume / box_volume(sand);
    return sand_volume;
}

/// 1. The sand dilated to the mix's sand fraction; refused when the mix's paste cannot fill
///    the packed sand's pore space.
Packing dilated_to_mix(const Packing& sand, const MixFractions& mix, double sand_volume, PasteReport& report) {
    if (mix.sand > report.packed_sand_fraction)
        throw std::invalid_argument(
            "the mix design's sand fraction " + fmt(mix.sand) + " exceeds the packed sand's " +
            fmt(report.packed_sand_fraction) + ": its paste (" + fmt(mix.paste) + " of the volume, air " + fmt(mix.air) +
            ") cannot fill the sand's pore space (" + fmt(1.0 - report.packed_sand_fraction) +
            "); expected a richer mix (a smaller mix.sand_to_cementitious_volume)");
    Packing out = sand;
    report.dilation = std::cbrt(report.packed_sand_fraction / mix.sand);
    dilate(out, report.dilation);
    report.sand_fraction = sand_volume / box_volume(out);
    return out;
}

/// 2. The memory estimate of `expected` paste particles beside the sand, before allocating:
///    PasteMemoryError over spec.memory_fraction of this machine's memory.
void check_memory(const PasteSpec& spec, double expected, std::size_t sand_count, PasteReport& report) {
    report.estimated_bytes = estimated_specimen_bytes(expected + static_cast<double>(sand_count));
    const double limit = spec.memory_fraction * physical_memory_bytes();
    if (report.estimated_bytes > limit)
        throw PasteMemoryError("paste.min_diameter_mm = " + fmt(spec.min_diameter * 1e3) + ": about " + fmt(expected, 3) +
                               " paste particles would need about " + fmt(report.estimated_bytes / 1e9, 3) +
                               " GB (" + fmt(kBytesPerParticle, 4) + " B per particle), more than " +
                               fmt(spec.memory_fraction, 2) + " x this machine's " +
                               fmt(physical_memory_bytes() / 1e9, 3) +
                               " GB; expected a larger paste.min_diameter_mm or a smaller genesis.edge_mm");
}

/// 3-4. The paste particles placed among the dilated sand (RSA), grown and relaxed, the
///      remaining overlaps shrunk away and measured.
Arrays placed_paste(const Packing& out, const std::vector<double>& diameters, const PasteSpec& spec, std::uint64_t seed,
                    PasteReport& report) {
    Arrays a;
    a.x = out.position;
    a.r = out.radius;
    a.full_r = out.radius;
    for (double r : out.radius) a.weight.push_back(1.0 / sphere_volume(r));
    a.family.assign(out.position.size(), kSandFamily);
    a.lo = out.box_lo;
    a.hi = out.box_hi;
    const std::size_t sand_count = a.x.size();
    report.rsa_failures = place_rsa(a, sand_count, diameters, spec, seed);
    report.growth_reached = grow_and_relax(a, sand_count, spec, report);
    std::vector<ParticlePair> pairs;
    make_neighbor_search()->find_pairs(a.x, a.r, 0.0, pairs);
    report.max_shrink = shrink_overlapping_paste(a, pairs);
    make_neighbor_search()->find_pairs(a.x, a.r, 0.0, pairs);
    const Overlaps o = measure(a, pairs);
    report.max_overlap = std::max(0.0, o.any);
    report.max_overlap_sand = std::max(0.0, o.paste_sand);
    return a;
}

/// 5. Everything into `out` in Morton order, and the specimen's fractions into the report.
void write_specimen(const Arrays& a, std::size_t sand_count, const MixFractions& mix, const PasteSpec& spec, double sand_volume,
                    Packing& out, PasteReport& report) {
    const double volume = box_volume(out);
    const std::vector<std::int32_t> order = morton_order(a.x, a.lo, a.hi);
    out.position = permuted(a.x, order);
    out.radius = permuted(a.r, order);
    out.family = permuted(a.family, order);
    out.paste_density = mix.paste_density / spec.solid_fraction;  // the particle carries the paste it stands for
    double paste_volume = 0.0;
    report.paste_d_min = std::numeric_limits<double>::infinity();
    for (std::size_t i = sand_count; i < a.r.size(); ++i) {
        paste_volume += sphere_volume(a.r[i]);
        report.paste_d_min = std::min(report.paste_d_min, 2.0 * a.r[i]);
        report.paste_d_max = std::max(report.paste_d_max, 2.0 * a.r[i]);
    }
    report.sand_count = sand_count;
    report.paste_count = a.x.size() - sand_count;
    report.size_ratio = report.sand_d_max / report.paste_d_min;
    report.paste_particle_fraction = paste_volume / volume;
    report.paste_fraction = report.paste_particle_fraction / spec.solid_fraction;
    report.void_fraction = 1.0 - report.sand_fraction - report.paste_fraction;
    out.porosity = 1.0 - (sand_volume + paste_volume) / volume;
    out.mean_coordination = 0.0;  // not measured for the paste specimen
}

}  // namespace

Packing fill_paste(const Packing& sand, const MixFractions& mix, const PasteSpec& spec, std::uint64_t seed,
                   PasteReport& report) {
    if (auto why = spec.invalid_reason()) throw std::invalid_argument(*why);
    if (sand.position.empty()) throw std::invalid_argument("paste fill: empty sand packing");
    const auto start = std::chrono::steady_clock::now();
    report = {};
    report.mix_sand_fraction = mix.sand;
    report.mix_paste_fraction = mix.paste;
    report.mix_air_fraction = mix.air;
    const double sand_volume = measure_sand(sand, report);
    Packing out = dilated_to_mix(sand, mix, sand_volume, report);
    const double paste_particle_volume = mix.paste * box_volume(out) * spec.solid_fraction;
    check_memory(spec, expected_paste_count(spec, paste_particle_volume), sand.position.size(), report);
    const std::vector<double> diameters = paste_diameters(spec, paste_particle_volume, seed);
    if (diameters.empty()) throw std::invalid_argument("paste fill: no paste particle fits the paste volume");
    const Arrays a = placed_paste(out, diameters, spec, seed, report);
    write_specimen(a, sand.position.size(), mix, spec, sand_volume, out, report);
    out.edge_over_d50 = sand.edge_over_d50 * report.dilation;
    report.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    return out;
}

std::string describe(const PasteReport& r) {
    std::ostringstream os;
    os << "explicit paste: " << r.sand_count << " sand grains (" << fmt(r.sand_d_min * 1e3) << "-"
       << fmt(r.sand_d_max * 1e3) << " mm) + " << r.paste_count << " paste particles (" << fmt(r.paste_d_min * 1e3) << "-"
       << fmt(r.paste_d_max * 1e3) << " mm), size ratio " << fmt(r.size_ratio, 3) << "\n"
       << "  volume fractions placed vs mix design: sand " << fmt(r.sand_fraction) << " vs " << fmt(r.mix_sand_fraction)
       << ", paste " << fmt(r.paste_fraction) << " vs " << fmt(r.mix_paste_fraction) << " (particles "
       << fmt(r.paste_particle_fraction) << "), voids " << fmt(r.void_fraction) << " vs air " << fmt(r.mix_air_fraction)
       << "\n  sand dilated x" << fmt(r.dilation, 5) << " from " << fmt(r.packed_sand_fraction) << "; growth reached "
       << fmt(r.growth_reached) << "; largest overlap " << fmt(r.max_overlap, 3) << " (paste-sand "
       << fmt(r.max_overlap_sand, 3) << ") of the smaller radius after shrinking paste by up to " << fmt(r.max_shrink, 3)
       << "; " << r.rsa_failures << " RSA failures, "
       << r.relax_sweeps << " relaxation sweeps, " << fmt(r.seconds, 3) << " s; memory estimate "
       << fmt(r.estimated_bytes / 1e6, 3) << " MB";
    return os.str();
}

}  // namespace gradem::exp
