// The flat joint as an interface (core/flat_joint_law.hpp): what it keeps once its elements are
// unbonded, the joint types, the friction angle and the gap stiffness, each against a hand
// calculation. Two spheres of radius R, B on +x (n = x), joint frame t1 = z, t2 = -y.
#include <catch2/catch.hpp>
#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

#include "bond_rig.hpp"
#include "core/contact_law.hpp"
#include "core/flat_joint_law.hpp"

using namespace gradem;
using namespace gradem::test;

namespace {

BondParams slit_joint(std::int32_t nr, std::int32_t na, double unbonded_stiffness_ratio = 1.0) {
    BondParams bp = joint(nr, na);
    bp.law<FlatJointLaw>().bonded_fraction = 0.0;
    bp.law<FlatJointLaw>().unbonded_stiffness_ratio = unbonded_stiffness_ratio;
    return bp;
}

/// Moves B toward A by `depth` [m] over `steps` steps, then holds it.
void press(BondRig& rig, double depth, int steps) {
    rig.set_motion({-depth / (steps * rig.dt), 0, 0}, {});
    for (int s = 0; s < steps; ++s) rig.world.step();
    rig.set_motion({}, {});
}

/// Integrals over the part ξ < c of the unit disc: ∫ dA, ∫ ξ dA, ∫ ξ² dA (circular segment).
struct Segment { double area, first, second; };
Segment disc_below(double c) {
    c = std::clamp(c, -1.0, 1.0);
    auto area = [](double x) { return x * std::sqrt(1 - x * x) + std::asin(x); };
    auto first = [](double x) { return -2.0 / 3.0 * std::pow(1 - x * x, 1.5); };
    auto second = [](double x) { return 0.25 * (x * (2 * x * x - 1) * std::sqrt(1 - x * x) + std::asin(x)); };
    return {area(c) - area(-1.0), first(c) - first(-1.0), second(c) - second(-1.0)};
}

/// Reference for compressed_part, independent of its method: in long double, the pieces between
/// the angles where the zero line crosses the arcs, each integrated by adaptive bisection with a
/// 20-node Gauss-Legendre rule in angle (to 1e-20 of the scale), the rays exactly.
/// Returns ∫ min(g,0) dA, ∫ min(g,0) ξ dA (2), ∫ min(g,0)² dA over the element (unit disc).
struct Reference {
    using LD = long double;
    std::vector<LD> x, w;
    Reference() {  // Gauss-Legendre nodes on [-1, 1] by Newton on P_20
        const int m = 20;
        const LD pi = 3.141592653589793238462643383279502884L;
        for (int i = 0; i < m; ++i) {
            LD t = std::cos(pi * (i + 0.75L) / (m + 0.5L)), dp = 1;
            for (int it = 0; it < 100; ++it) {
                LD p0 = 1, p1 = t;
                for (int k = 2; k <= m; ++k) {
                    const LD p2 = ((2.0L * k - 1) * t * p1 - (k - 1.0L) * p0) / k;
                    p0 = p1;
                    p1 = p2;
                }
                dp = m * (t * p1 - p0) / (t * t - 1);
                const LD step = p1 / dp;
                t -= step;
                if (std::fabs(step) < 1e-21L) break;
            }
            x.push_back(t);
            w.push_back(2 / ((1 - t * t) * dp * dp));
        }
    }
    std::array<LD, 4> rule(const DiscElement& e, LD g, LD wy, LD wz, LD lo_angle, LD hi_angle) const {
        std::array<LD, 4> acc{};
        const LD mid = (lo_angle + hi_angle) / 2, half = (hi_angle - lo_angle) / 2, r0 = e.r0, r1 = e.r1;
        for (std::size_t q = 0; q < x.size(); ++q) {
            const LD a = mid + half * x[q], c = std::cos(a), s = std::sin(a), sl = wy * c + wz * s, wq = half * w[q];
            LD lo = r0, hi = r1;  // the compressed part of the ray: g + sl ρ < 0
            if (sl > 0) hi = std::min(r1, -g / sl);
            else if (sl < 0) lo = std::max(r0, -g / sl);
            else if (!(g < 0)) continue;
            if (!(hi > lo)) continue;
            const LD d2 = (hi * hi - lo * lo) / 2, d3 = (hi * hi * hi - lo * lo * lo) / 3;
            const LD d4 = (hi * hi * hi * hi - lo * lo * lo * lo) / 4;
            acc[0] += wq * (g * d2 + sl * d3);
            acc[1] += wq * (g * d3 + sl * d4) * c;
            acc[2] += wq * (g * d3 + sl * d4) * s;
            acc[3] += wq * (g * g * d2 + 2 * g * sl * d3 + sl * sl * d4);
        }
        return acc;
    }
    std::array<double, 4> operator()(const DiscElement& e, double gd, double wyd, double wzd) const {
        const LD g = gd, wy = wyd, wz = wzd, pi = 3.141592653589793238462643383279502884L;
        std::vector<LD> cuts{e.a0, e.a1};
        const LD slope = std::sqrt(wy * wy + wz * wz), dir = std::atan2(wz, wy);
        for (const LD r : {LD(e.r0), LD(e.r1)}) {
            const LD c = -g / (slope * r);
            if (!(r > 0 && c > -1 && c < 1)) continue;
            for (LD a : {dir + std::acos(c), dir - std::acos(c)}) {
                while (a < e.a0) a += 2 * pi;
                while (a >= e.a0 + 2 * pi) a -= 2 * pi;
                if (a > e.a0 && a < e.a1) cuts.push_back(a);
            }
        }
        std::sort(cuts.begin(), cuts.end());
        const LD scale = (std::fabs(g) + slope * e.r1) * e.area;
        std::array<LD, 4> sum{};
        auto adapt = [&](auto&& self, LD a, LD b, const std::array<LD, 4>& whole, int depth) -> void {
            const LD m = (a + b) / 2;
            const auto left = rule(e, g, wy, wz, a, m), right = rule(e, g, wy, wz, m, b);
            LD diff = 0;
            for (int k = 0; k < 4; ++k) diff = std::max(diff, std::fabs(left[k] + right[k] - whole[k]));
            if (diff < 1e-20L * scale || depth > 40) {
                for (int k = 0; k < 4; ++k) sum[k] += left[k] + right[k];
                return;
            }
            self(self, a, m, left, depth + 1);
            self(self, m, b, right, depth + 1);
        };
        for (std::size_t p = 0; p + 1 < cuts.size(); ++p)
            adapt(adapt, cuts[p], cuts[p + 1], rule(e, g, wy, wz, cuts[p], cuts[p + 1]), 0);
        return {double(sum[0]), double(sum[1]), double(sum[2]), double(sum[3])};
    }
};

}  // namespace

