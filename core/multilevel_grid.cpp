// Multi-level neighbour grid (Ogarko & Luding 2012, "A fast multilevel algorithm for contact
// detection of arbitrarily polydisperse objects", CPC 183:931; MercuryDPM's HGrid works the
// same way). A single cell grid sized by the largest grain holds (d_max/d_min)^3 small grains
// per cell (~7e4 at a size ratio of 50); here every particle lives on the level whose cells
// fit it:
//   1. levels: particle i goes to the first level whose bound is >= s_i = 2 r_i + max_gap;
//      each level's cell edge is s_max of its own particles (so cell >= 2 r_max,l + max_gap);
//   2. per level, particles are counting-sorted into hashed cell buckets (O(N) memory, no
//      dense grid: a stray particle far away cannot blow memory up);
//   3. same level: own cell + the 13-cell forward half stencil finds every pair once;
//   4. across levels: for each pair of levels, the particles of one scan the cells of the
//      other that meet the ball of radius r_i + r_max,other + max_gap around them (the only
//      place a partner can be): top-down (large scan fine cells) or bottom-up (small scan
//      coarse cells), whichever the cost model below finds cheaper;
//   5. pairs are counting-sorted by (i, j): the output does not depend on the thread count.
// Level choice (plan_levels), after Krijgsman, Ogarko & Luding 2014 (Comp. Part. Mech.
// 1:357: choose levels and cell sizes by minimising an estimate of the search time for the
// given size distribution), in a simplified form: level bounds are geometric between s_min
// and s_max (constant cell-size ratio), and the number of levels L = 1..8 minimises the
// cost estimate below, evaluated on a 64-bin histogram of s with uniform particle density
// n_l / V per level (V: bounding box padded by one s_max):
//   same level   n_l [14 + 13.5 n_l c_l^3 / V]           (cell visits + distance checks)
//   a scans b    n_a (π/6)((c_a + c_b)/c_b + 2)^3 [1 + n_b c_b^3 / V]
//   cross level  min(l scans m, m scans l) for every m < l: top-down (a large grain visits
//                the fine cells over its extent) or bottom-up (a small grain visits the ~27
//                coarse cells around it), whichever is cheaper; the search uses the same rule
// and a level is only added when it lowers that cost by more than 2 %.
#include "core/multilevel_grid.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>

#include "core/neighbor_search.hpp"
#include "core/parallel.hpp"

