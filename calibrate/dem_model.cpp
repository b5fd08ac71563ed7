// The real cube model: the base cube config's specimen and test, one cached packing per
// (sand, seed), and exp::run_cube_test with the material of the request - or, for a
// CubeTest::tension request (a model made with tension), exp::run_tension_test of the same
// packing (as `gradem tension` runs it: the base config's [tension] table, its strain rate
// rule, the compression test's stop rules).
#include <chrono>
#include <cmath>
#include <map>
#include <mutex>
#include <optional>
#include <sstream>
#include <stdexcept>
#include <thread>

#include "experiments/paste/paste_cache.hpp"
#include "calibrate/cube_model.hpp"
#include "calibrate/execution/thread_pool.hpp"
#include "common/input_error.hpp"
#include "common/number_format.hpp"
#include "experiments/specimen/packing_cache.hpp"
#include "experiments/config/tension_config.hpp"

namespace gradem::cal {
namespace {

using Clock = std::chrono::steady_clock;

struct Timeout : std::runtime_error {
    using std::runtime_error::runtime_error;
};

/// Every k-th point of the gauge-strain curve up to the end (about 200 points).
void thin_curve(const exp::CubeTestResult& r, RunOutcome& out) {
    const auto& c = r.test.curve;
    const std::size_t every = std::max<std::size_t>(1, c.size() / 200);
    for (std::size_t i = 0; i < c.size(); i += every) {
        if (!std::isfinite(c[i].gauge_strain)) continue;
        out.curve_strain.push_back(c[i].gauge_strain);
        out.curve_stress_pa.push_back(c[i].stress);
    }
}

class DemCubeModel final : public CubeModel {
public:
    DemCubeModel(exp::CubeConfig base, const std::vector<std::string>& sands, bool tension) : base_(std::move(base)) {
        if (tension) tension_ = exp::load_tension_config(base_);
        names_ = sands;
        for (const std::string& name : sands) {
            exp::CubeConfig c = base_;
            c.sand = name;
            curves_.push_back(exp::load_gradation(c));
        }
    }

    void prepare(const PackingSeeds& seeds, int workers, const std::function<void(const std::string&)>& log) override {
        std::vector<std::pair<std::size_t, std::uint64_t>> cases;
        for (std::size_t s = 0; s < curves_.size(); ++s)
            for (std::uint64_t seed : seeds.of(s))
                if (!packings_.count({s, seed})) cases.emplace_back(s, seed);
        std::mutex mutex;
        parallel_for(cases.size(), workers, [&](std::size_t k) {
            const auto [s, seed] = cases[k];
            exp::SpecimenSpec spec = base_.specimen;
            spec.seed = seed;
            bool cached = false;
            exp::Packing p = exp::load_or_generate(curves_[s], spec, base_.cache_dir, &cached);
            std::ostringstream line;
            line << "packing of " << names_[s] << ", seed " << seed << ": "
                 << p.radius.size() << " grains (" << (cached ? "cached" : "generated") << ")";
            const std::lock_guard lock(mutex);
            packings_.emplace(std::make_pair(s, seed), std::move(p));
            if (log) log(line.str());
        });
    }

    void load_prepared(const PackingSeeds& seeds) override {
        for (std::size_t s = 0; s < curves_.size(); ++s)
            for (std::uint64_t seed : seeds.of(s)) {
                if (packings_.count({s, seed})) continue;
                exp::SpecimenSpec spec = base_.specimen;
                spec.seed = seed;
                const std::uint64_t key = exp::packing_key(curves_[s], spec);
                const std::filesystem::path path = spec.paste ? exp::paste_cache_path(curves_[s], spec, base_.cache_dir)
                                                              : exp::packing_cache_path(base_.cache_dir, key);
                std::error_code ec;
                if (!std::filesystem::exists(path, ec))
                    throw std::runtime_error("packing of " + names_[s] + ", seed " + std::to_string(seed) + " not found at " +
                                             std::filesystem::absolute(path).string() +
                                             " (the packing cache folder must be one every rank can read, e.g. on a shared file system)");
                packings_.emplace(std::make_pair(s, seed), spec.paste ? exp::load_or_generate_paste(curves_[s], spec, base_.cache_dir)
                                                                      : exp::load_packing(path, key));
            }
    }

    RunOutcome run(const RunRequest& q, double timeout_s) const override {
        const auto it = packings_.find({q.sand, q.seed});
        if (it == packings_.end()) throw std::logic_error("DemCubeModel::run: packing not prepared");
        const exp::Packing& packing = it->second;
        const bool tension = q.test == CubeTest::tension;
        if (tension && !tension_) throw std::logic_error("DemCubeModel::run: a tension request to a model made without tension");
        const auto start = Clock::now();
        exp::ProgressCallback watchdog;
        if (timeout_s > 0.0)
            watchdog = [start, timeout_s](const exp::CurvePoint&, double) {
                if (std::chrono::duration<double>(Clock::now() - start).count() > timeout_s)
                    throw Timeout("timed out after " + common::format_significant(timeout_s, 6) + " s");
            };
        RunOutcome out;
        try {
            const exp::CubeTestResult r = tension ? run_tension(packing, q.material, watchdog) : run_compression(packing, q.material, watchdog);
            out.particles = static_cast<std::int64_t>(r.particles);
            out.bonds = static_cast<std::int64_t>(r.bonds);
            out.steps = r.test.steps;
            out.modulus_pa = r.macro.chord_modulus_pa;
            out.peak_pa = r.macro.peak_stress_pa;
            out.strain_at_peak = r.macro.strain_at_peak;
            out.poisson = r.macro.poisson_ratio;
            thin_curve(r, out);
            if (r.diverged()) {
                out.status = OutcomeStatus::diverged;
                out.reason = r.test.stop_reason;
            } else if (tension && std::isfinite(out.peak_pa) && out.peak_pa > 0.0) {
                out.status = OutcomeStatus::ok;  // σt is what the tension test is run for; its modulus may be NaN
                if (r.macro.status != lab::ReductionStatus::ok) out.reason = "tension curve partly reduced: " + r.macro.message;
            } else if (r.macro.status != lab::ReductionStatus::ok || !std::isfinite(out.modulus_pa)) {
                out.status = OutcomeStatus::failed;
                out.reason = "curve not reducible: " + r.macro.message;
            } else {
                out.status = OutcomeStatus::ok;
            }
        } catch (const Timeout& e) {
            out.status = OutcomeStatus::timeout;
            out.reason = e.what();
        } catch (const std::exception& e) {
            out.status = OutcomeStatus::failed;
            out.reason = e.what();
        }
        out.wall_seconds = std::chrono::duration<double>(Clock::now() - start).count();
        return out;
    }