// The compressed part of one element (disc_elements.hpp: closed-form area moments of the
// region where the zero line leaves g < 0) against the reference quadrature, for lines anywhere,
// lines nearly tangent to an arc (slivers) and lines through or near the disc centre. Measured:
// relative error <= 1e-12 where the integral is at least 1e-3 of its scale, and <= 4e-15 of the
// scale (k_n (|γ| + |w| r1) A_e, times r1 for P, squared for U) everywhere; the Gauss rule it
// replaced (8 nodes per piece) erred by up to 3e-2 relative, 1e-4 of the scale.
TEST_CASE("flat joint: an element's compressed part is the exact integral over the disc cut by the zero line",
          "[core][flat_joint]") {
    const Reference reference;
    std::mt19937_64 bits(11);
    auto uniform = [&]() { return static_cast<double>(bits() >> 11) * 0x1p-53; };
    const std::pair<int, int> layouts[] = {{1, 1}, {1, 4}, {2, 6}, {3, 8}, {4, 5}};
    double worst_relative = 0.0, worst_scaled = 0.0;
    for (const auto& [nr, na] : layouts) {
        const std::vector<DiscElement> elements = disc_elements(nr, na);
        for (int trial = 0; trial < 240; ++trial) {
            const DiscElement& e = elements[static_cast<std::size_t>(trial) % elements.size()];
            const double phi = (2.0 * uniform() - 1.0) * kPi, arc = uniform() < 0.5 ? e.r0 : e.r1;
            double gamma = 2.4 * uniform() - 1.2;  // anywhere
            if (trial % 3 == 1) gamma = (uniform() < 0.5 ? 1 : -1) * arc * (1 - std::pow(10.0, -1 - 8 * uniform()));
            if (trial % 3 == 2) gamma = (2.0 * uniform() - 1.0) * std::pow(10.0, -12 * uniform());
            const double wy = std::cos(phi), wz = std::sin(phi);
            ZeroLineCache line;
            line.prepare(gamma, wy, wz);
            const CompressedPart c =
                compressed_part(e, line.field, line.crossing(e.ring, e.r0), line.crossing(e.ring + 1, e.r1));
            const std::array<double, 4> got{c.force, c.py, c.pz, c.energy}, want = reference(e, gamma, wy, wz);
            const double scale_f = (std::fabs(gamma) + e.r1) * e.area;
            const double scale[4] = {scale_f, scale_f * e.r1, scale_f * e.r1, scale_f * scale_f / e.area};
            for (int k = 0; k < 4; ++k) {
                INFO(nr << "x" << na << " a0 " << e.a0 << " r1 " << e.r1 << " gamma " << gamma << " phi " << phi << " k " << k);
                const double err = std::fabs(got[static_cast<std::size_t>(k)] - want[static_cast<std::size_t>(k)]);
                REQUIRE(std::isfinite(got[static_cast<std::size_t>(k)]));
                worst_scaled = std::max(worst_scaled, err / scale[k]);
                if (std::fabs(want[static_cast<std::size_t>(k)]) > 1e-3 * scale[k])
                    worst_relative = std::max(worst_relative, err / std::fabs(want[static_cast<std::size_t>(k)]));
            }
        }
    }
    CHECK(worst_relative < 1e-11);
    CHECK(worst_scaled < 1e-13);
}