namespace gradem {

// ---------------------------------------------------------------------------------------
// Level choice
// ---------------------------------------------------------------------------------------

namespace {

constexpr int kMaxLevels = 8;
constexpr int kBins = 64;

// Same level: 14 cell visits (own + half stencil), 13.5 cells' worth of distance checks.
double same_level_cost(double n, double cell, double volume) {
    return n * (14.0 + 13.5 * n * cell * cell * cell / volume);
}

// `n_a` particles of level a (cell c_a ~ 2 r_max,a + gap) each visit the cells of level b
// that meet the ball of radius h = (c_a + c_b) / 2 around them, ~ (π/6)(2h/c_b + 2)^3 cells,
// and check every particle in them (density n_b / volume).
double scan_cost(double n_a, double c_a, double n_b, double c_b, double volume) {
    const double side = (c_a + c_b) / c_b + 2.0;
    const double cells = kPi / 6.0 * side * side * side;
    return n_a * cells * (1.0 + n_b * c_b * c_b * c_b / volume);
}

struct SizeHistogram {
    std::array<double, kBins> count{};
    std::array<double, kBins> top{};  // largest s in the bin [m]
};

SizeHistogram histogram_of(const std::vector<double>& radius, double max_gap, double s_min,
                           double s_max) {
    SizeHistogram h;
    const double log_span = std::log(s_max / s_min);
    for (double r : radius) {
        const double s = 2.0 * r + max_gap;
        const int b = std::clamp(static_cast<int>(std::log(s / s_min) / log_span * kBins), 0, kBins - 1);
        h.count[static_cast<std::size_t>(b)] += 1.0;
        h.top[static_cast<std::size_t>(b)] = std::max(h.top[static_cast<std::size_t>(b)], s);
    }
    return h;
}

// Cost estimate per particle for the given level bounds (see the file header).
double level_cost(const SizeHistogram& h, const std::vector<double>& bound, double volume,
                  double n_total) {
    const std::size_t levels = bound.size();
    std::vector<double> n(levels, 0.0), cell(levels, 0.0);
    for (std::size_t b = 0; b < kBins; ++b) {
        if (h.count[b] == 0.0) continue;
        std::size_t l = 0;
        while (l + 1 < levels && h.top[b] > bound[l]) ++l;
        n[l] += h.count[b];
        cell[l] = std::max(cell[l], h.top[b]);
    }
    double cost = 0.0;
    for (std::size_t l = 0; l < levels; ++l) {
        if (n[l] == 0.0) continue;
        cost += same_level_cost(n[l], cell[l], volume);
        for (std::size_t m = 0; m < l; ++m)
            if (n[m] > 0.0)
                cost += std::min(scan_cost(n[l], cell[l], n[m], cell[m], volume),
                                 scan_cost(n[m], cell[m], n[l], cell[l], volume));
    }
    return cost / n_total;
}

// Geometric bounds s_min * (s_max/s_min)^((l+1)/L), l = 0..L-1; the last is exactly s_max.
std::vector<double> geometric_bounds(double s_min, double s_max, int levels) {
    std::vector<double> bound(static_cast<std::size_t>(levels));
    for (int l = 0; l < levels; ++l)
        bound[static_cast<std::size_t>(l)] =
            s_min * std::pow(s_max / s_min, static_cast<double>(l + 1) / levels);
    bound.back() = s_max;
    return bound;
}

}  // namespace

LevelPlan plan_levels(const std::vector<double>& radius, double max_gap, double box_volume) {
    LevelPlan plan;
    if (radius.empty()) {
        plan.cell = {std::max(max_gap, std::numeric_limits<double>::min())};
        return plan;
    }
    const auto [lo, hi] = std::minmax_element(radius.begin(), radius.end());
    const double s_min = 2.0 * *lo + max_gap, s_max = 2.0 * *hi + max_gap;
    const auto n = static_cast<double>(radius.size());
    const double volume = std::max(box_volume, std::numeric_limits<double>::min());
    if (!(s_min > 0.0) || s_max <= s_min * (1.0 + 1e-12)) {
        plan.cell = {s_max};
        plan.estimated_cost = 14.0 + 13.5 * n * s_max * s_max * s_max / volume;
        return plan;
    }
    const SizeHistogram h = histogram_of(radius, max_gap, s_min, s_max);
    const int max_levels = std::clamp(static_cast<int>(std::ceil(std::log2(s_max / s_min))), 1, kMaxLevels);
    plan.cell = {s_max};
    plan.estimated_cost = level_cost(h, plan.cell, volume, n);
    for (int levels = 2; levels <= max_levels; ++levels) {
        std::vector<double> bound = geometric_bounds(s_min, s_max, levels);
        const double cost = level_cost(h, bound, volume, n);
        if (cost < 0.98 * plan.estimated_cost) {
            plan.cell = std::move(bound);
            plan.estimated_cost = cost;
        }
    }
    return plan;
}

// ---------------------------------------------------------------------------------------
// The search
// ---------------------------------------------------------------------------------------

namespace {

constexpr int kCoordBits = 21;  // cell coordinates per axis packed into one 64-bit key
constexpr std::int64_t kMaxCoord = (std::int64_t{1} << kCoordBits) - 1;
constexpr std::int64_t kSameLevelBlock = 2048;  // entries per task, same-level search
constexpr std::int64_t kCrossLevelWork = 4096;  // ~cell visits per task, cross-level scans

using Cell = std::array<std::int64_t, 3>;

std::uint64_t pack(const Cell& c) {
    return static_cast<std::uint64_t>(c[0]) | (static_cast<std::uint64_t>(c[1]) << kCoordBits) |
           (static_cast<std::uint64_t>(c[2]) << (2 * kCoordBits));
}

// One level: its particles counting-sorted by hashed cell (stable in particle index), with
// copies of position and radius in that order so candidate checks read contiguous memory.
struct Level {
    double cell = 1.0;      // cell edge [m] (>= 2 r_max + max_gap of this level)
    double r_max = 0.0;     // largest radius on this level [m]
    Vec3 origin;            // lower corner of this level's particles [m]
    Cell dims{1, 1, 1};     // cells per axis
    int hash_bits = 4;
    std::vector<std::int64_t> bucket_start;  // CSR over hash buckets
    std::vector<std::uint64_t> key;          // packed cell of each entry
    std::vector<Vec3> x;
    std::vector<double> r;
    std::vector<std::int32_t> id;

