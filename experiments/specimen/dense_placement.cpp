#include "experiments/specimen/dense_placement.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "core/contact_law.hpp"
#include "core/parallel.hpp"
#include "core/random.hpp"
#include "experiments/specimen/morton_order.hpp"

namespace gradem::exp {
namespace {

// FIRE 2.0 parameters (Guenole et al. 2020, Table 1), times in units of 1/omega (unit masses).
// kDtMax: Guenole et al. use 10 x the start step; in unit-mass scaling the stiffest grain's
// frequency is about 2 (a few contacts plus a wall), so semi-implicit Euler is stable below
// ~0.9. Measured on 2e4 grains of the pre-blended sand: dt_max 0.35 / 0.5 / 0.7 / 1.0 took
// 12489 / 9361 / 8168 / > 20000 iterations (1.0 is past the stability limit, FIRE keeps
// restarting); 0.5 keeps a margin for gradations with larger size ratios.
constexpr double kDtStart = 0.1, kDtMax = 0.5, kDtMin = 0.002;
constexpr double kIncrease = 1.1, kDecrease = 0.5, kAlphaStart = 0.25, kAlphaShrink = 0.99;
constexpr int kDelay = 20;         // uphill-free steps before dt may grow
constexpr double kSkinFraction = 0.3;  // Verlet skin / mean radius [-]

double& component(Vec3& v, int a) { return a == 0 ? v.x : (a == 1 ? v.y : v.z); }

// Fixed blocks (core/parallel.hpp), run in parallel only when there are enough of them: an
// iteration is a few microseconds per block, and two OpenMP barriers per iteration cost more
// than that for small packings (and far more on a loaded machine). Same blocks either way, so
// the results do not change.
constexpr std::int64_t kMinParallelBlocks = 8;

template <class Body>
void for_blocks(std::int64_t n, Body&& body) {
    if (block_count(n) >= kMinParallelBlocks) return for_each_block(n, body);
    for (std::int64_t b = 0; b < block_count(n); ++b) body(b * kBlockSize, std::min(n, (b + 1) * kBlockSize), b);
}

}  // namespace

// Per-block partial sums of one force evaluation (combined in block order).
struct DensePacker::Sums {
    double unbalanced = 0.0;      // sum |F_i| [N]
    double contact_force = 0.0;   // sum of contact normal forces [N]
    std::int64_t contacts = 0;    // pairs and wall contacts with a force
    double power = 0.0;           // sum F.v
    double force_norm2 = 0.0;     // sum |F|^2 / m (mass-weighted metric)
    double velocity_norm2 = 0.0;  // sum m |v|^2
    Vec3 virial;                  // sum f n_a d_a over pairs plus the wall terms [N m]
    Vec3 wall_lo, wall_hi;        // total force on each wall [N]
    double max_overlap = 0.0, overlap_sum = 0.0;  // overlap / smaller diameter
    std::int64_t pair_contacts = 0;
    Sums& operator+=(const Sums& o) {
        unbalanced += o.unbalanced, contact_force += o.contact_force, contacts += o.contacts;
        power += o.power, force_norm2 += o.force_norm2, velocity_norm2 += o.velocity_norm2;
        virial += o.virial, wall_lo += o.wall_lo, wall_hi += o.wall_hi;
        max_overlap = std::max(max_overlap, o.max_overlap), overlap_sum += o.overlap_sum;
        pair_contacts += o.pair_contacts;
        return *this;
    }
};

DensePacker::DensePacker(const std::vector<double>& diameters, double edge, double modulus, std::uint64_t seed)
    : modulus_(modulus), box_{edge, edge, edge}, search_(make_neighbor_search()) {
    if (diameters.empty()) throw std::invalid_argument("DensePacker: no grains");
    const std::size_t n = diameters.size();
    r_.resize(n), m_.resize(n), x_.resize(n), v_.assign(n, Vec3{}), f_.assign(n, Vec3{});
    SplitMix64 rng(seed);
    double r_sum = 0.0, box_mass = 0.0;
    for (std::size_t i = 0; i < n; ++i) {
        const double r = 0.5 * diameters[i];
        if (!(r > 0.0) || 2.0 * r >= edge) throw std::invalid_argument("DensePacker: grain diameter out of range");
        r_[i] = r;
        m_[i] = wall_normal_stiffness(modulus, r);  // fictitious mass: natural frequency ~ 1
        x_[i] = {rng.uniform(r, edge - r), rng.uniform(r, edge - r), rng.uniform(r, edge - r)};
        r_sum += r;
        box_mass += m_[i] * 4.0 * r * r;
    }
    box_mass_ = {box_mass, box_mass, box_mass};
    skin_ = kSkinFraction * r_sum / static_cast<double>(n);
    // Grains in Morton order of their drop positions: neighbours in space are neighbours in
    // memory, so the force loop's x_[j] loads hit the cache (at 2e5 grains the positions no
    // longer fit in L2). The box shrinks affinely, which keeps the order close to Morton.
    const std::vector<std::int32_t> order = morton_order(x_, {0, 0, 0}, box_);
    x_ = permuted(x_, order), r_ = permuted(r_, order), m_ = permuted(m_, order);
}

void DensePacker::grow(std::size_t i, double factor) {
    r_[i] *= factor;
    m_[i] = wall_normal_stiffness(modulus_, r_[i]);
    rebuild_needed_ = true;
}

double DensePacker::solid_fraction() const {
    double solid = 0.0;
    for (double r : r_) solid += 4.0 / 3.0 * kPi * r * r * r;
    return solid / (box_.x * box_.y * box_.z);
}

void DensePacker::rebuild_neighbors() {
    search_->find_pairs(x_, r_, skin_, pairs_);
    const std::size_t n = x_.size();
    nbr_start_.assign(n + 1, 0);
    for (const ParticlePair& p : pairs_) ++nbr_start_[static_cast<std::size_t>(p.i) + 1], ++nbr_start_[static_cast<std::size_t>(p.j) + 1];
    for (std::size_t i = 0; i < n; ++i) nbr_start_[i + 1] += nbr_start_[i];
    nbr_.resize(2 * pairs_.size());
    std::vector<std::int32_t> fill(nbr_start_.begin(), nbr_start_.end() - 1);
    for (const ParticlePair& p : pairs_) {  // sorted pairs: every list comes out in a fixed order
        nbr_[static_cast<std::size_t>(fill[static_cast<std::size_t>(p.i)]++)] = p.j;
        nbr_[static_cast<std::size_t>(fill[static_cast<std::size_t>(p.j)]++)] = p.i;
    }
    x_at_rebuild_ = x_;
    rebuild_needed_ = false;
    ++rebuilds_;
}

// Forces on every grain (frictionless linear contacts with neighbours and walls) and the
// generalised forces on the box edges, -dH/d ln L_a = virial_a - p V.
DensePacker::Sums DensePacker::compute_forces(double pressure) {
    if (rebuild_needed_) rebuild_neighbors();
    const auto n = static_cast<std::int64_t>(x_.size());
    std::vector<Sums> partial(static_cast<std::size_t>(block_count(n)));
    for_blocks(n, [&](std::int64_t begin, std::int64_t end, std::int64_t block) {
        Sums s;
        for (std::int64_t ii = begin; ii < end; ++ii) {
            const auto i = static_cast<std::size_t>(ii);
            const Vec3 xi = x_[i];
            const double ri = r_[i];
            Vec3 force;
            for (std::int32_t k = nbr_start_[i]; k < nbr_start_[i + 1]; ++k) {
                const auto j = static_cast<std::size_t>(nbr_[static_cast<std::size_t>(k)]);
                const Vec3 d = x_[j] - xi;
                const double reach = ri + r_[j], dist2 = norm2(d);
                if (dist2 >= reach * reach) continue;
                const double dist = std::sqrt(dist2), overlap = reach - dist;
                const double f = contact_normal_stiffness(modulus_, ri, r_[j]) * overlap;
                const Vec3 n_ij = dist > 0.0 ? (1.0 / dist) * d : Vec3{1, 0, 0};
                force -= f * n_ij;
                if (i < j) {  // pair quantities once per pair
                    s.virial += Vec3{f * n_ij.x * d.x, f * n_ij.y * d.y, f * n_ij.z * d.z};
                    s.contact_force += f, ++s.contacts, ++s.pair_contacts;
                    const double rel = overlap / (2.0 * std::min(ri, r_[j]));
                    s.max_overlap = std::max(s.max_overlap, rel), s.overlap_sum += rel;
                }
            }
            const double kw = m_[i];  // = wall_normal_stiffness(modulus_, ri): the fictitious mass
            for (int a = 0; a < 3; ++a) {
                const double lo = ri - xi[a], hi = xi[a] + ri - box_[a];
                if (lo > 0.0) {
                    component(force, a) += kw * lo;
                    component(s.virial, a) += kw * lo * xi[a];
                    component(s.wall_lo, a) += kw * lo;
                    s.contact_force += kw * lo, ++s.contacts;
                }
                if (hi > 0.0) {
                    component(force, a) -= kw * hi;
                    component(s.virial, a) += kw * hi * (box_[a] - xi[a]);
                    component(s.wall_hi, a) += kw * hi;
                    s.contact_force += kw * hi, ++s.contacts;
                }
            }
            f_[i] = force;
            s.unbalanced += norm(force);
            s.power += dot(force, v_[i]);
            s.force_norm2 += norm2(force) / m_[i];
            s.velocity_norm2 += m_[i] * norm2(v_[i]);
        }
        partial[static_cast<std::size_t>(block)] = s;
    });
    Sums total = ordered_sum(partial);
    const double volume = box_.x * box_.y * box_.z;
    for (int a = 0; a < 3; ++a) {
        const double g = total.virial[a] - pressure * volume;
        component(box_force_, a) = g;
        total.power += g * box_rate_[a];
        total.force_norm2 += g * g / box_mass_[a];
        total.velocity_norm2 += box_mass_[a] * box_rate_[a] * box_rate_[a];
    }
    return total;
}

// Semi-implicit Euler step with FIRE velocity mixing; the box edges scale every centre.
void DensePacker::move(double dt, double alpha, double v_norm, double f_norm) {
    const double mix = f_norm > 0.0 ? alpha * v_norm / f_norm : 0.0;
    Vec3 stretch;
    for (int a = 0; a < 3; ++a) {
        double& rate = component(box_rate_, a);
        rate += dt * box_force_[a] / box_mass_[a];
        rate = (1.0 - alpha) * rate + mix * box_force_[a] / box_mass_[a];
        component(stretch, a) = std::exp(dt * rate);
        component(box_, a) *= stretch[a];
    }
    const auto n = static_cast<std::int64_t>(x_.size());
    std::vector<double> moved(static_cast<std::size_t>(block_count(n)), 0.0);
    for_blocks(n, [&](std::int64_t begin, std::int64_t end, std::int64_t block) {
        double worst = 0.0;
        for (std::int64_t ii = begin; ii < end; ++ii) {
            const auto i = static_cast<std::size_t>(ii);
            const Vec3 a = (1.0 / m_[i]) * f_[i];
            Vec3 v = v_[i] + dt * a;
            v = (1.0 - alpha) * v + mix * a;
            v_[i] = v;
            const Vec3 p = x_[i];
            x_[i] = Vec3{p.x * stretch.x, p.y * stretch.y, p.z * stretch.z} + dt * v;
            worst = std::max(worst, norm2(x_[i] - x_at_rebuild_[i]));
        }
        moved[static_cast<std::size_t>(block)] = worst;
    });
    const double worst = *std::max_element(moved.begin(), moved.end());
    if (worst > 0.25 * skin_ * skin_) rebuild_needed_ = true;
}

PackingBalance DensePacker::balance_of(const Sums& s) const {
    PackingBalance b;
    const double n = static_cast<double>(x_.size());
    b.unbalanced_ratio = s.contacts > 0 && s.contact_force > 0.0
                             ? (s.unbalanced / n) / (s.contact_force / static_cast<double>(s.contacts))
                             : 0.0;
    const Vec3 area{box_.y * box_.z, box_.z * box_.x, box_.x * box_.y};
    b.wall_stress_lo = {s.wall_lo.x / area.x, s.wall_lo.y / area.y, s.wall_lo.z / area.z};
    b.wall_stress_hi = {s.wall_hi.x / area.x, s.wall_hi.y / area.y, s.wall_hi.z / area.z};
    b.max_overlap = s.max_overlap;
    b.mean_overlap = s.pair_contacts > 0 ? s.overlap_sum / static_cast<double>(s.pair_contacts) : 0.0;
    b.contacts = s.contacts;
    return b;
}

PackingBalance DensePacker::balance() { return balance_of(compute_forces(pressure_)); }

namespace {

bool balanced(const PackingBalance& b, double pressure, double ratio_tol, double stress_tol) {
    if (b.contacts == 0 || b.unbalanced_ratio > ratio_tol) return false;
    for (int a = 0; a < 3; ++a)
        if (std::fabs(b.wall_stress_lo[a] - pressure) > stress_tol * pressure ||
            std::fabs(b.wall_stress_hi[a] - pressure) > stress_tol * pressure)
            return false;
    return true;
}

}  // namespace

bool DensePacker::relax(double pressure, double ratio_tol, double stress_tol, std::int64_t budget) {
    pressure_ = pressure;
    double dt = kDtStart, alpha = kAlphaStart;
    int downhill = 0;
    for (std::int64_t it = 0; it < budget; ++it) {
        Sums s = compute_forces(pressure);
        ++iterations_;
        if (balanced(balance_of(s), pressure, ratio_tol, stress_tol)) return true;
        if (s.power > 0.0) {
            if (++downhill > kDelay) dt = std::min(dt * kIncrease, kDtMax), alpha *= kAlphaShrink;
        } else {  // uphill: stop, shorten the step, restart the mixing
            downhill = 0;
            dt = std::max(dt * kDecrease, kDtMin);
            alpha = kAlphaStart;
            std::fill(v_.begin(), v_.end(), Vec3{});
            box_rate_ = {};
            s.power = 0.0, s.velocity_norm2 = 0.0;
        }
        // |v| after the velocity update, from the sums: |v + dt F/m|^2 in the mass metric.
        const double v2 = s.velocity_norm2 + 2.0 * dt * s.power + dt * dt * s.force_norm2;
        move(dt, alpha, std::sqrt(std::max(0.0, v2)), std::sqrt(s.force_norm2));
    }
    return false;
}

std::vector<std::int32_t> DensePacker::contact_counts() {
    if (rebuild_needed_) rebuild_neighbors();
    std::vector<std::int32_t> count(x_.size(), 0);
    for (std::size_t i = 0; i < x_.size(); ++i) {
        for (std::int32_t k = nbr_start_[i]; k < nbr_start_[i + 1]; ++k) {
            const auto j = static_cast<std::size_t>(nbr_[static_cast<std::size_t>(k)]);
            const double reach = r_[i] + r_[j];
            if (norm2(x_[j] - x_[i]) < reach * reach) ++count[i];
        }
        for (int a = 0; a < 3; ++a) count[i] += (x_[i][a] < r_[i]) + (x_[i][a] + r_[i] > box_[a]);
    }
    return count;
}

}  // namespace gradem::exp