// A bonded joint pressed to σ and sheared breaks when τ = c̄ + |σ| tan φ̄ (all elements at
// once: uniform stresses); broken and closed, it then carries ρ σ A at the same closure (ρ:
// the unbonded elements' share of k̄_n) and slides at |F_s| = μ_r |F_n|, and it still acts (an
// interface, not a released bond).
TEST_CASE("flat joint: the friction angle adds |sigma| tan(phi) to the shear strength, broken and closed, "
          "the joint slides at mu_r N", "[core][flat_joint]") {
    const std::pair<double, double> cases[] = {{0.0, 1.0}, {30.0, 1.0}, {0.0, 0.45}};
    for (const auto& [phi_deg, rho] : cases) {
        INFO("phi " << phi_deg << " rho " << rho);
        BondParams bp = joint(1, 4);
        bp.cohesion_mean = 4.0e6;
        bp.tensile_strength_mean = 2.0e6;
        bp.friction_angle_deg = phi_deg;
        bp.law<FlatJointLaw>().unbonded_stiffness_ratio = rho;
        BondRig rig(bp);
        const double sigma = -5.0e6;  // [Pa], compression
        press(rig, -sigma / rig.stiffness.normal, 200);
        REQUIRE(rig.axial_stress() == Approx(sigma).epsilon(1e-6));
        const double strength = bp.cohesion_mean - sigma * std::tan(phi_deg * kPi / 180.0);
        const double per_step = strength / 1000.5;  // shear stress increment [Pa]
        rig.set_motion({0, per_step / rig.stiffness.shear / rig.dt, 0}, {});
        int broke = 0;
        for (int s = 1; s <= 1500 && rig.intact(); ++s) {
            rig.world.step();
            if (!rig.intact()) broke = s;
        }
        REQUIRE(broke > 0);
        const auto& events = rig.world.break_events();
        REQUIRE(events.size() == 4u);
        for (const BreakEvent& e : events) {
            CHECK(e.mode == BondState::broken_shear);
            const double envelope = bp.cohesion_mean - e.tensile_stress * std::tan(phi_deg * kPi / 180.0);
            CHECK(e.shear_stress >= envelope);
            CHECK(e.shear_stress < envelope + 1.5 * per_step);
            CHECK(e.shear_stress == Approx(strength).epsilon(3e-3));
        }
        CHECK(rig.bond().state == BondState::broken_shear);
        CHECK(rig.bond().interface == 1);
        for (std::size_t e = 0; e < 4; ++e) CHECK_FALSE(flat_joint_element_bonded(rig.world.bond_side_state(0), e));
        for (int s = 0; s < 300; ++s) rig.world.step();
        CHECK(bond_acts(rig.bond()));
        const double normal = rig.bond().normal_force;
        CHECK(normal == Approx(rho * sigma * rig.section.area).epsilon(2e-3));
        CHECK(norm(rig.bond().shear_force) == Approx(0.5 * std::fabs(normal)).epsilon(1e-9));
        CHECK(rig.world.energy().friction > 0.0);
    }
}