    std::int64_t coord(double v, double o, int k) const {
        const auto c = static_cast<std::int64_t>(std::floor((v - o) / cell));
        return std::clamp<std::int64_t>(c, 0, dims[static_cast<std::size_t>(k)] - 1);
    }
    Cell cell_of(const Vec3& p) const {
        return {coord(p.x, origin.x, 0), coord(p.y, origin.y, 1), coord(p.z, origin.z, 2)};
    }
    std::size_t bucket(std::uint64_t k) const {
        return static_cast<std::size_t>((k * 0x9e3779b97f4a7c15ull) >> (64 - hash_bits));
    }
    bool inside(const Cell& c) const {
        return c[0] >= 0 && c[1] >= 0 && c[2] >= 0 && c[0] < dims[0] && c[1] < dims[1] &&
               c[2] < dims[2];
    }
    std::size_t size() const { return id.size(); }
};

// Lays out one level over the particles `members` (ascending indices).
void build_level(const std::vector<Vec3>& x, const std::vector<double>& r, double max_gap,
                 const std::vector<std::int32_t>& members, Level& level) {
    Vec3 lo{std::numeric_limits<double>::max(), std::numeric_limits<double>::max(),
            std::numeric_limits<double>::max()};
    Vec3 hi = -1.0 * lo;
    double s_max = 0.0;
    level.r_max = 0.0;
    for (std::int32_t i : members) {
        const Vec3& p = x[static_cast<std::size_t>(i)];
        lo = {std::min(lo.x, p.x), std::min(lo.y, p.y), std::min(lo.z, p.z)};
        hi = {std::max(hi.x, p.x), std::max(hi.y, p.y), std::max(hi.z, p.z)};
        level.r_max = std::max(level.r_max, r[static_cast<std::size_t>(i)]);
        s_max = std::max(s_max, 2.0 * r[static_cast<std::size_t>(i)] + max_gap);
    }
    const Vec3 extent = hi - lo;
    const double widest = std::max({extent.x, extent.y, extent.z});
    // Relative margin 1e-8 keeps two particles a full cell apart within neighbouring cells
    // despite rounding in (x - origin) / cell; cells also grow until the packed key fits.
    level.cell = std::max({s_max * (1.0 + 1e-8), widest / static_cast<double>(kMaxCoord - 2),
                           std::numeric_limits<double>::min()});
    level.origin = lo;
    for (int k = 0; k < 3; ++k)
        level.dims[static_cast<std::size_t>(k)] = static_cast<std::int64_t>(extent[k] / level.cell) + 1;

    const std::size_t n = members.size();
    level.hash_bits = 4;
    while ((std::size_t{1} << level.hash_bits) < 2 * n) ++level.hash_bits;
    const std::size_t buckets = std::size_t{1} << level.hash_bits;
    std::vector<std::uint64_t> member_key(n);
    level.bucket_start.assign(buckets + 1, 0);
    for (std::size_t k = 0; k < n; ++k) {
        member_key[k] = pack(level.cell_of(x[static_cast<std::size_t>(members[k])]));
        ++level.bucket_start[level.bucket(member_key[k]) + 1];
    }
    for (std::size_t b = 0; b < buckets; ++b) level.bucket_start[b + 1] += level.bucket_start[b];
    std::vector<std::int64_t> fill(level.bucket_start.begin(), level.bucket_start.end() - 1);
    level.key.resize(n);
    level.x.resize(n);
    level.r.resize(n);
    level.id.resize(n);
    for (std::size_t k = 0; k < n; ++k) {
        const auto slot = static_cast<std::size_t>(fill[level.bucket(member_key[k])]++);
        const auto i = static_cast<std::size_t>(members[k]);
        level.key[slot] = member_key[k];
        level.x[slot] = x[i];
        level.r[slot] = r[i];
        level.id[slot] = members[k];
    }
}

// Appends (min, max) of two particle ids when they are within reach. The test is the cell
// grid's, written symmetrically, so both searches return bitwise the same pair set.
inline void check(std::int32_t a, const Vec3& xa, double ra, std::int32_t b, const Vec3& xb,
                  double rb, double max_gap, std::vector<ParticlePair>& out) {
    const double reach = ra + rb + max_gap;
    if (norm2(xb - xa) <= reach * reach) out.push_back({std::min(a, b), std::max(a, b)});
}

// Entries [begin, end) of `level` against their own level: own cell (later entries only)
// and the 13 forward neighbour cells, so every pair on the level is seen exactly once.
void same_level_pairs(const Level& level, std::int64_t begin, std::int64_t end, double max_gap,
                      std::vector<ParticlePair>& out) {
    static constexpr std::array<Cell, 13> kForward{{{1, 0, 0},  {-1, 1, 0}, {0, 1, 0},  {1, 1, 0},
                                                    {-1, -1, 1}, {0, -1, 1}, {1, -1, 1}, {-1, 0, 1},
                                                    {0, 0, 1},   {1, 0, 1},  {-1, 1, 1}, {0, 1, 1},
                                                    {1, 1, 1}}};
    constexpr std::uint64_t kMask = static_cast<std::uint64_t>(kMaxCoord);
    for (std::int64_t e = begin; e < end; ++e) {
        const auto k = static_cast<std::size_t>(e);
        const std::uint64_t own = level.key[k];
        const Vec3& xi = level.x[k];
        const double ri = level.r[k];
        const std::int32_t i = level.id[k];
        const std::size_t b = level.bucket(own);
        for (auto q = k + 1; q < static_cast<std::size_t>(level.bucket_start[b + 1]); ++q)
            if (level.key[q] == own) check(i, xi, ri, level.id[q], level.x[q], level.r[q], max_gap, out);
        const Cell c{static_cast<std::int64_t>(own & kMask),
                     static_cast<std::int64_t>((own >> kCoordBits) & kMask),
                     static_cast<std::int64_t>(own >> (2 * kCoordBits))};
        for (const Cell& d : kForward) {
            const Cell nc{c[0] + d[0], c[1] + d[1], c[2] + d[2]};
            if (!level.inside(nc)) continue;
            const std::uint64_t key = pack(nc);
            const std::size_t nb = level.bucket(key);
            for (auto q = static_cast<std::size_t>(level.bucket_start[nb]);
                 q < static_cast<std::size_t>(level.bucket_start[nb + 1]); ++q)
                if (level.key[q] == key)
                    check(i, xi, ri, level.id[q], level.x[q], level.r[q], max_gap, out);
        }
    }
}

// Particle (i, xi, ri) against every particle of another level `fine` (finer or coarser):
// the cells meeting the ball of radius h = ri + r_max,fine + max_gap around xi, row by row.
void ball_pairs(std::int32_t i, const Vec3& xi, double ri, const Level& fine, double max_gap,
                std::vector<ParticlePair>& out) {
    // Slightly larger than any reach, so rounding in the cell bounds cannot lose a partner.
    const double h = (ri + fine.r_max + max_gap) * (1.0 + 1e-9);
    const Cell lo = fine.cell_of(xi - Vec3{h, h, h});
    const Cell hi = fine.cell_of(xi + Vec3{h, h, h});
    auto gap_to = [&](double v, double o, std::int64_t c) {  // distance from v to a cell slab
        const double a = o + static_cast<double>(c) * fine.cell, b = a + fine.cell;
        return v < a ? a - v : (v > b ? v - b : 0.0);
    };
    for (std::int64_t cz = lo[2]; cz <= hi[2]; ++cz) {
        const double dz = gap_to(xi.z, fine.origin.z, cz);
        if (dz > h) continue;
        for (std::int64_t cy = lo[1]; cy <= hi[1]; ++cy) {
            const double dy = gap_to(xi.y, fine.origin.y, cy);
            const double rest = h * h - dy * dy - dz * dz;
            if (rest < 0.0) continue;
            const double w = std::sqrt(rest) * (1.0 + 1e-9);
            const std::int64_t x0 = fine.coord(xi.x - w, fine.origin.x, 0);
            const std::int64_t x1 = fine.coord(xi.x + w, fine.origin.x, 0);
            for (std::int64_t cx = x0; cx <= x1; ++cx) {
                const std::uint64_t key = pack({cx, cy, cz});
                const std::size_t b = fine.bucket(key);
                for (auto q = static_cast<std::size_t>(fine.bucket_start[b]);
                     q < static_cast<std::size_t>(fine.bucket_start[b + 1]); ++q)
                    if (fine.key[q] == key)
                        check(i, xi, ri, fine.id[q], fine.x[q], fine.r[q], max_gap, out);
            }
        }
    }
}

// Entries [begin, end) of level `scanner`: the same-level stencil when target == scanner,
// else a ball scan of level `target`.
struct Task {
    std::size_t scanner = 0, target = 0;
    std::int64_t begin = 0, end = 0;
};

class MultilevelGridSearch final : public NeighborSearch {
public:
    void find_pairs(const std::vector<Vec3>& x, const std::vector<double>& r, double max_gap,
                    std::vector<ParticlePair>& pairs) override {
        pairs.clear();
        if (x.size() < 2) return;
        build_levels(x, r, max_gap);
        make_tasks();
        run_tasks(max_gap);
        sort_pairs(x.size(), pairs);
    }
    [[nodiscard]] std::string name() const override { return "multilevel-grid"; }

private:
    std::vector<Level> levels_;
    double volume_ = 1.0;  // bounding box of all particles, padded by one largest reach [m^3]
    std::vector<Task> tasks_;
    std::vector<std::vector<ParticlePair>> found_;  // per task
    std::vector<std::int64_t> pair_start_;          // CSR by first index