    std::string fingerprint() const override { return tension_ ? run_fingerprint(CubeTest::tension) : compression_fingerprint(); }

    std::string run_fingerprint(CubeTest test) const override {
        if (test == CubeTest::compression) return compression_fingerprint();
        if (!tension_) throw std::logic_error("DemCubeModel: no tension test (made without it)");
        std::ostringstream f;
        f << compression_fingerprint() << std::hexfloat << "; direct tension v1 grip " << tension_->spec.grip_depth_fraction
          << " auto peak strain " << tension_->auto_peak_strain << " transits " << tension_->auto_transits;
        return f.str();
    }

private:
    std::string compression_fingerprint() const {
        std::ostringstream f;
        // The engine's version (v2: one time step per step, world_step.cpp); bump whenever the
        // engine's results change on purpose, so the ledger never serves a run of another engine.
        f << "dem cube model v2; genesis v" << exp::kGenesisAlgorithmVersion << "; format v" << exp::kPackingFormatVersion;
        // A bond that replaces its contact counts the larger of the two springs in the time step
        // (core/bond_law.hpp add_pair_time_step_stiffness; before, their sum): such runs changed.
        if (base_.material.bond.bond_replaces_contact()) f << "; replacing bond's step v2";
        // The flat joint's zero line by core/portable_math.hpp's atan2 and acos (before, the C
        // library's, whose bits depend on the processor): its runs changed.
        if (base_.material.bond.model == BondModel::flat_joint) f << "; flat joint's zero line v2";
        for (const auto& curve : curves_) {
            exp::SpecimenSpec spec = base_.specimen;
            spec.seed = 0;  // seeds are part of each run key
            f << "; packing " << std::hex << exp::packing_key(curve, spec) << std::dec;
            if (spec.paste)  // explicit paste: the paste specimen and the bond families
                f << "; paste " << std::hex << exp::paste_packing_key(exp::packing_key(curve, spec), *spec.paste) << std::dec
                  << " itz " << std::hexfloat << base_.material.families.itz_strength_factor << " "
                  << base_.material.families.itz_modulus_factor << std::defaultfloat << " sand-sand "
                  << (base_.material.families.sand_sand_bonded ? "bonded" : "frictional");
        }
        const exp::PlatenTestSpec& l = base_.test.loading;
        f << "; rate " << (base_.auto_strain_rate ? std::string("auto") : std::to_string(l.strain_rate)) << std::hexfloat
          << "; ramp " << l.ramp_strain << "; stop " << l.stop_fraction << "; max " << l.max_strain << "; record "
          << l.record_interval << "; gauge " << base_.test.gauge_length_fraction << " " << base_.test.slab_fraction << " "
          << base_.test.core_fraction << "; settle " << base_.test.settle_ratio << " " << base_.test.max_settle_steps;
        if (l.stop_strain_ratio > 0.0) f << "; stop strain " << l.stop_strain_ratio;  // absent when off: earlier keys hold
        return f.str();
    }

    exp::CubeTestResult run_compression(const exp::Packing& packing, const exp::MaterialParams& material,
                                        const exp::ProgressCallback& watchdog) const {
        exp::CubeTestSpec spec = base_.test;
        spec.snapshot = {};
        spec.loading.platen_friction = material.platen_friction;
        spec.loading.strain_rate = base_.auto_strain_rate ? exp::quasi_static_strain_rate(packing, material)
                                                          : base_.test.loading.strain_rate;
        return exp::run_cube_test(packing, material, spec, watchdog);
    }

    /// The tension test's result (its `cube` part: the grips' facts are not kept).
    exp::CubeTestResult run_tension(const exp::Packing& packing, const exp::MaterialParams& material,
                                    const exp::ProgressCallback& watchdog) const {
        exp::CubeConfig config = base_;
        config.material = material;
        exp::TensionTestSpec spec = tension_->spec;
        spec.test.snapshot = {};
        spec.test.loading.platen_friction = material.platen_friction;
        spec.test.loading.strain_rate = exp::tension_strain_rate(config, *tension_, packing);
        return exp::run_tension_test(packing, material, spec, watchdog).cube;
    }

    exp::CubeConfig base_;
    std::optional<exp::TensionConfig> tension_;  ///< set: the model runs the direct-tension test
    std::vector<std::string> names_;
    std::vector<lab::GradationCurve> curves_;
    std::map<std::pair<std::size_t, std::uint64_t>, exp::Packing> packings_;
};

}  // namespace

std::unique_ptr<CubeModel> make_dem_model(const exp::CubeConfig& base, const std::vector<std::string>& sands, bool tension) {
    return std::make_unique<DemCubeModel>(base, sands, tension);
}

}  // namespace gradem::cal