// A slit joint (unbonded, no initial gap) pressed by δ0 and bent by θ: gap g = -δ0 + θ z over
// the disc; the compressed part z < δ0/θ carries σ = ρ k_n g. Normal force and moment against
// the circular-segment integrals, from fully closed to mostly open, for several layouts.
TEST_CASE("flat joint: an unbonded joint resists bending through its compressed part, as the hand "
          "integral over the disc", "[core][flat_joint]") {
    struct Layout { int nr, na; double rho; };  // rho: the unbonded elements' share of k_n
    const Layout layouts[] = {{1, 1, 1.0}, {1, 4, 1.0}, {2, 6, 1.0}, {3, 8, 1.0}, {1, 4, 0.3}, {3, 8, 0.3}};
    for (const auto& [nr, na, rho] : layouts) {
        INFO("N_r " << nr << " N_a " << na << " rho " << rho);
        BondRig rig(slit_joint(nr, na, rho), 0.0);
        REQUIRE(rig.bond().state == BondState::none);
        REQUIRE(bond_acts(rig.bond()));
        const double kn = rho * rig.stiffness.normal, R = rig.section.radius, depth = 1.0e-6;
        press(rig, depth, 100);
        const double w = 3.7, per_step = 2.0 * w * rig.dt;
        const int steps = static_cast<int>(depth / (0.15 * R) / per_step);  // to c = 0.15
        rig.set_motion({}, {0, w, 0}, {0, -w, 0});
        double worst_force = 0.0, worst_moment = 0.0;
        for (int s = 1; s <= steps; ++s) {
            rig.world.step();
            const double theta = s * per_step;
            const Segment g = disc_below(depth / (theta * R));
            const double fn = kn * R * R * (-depth * g.area + theta * R * g.first);
            const double pz = kn * R * R * R * (-depth * g.first + theta * R * g.second);
            worst_force = std::max(worst_force, std::fabs(rig.bond().normal_force - fn) / std::fabs(fn));
            worst_moment = std::max(worst_moment, std::fabs(rig.world.particles().torque[1].y + pz) / std::fabs(pz));
        }
        // Closed form (exact to round-off): measured worst 5.9e-12 (force), 1.9e-12 (moment) for
        // every layout, the rig's own round-off in θ (the Gauss rule before: 4.7e-6, 1x4).
        CHECK(worst_force < 2e-11);
        CHECK(worst_moment < 2e-11);
        CHECK(bond_acts(rig.bond()));
    }
}