    void build_levels(const std::vector<Vec3>& x, const std::vector<double>& r, double max_gap) {
        Vec3 lo = x.front(), hi = x.front();
        for (const Vec3& p : x) {
            lo = {std::min(lo.x, p.x), std::min(lo.y, p.y), std::min(lo.z, p.z)};
            hi = {std::max(hi.x, p.x), std::max(hi.y, p.y), std::max(hi.z, p.z)};
        }
        const double s_max = 2.0 * *std::max_element(r.begin(), r.end()) + max_gap;
        const Vec3 span = hi - lo + Vec3{s_max, s_max, s_max};
        volume_ = std::max(span.x * span.y * span.z, std::numeric_limits<double>::min());
        const LevelPlan plan = plan_levels(r, max_gap, volume_);
        std::vector<std::vector<std::int32_t>> members(plan.cell.size());
        for (std::size_t i = 0; i < x.size(); ++i) {
            const double s = 2.0 * r[i] + max_gap;
            std::size_t l = 0;
            while (l + 1 < plan.cell.size() && s > plan.cell[l]) ++l;
            members[l].push_back(static_cast<std::int32_t>(i));
        }
        std::erase_if(members, [](const auto& m) { return m.empty(); });
        levels_.resize(members.size());
        for (std::size_t l = 0; l < members.size(); ++l) build_level(x, r, max_gap, members[l], levels_[l]);
    }