// A gapped joint (g_0 = gap_ratio R̄) carries nothing until its gap has closed, then
// F_n = k_n A (δ + g_0): the hand solution of a uniform press.
TEST_CASE("flat joint: a gapped joint carries nothing until its initial gap closes", "[core][flat_joint]") {
    BondParams bp = joint(1, 4);
    bp.law<FlatJointLaw>().bonded_fraction = 0.0;
    bp.law<FlatJointLaw>().gapped_fraction = 1.0;
    bp.law<FlatJointLaw>().gap_ratio = 2.0e-3;
    BondRig rig(bp);
    const double g0 = bp.law<FlatJointLaw>().gap_ratio * rig.section.radius;
    REQUIRE(rig.world.bond_side_state(0)[flat_side::initial_gap] == Approx(g0).epsilon(1e-12));
    REQUIRE(flat_joint_type(rig.world.bond_side_state(0)) == FlatJointType::gapped);
    const double per_step = 3.0 * g0 / 3000.0;
    rig.set_motion({-per_step / rig.dt, 0, 0}, {});
    bool carried_early = false;
    double worst = 0.0;
    for (int s = 1; s <= 3000; ++s) {
        rig.world.step();
        const double delta = rig.opening();
        if (delta > -g0 * (1 - 1e-6)) {
            carried_early = carried_early || rig.bond().normal_force != 0.0;
        } else if (delta < -g0 * (1 + 1e-3)) {
            const double expected = rig.stiffness.normal * rig.section.area * (delta + g0);
            worst = std::max(worst, std::fabs(rig.bond().normal_force - expected) / std::fabs(expected));
        }
    }
    CHECK_FALSE(carried_early);
    CHECK(worst < 1e-6);
    CHECK(rig.bond().normal_force < 0.0);
}

// A joint broken in tension stays an interface while the pair is within the installation
// reach: closed again it carries compression (ρ k_n A δ, ρ the unbonded elements' share of
// k_n); once every element is open and the surfaces are beyond the reach it is released (no
// longer acting), and its pair's linear contact acts again when they touch.
TEST_CASE("flat joint: a joint broken in tension recloses in compression, and is released once its "
          "surfaces separate beyond the installation reach", "[core][flat_joint]") {
    for (const double rho : {1.0, 0.25}) {
        INFO("rho " << rho);
        BondParams bp = joint(1, 4);
        bp.tensile_strength_mean = 2.0e6;
        bp.law<FlatJointLaw>().unbonded_stiffness_ratio = rho;
        const double reach = 2.0e-6;
        BondRig rig(bp, kRigGap, reach);
        const double per_step = bp.tensile_strength_mean / rig.stiffness.normal / 500.5;
        rig.set_motion({per_step / rig.dt, 0, 0}, {});
        for (int s = 0; s < 600; ++s) rig.world.step();
        REQUIRE(rig.bond().state == BondState::broken_tension);
        CHECK(rig.bond().interface == 1);
        CHECK(rig.bond().normal_force == 0.0);
        // Back through the installed position into compression.
        rig.set_motion({-per_step / rig.dt, 0, 0}, {});
        for (int s = 0; s < 1200; ++s) rig.world.step();
        const double delta = rig.opening();
        REQUIRE(delta < 0.0);
        CHECK(rig.bond().normal_force == Approx(rho * rig.stiffness.normal * rig.section.area * delta).epsilon(1e-6));
        // Apart beyond the reach: released.
        rig.set_motion({10 * per_step / rig.dt, 0, 0}, {});
        int released = 0;
        for (int s = 1; s <= 2000 && bond_acts(rig.bond()); ++s) {
            rig.world.step();
            if (!bond_acts(rig.bond())) released = s;
        }
        REQUIRE(released > 0);
        const double gap_at_release = rig.rest_distance + rig.opening() - 2.0 * kRigRadius;
        CHECK(gap_at_release > reach);
        CHECK(gap_at_release < reach + 10 * per_step * 1.01);
        CHECK(rig.bond().interface == 0);
        CHECK(rig.bond().state == BondState::broken_tension);
        // Pushed back into overlap: the pair's linear contact acts again, k_n |δ| on each side.
        rig.set_motion({-10 * per_step / rig.dt, 0, 0}, {});
        while (rig.rest_distance + rig.opening() > 2.0 * kRigRadius - 1.0e-7) rig.world.step();
        const double overlap = 2.0 * kRigRadius - (rig.rest_distance + rig.opening());
        const double kn = contact_normal_stiffness(kRigModulus, kRigRadius, kRigRadius);
        CHECK_FALSE(bond_acts(rig.bond()));
        CHECK(rig.world.particles().force[1].x == Approx(kn * overlap).epsilon(1e-9));
        CHECK(rig.world.particles().force[0].x == Approx(-kn * overlap).epsilon(1e-9));
    }
}

// k̄_n of a joint installed across a gap g: Ē*/(R_A + R_B + g) with stiffness_over_gap, the
// touching pair's Ē*/(R_A + R_B) without; zero force at installation either way.
TEST_CASE("flat joint: a joint installed across a gap has the stiffness of a bridge that long",
          "[core][flat_joint]") {
    const double gap = 0.25 * kRigRadius;
    for (bool over_gap : {false, true}) {
        INFO("stiffness_over_gap " << over_gap);
        BondParams bp = joint(1, 4);
        bp.law<FlatJointLaw>().stiffness_over_gap = over_gap;
        BondRig rig(bp, gap);
        rig.world.step();
        CHECK(rig.bond().normal_force == 0.0);
        rig.set_motion({1.0e-4, 0, 0}, {});
        for (int s = 0; s < 200; ++s) rig.world.step();
        const double length = 2.0 * kRigRadius + (over_gap ? gap : 0.0);
        const double kn = kRigModulus / length;
        CHECK(rig.bond().normal_force == Approx(kn * rig.section.area * rig.opening()).epsilon(1e-9));
    }
}

// Types drawn per joint with the strength seed: on ~1e4 joints the fractions come out as asked
// (4 binomial standard deviations), gapped joints get g_0 = gap_ratio R̄, the draw is the same
// on a second installation, and slit and gapped joints act as interfaces from the start.
TEST_CASE("flat joint: bonded, gapped and slit joints come out in the stated fractions", "[core][flat_joint]") {
    BondParams bp = joint(1, 3);
    bp.law<FlatJointLaw>().bonded_fraction = 0.55;
    bp.law<FlatJointLaw>().gapped_fraction = 0.25;
    bp.law<FlatJointLaw>().gap_ratio = 0.02;
    auto install = [&]() {
        World world(jittered_cluster(14, 1.0e-3, 7), frictionless(1.0e9), SimParams{});
        world.install_bonds(bp, 0.5e-3);
        return world;
    };
    World world = install();
    const std::size_t n = world.bonds().size();
    REQUIRE(n > 7000);
    std::size_t counts[3] = {0, 0, 0};
    std::vector<int> types;
    for (std::size_t k = 0; k < n; ++k) {
        const auto side = world.bond_side_state(k);
        const FlatJointType t = flat_joint_type(side);
        types.push_back(static_cast<int>(t));
        ++counts[static_cast<int>(t)];
        const ParallelBond& b = world.bonds()[k];
        const double rbar = std::min(world.particles().radius[static_cast<std::size_t>(b.i)],
                                     world.particles().radius[static_cast<std::size_t>(b.j)]);
        if (t == FlatJointType::gapped) CHECK(side[flat_side::initial_gap] == Approx(0.02 * rbar).epsilon(1e-12));
        else CHECK(side[flat_side::initial_gap] == 0.0);
        CHECK((b.state == BondState::intact) == (t == FlatJointType::bonded));
        CHECK(bond_acts(b));
    }
    const double fractions[3] = {0.55, 0.25, 0.20};
    for (int t = 0; t < 3; ++t) {
        INFO("type " << t);
        const double expected = fractions[t] * static_cast<double>(n);
        const double sd = std::sqrt(static_cast<double>(n) * fractions[t] * (1 - fractions[t]));
        CHECK(std::fabs(static_cast<double>(counts[t]) - expected) < 4.0 * sd);
    }
    World again = install();
    for (std::size_t k = 0; k < n; ++k) REQUIRE(static_cast<int>(flat_joint_type(again.bond_side_state(k))) == types[k]);
}