    // Fixed blocks of entries (sizes depend on the levels only, never on the thread count).
    void add_tasks(std::size_t scanner, std::size_t target, std::int64_t block) {
        const auto n = static_cast<std::int64_t>(levels_[scanner].size());
        for (std::int64_t b = 0; b < n; b += block) tasks_.push_back({scanner, target, b, std::min(n, b + block)});
    }

    void make_tasks() {
        tasks_.clear();
        for (std::size_t l = 0; l < levels_.size(); ++l) {
            add_tasks(l, l, kSameLevelBlock);
            for (std::size_t m = 0; m < l; ++m) {
                const Level& coarse = levels_[l];
                const Level& fine = levels_[m];
                const auto n_c = static_cast<double>(coarse.size()), n_f = static_cast<double>(fine.size());
                const double top_down = scan_cost(n_c, coarse.cell, n_f, fine.cell, volume_);
                const double bottom_up = scan_cost(n_f, fine.cell, n_c, coarse.cell, volume_);
                const bool down = top_down <= bottom_up;
                const double per_entry = down ? top_down / n_c : bottom_up / n_f;
                const auto block = static_cast<std::int64_t>(
                    std::clamp(static_cast<double>(kCrossLevelWork) / per_entry, 1.0, 2048.0));
                if (down) add_tasks(l, m, block);
                else add_tasks(m, l, block);
            }
        }
        found_.resize(tasks_.size());
    }

    void run_tasks(double max_gap) {
        const auto count = static_cast<std::int64_t>(tasks_.size());
#pragma omp parallel for schedule(dynamic, 1)
        for (std::int64_t t = 0; t < count; ++t) {
            const Task& task = tasks_[static_cast<std::size_t>(t)];
            auto& out = found_[static_cast<std::size_t>(t)];
            out.clear();
            const Level& level = levels_[task.scanner];
            if (task.scanner == task.target) {
                same_level_pairs(level, task.begin, task.end, max_gap, out);
                continue;
            }
            const Level& target = levels_[task.target];
            for (std::int64_t e = task.begin; e < task.end; ++e) {
                const auto k = static_cast<std::size_t>(e);
                ball_pairs(level.id[k], level.x[k], level.r[k], target, max_gap, out);
            }
        }
    }

    // Counting sort by i, then each i's partners by j: sorted (i, j) whatever the task order.
    void sort_pairs(std::size_t n, std::vector<ParticlePair>& pairs) {
        pair_start_.assign(n + 1, 0);
        for (const auto& v : found_)
            for (const ParticlePair& p : v) ++pair_start_[static_cast<std::size_t>(p.i) + 1];
        for (std::size_t i = 0; i < n; ++i) pair_start_[i + 1] += pair_start_[i];
        pairs.resize(static_cast<std::size_t>(pair_start_[n]));
        std::vector<std::int64_t> fill(pair_start_.begin(), pair_start_.end() - 1);
        for (const auto& v : found_)
            for (const ParticlePair& p : v) pairs[static_cast<std::size_t>(fill[static_cast<std::size_t>(p.i)]++)] = p;
        for_each_block(static_cast<std::int64_t>(n), [&](std::int64_t begin, std::int64_t end, std::int64_t) {
            for (auto i = static_cast<std::size_t>(begin); i < static_cast<std::size_t>(end); ++i)
                std::sort(pairs.begin() + pair_start_[i], pairs.begin() + pair_start_[i + 1]);
        });
    }
};

}  // namespace

std::unique_ptr<NeighborSearch> make_multilevel_grid_search() {
    return std::make_unique<MultilevelGridSearch>();
}

}  // namespace gradem
