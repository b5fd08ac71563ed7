#include "calibrate/plan.hpp"

#include <omp.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <optional>
#include <sstream>
#include <thread>

#include <nlohmann/json.hpp>

#include "calibrate/calibration.hpp"
#include "calibrate/parameters.hpp"
#include "common/clock_text.hpp"
#include "common/number_format.hpp"
#include "core/world.hpp"
#include "experiments/virtual_tests/cube_specimen.hpp"
#include "experiments/specimen/grain_sampler.hpp"
#include "experiments/specimen/packing_cache.hpp"
#include "experiments/paste/paste_cache.hpp"
#include "experiments/config/tension_config.hpp"

namespace gradem::cal {
namespace {

using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point t) { return std::chrono::duration<double>(Clock::now() - t).count(); }

std::vector<PlannedSpecimens> specimen_sets(const CalibrationProblem& problem) {
    std::vector<PlannedSpecimens> sets{{"fit", problem.base, problem.packing_seeds()}};
    if (problem.scale_up.enabled()) sets.push_back({"scale-up", scale_up_problem(problem).base, problem.scale_up.seeds});
    if (problem.validation.enabled()) {
        const CalibrationProblem v = validation_problem(problem);
        sets.push_back({"validation", v.base, problem.validation.seeds});
    }
    return sets;
}

/// The cached packing of (curve, spec), if genesis has made it.
std::optional<exp::Packing> cached_packing(const lab::GradationCurve& curve, const exp::SpecimenSpec& spec,
                                           const std::filesystem::path& cache_dir) {
    const std::uint64_t key = exp::packing_key(curve, spec);
    const std::filesystem::path path =
        spec.paste ? exp::paste_cache_path(curve, spec, cache_dir) : exp::packing_cache_path(cache_dir, key);
    std::error_code ec;
    if (!std::filesystem::exists(path, ec)) return std::nullopt;
    return spec.paste ? exp::load_or_generate_paste(curve, spec, cache_dir) : exp::load_packing(path, key);
}

/// The packing of (curve, spec) made by genesis and cached, for the engine timing of a set none
/// of whose packings is cached: the run then reads it from the cache. Genesis on every core, as
/// the run's preparation makes it (the same bits for any thread count); its wall time [s] into
/// `seconds`.
exp::Packing make_packing(const lab::GradationCurve& curve, const exp::SpecimenSpec& spec,
                          const std::filesystem::path& cache_dir, double& seconds) {
    const auto start = Clock::now();
    const int threads = omp_get_max_threads();
    omp_set_num_threads(omp_get_num_procs());
    exp::Packing p = spec.paste ? exp::load_or_generate_paste(curve, spec, cache_dir) : exp::load_or_generate(curve, spec, cache_dir);
    omp_set_num_threads(threads);
    seconds = seconds_since(start);
    return p;
}

/// What the engine timing measured on one specimen.
struct Probe {
    double seconds_per_particle_step = 0.0, time_step = 0.0, settle_steps = 0.0;
};

/// Bonds `packing` with `material` between the platens and cycles it, as a run settles it, for
/// about `seconds` on one thread: the cost per particle-step is the median of its 100-step
/// batches (a batch the machine interrupted, or the first one's set-up, does not move it). The
/// settling steps are where the unbalanced-force ratio fell under the test's; beyond the probe
/// they are extrapolated from its decay (log-linear in steps), at most the settling budget.
Probe probe_engine(const exp::Packing& packing, const exp::MaterialParams& material, const exp::CubeTestSpec& test,
                   double seconds) {
    constexpr int kBatch = 100;
    omp_set_num_threads(1);
    World world = exp::bonded_cube_specimen(packing, material);
    Probe probe;
    probe.time_step = world.time_step();
    const auto start = Clock::now();
    std::vector<double> batch_seconds;
    std::int64_t steps = 0, settled_at = 0;
    double first_ratio = 0.0, ratio = 1.0;
    while (seconds_since(start) < seconds && steps < test.max_settle_steps) {
        const auto t = Clock::now();
        world.run(kBatch);
        batch_seconds.push_back(seconds_since(t));
        steps += kBatch;
        if (settled_at > 0) continue;  // settled: timing only
        ratio = world.unbalanced_force_ratio();
        if (steps == kBatch) first_ratio = ratio;
        if (ratio < test.settle_ratio) settled_at = steps;
    }
    std::nth_element(batch_seconds.begin(), batch_seconds.begin() + batch_seconds.size() / 2, batch_seconds.end());
    probe.seconds_per_particle_step = batch_seconds[batch_seconds.size() / 2] / (kBatch * static_cast<double>(packing.radius.size()));
    probe.settle_steps = static_cast<double>(settled_at > 0 ? settled_at : steps);
    if (settled_at > 0 || steps >= test.max_settle_steps) return probe;
    const double decay = (std::log(first_ratio) - std::log(ratio)) / static_cast<double>(steps - kBatch);
    const double more = decay > 0.0 ? (std::log(ratio) - std::log(test.settle_ratio)) / decay : static_cast<double>(test.max_settle_steps);
    probe.settle_steps = std::min(static_cast<double>(test.max_settle_steps), steps + more);
    return probe;
}

/// Loading steps of a platen test from 0 to `end_strain` at `rate` [1/s] with time step `dt`;
/// the half-cosine ramp over the first ramp_strain moves at half the speed on average.
double loading_steps(double end_strain, double ramp_strain, double rate, double dt) {
    return (end_strain + 0.5 * std::min(ramp_strain, end_strain)) / (rate * dt);
}

/// The platen strains at which a compression run of this sand is expected to peak and to end
/// when it stops at `stop` (plan.hpp, step 4): its stress down to stop_fraction of its peak, or,
/// with a stop_strain_ratio, its strain at most that × the strain at the peak (a ratio of gauge
/// strains, taken as one of platen strains).
struct CompressionStrains {
    double peak = 0.0, end = 0.0;
};
CompressionStrains compression_strains(const std::optional<PlatenTestCost>& cost, const SandTargets& lab, const exp::PlatenTestSpec& stop) {
    const double elastic = lab.peak.mean / lab.modulus.mean;
    const double peak = cost ? cost->compression_peak_over_elastic * elastic : lab.strain.mean;
    const double end = cost ? cost->compression_end_over_elastic * elastic : kEndOverPeakStrain * lab.strain.mean;
    const double tail = (1.0 - stop.stop_fraction) / (1.0 - PlatenTestCost::kMeasuredStopFraction);
    const double stopped = peak + (end - peak) * tail;
    return {peak, stop.stop_strain_ratio > 0.0 ? std::min(stopped, stop.stop_strain_ratio * peak) : stopped};
}

/// The runs of each sand on a set, from the stand-in's path: the fitted runs spread over the
/// sands the mode fits (study mode: all but the prediction on `calibrate_on`).
int fitted_runs_of(const CalibrationProblem& problem, const ExpectedRuns& e, std::size_t sand) {
    const int own = static_cast<int>(problem.seeds_of(sand).size());
    if (problem.mode != Mode::study) return e.fitted * own / std::max(1, problem.runs_per_test());
    if (problem.sands[sand] != problem.calibrate_on) return own;
    const int prediction = problem.runs_per_test() - own;
    return std::max(0, e.fitted - prediction);
}

/// The runs of sand s on a calibration's set, from the stand-in's path.
RunCostPlan plan_sand(const CalibrationProblem& problem, const PlannedSpecimens& set, std::size_t s, const ExpectedRuns& e,
                      const exp::MaterialParams& start, double probe_seconds, std::vector<SpecimenPlan>& specimens) {
    const int sands = static_cast<int>(problem.sands.size());
    int per_set = set.name == "fit" ? fitted_runs_of(problem, e, s) : set.name == "scale-up" ? e.scale_up / sands : e.validation / sands;
    // the companions of every compression run, or the result's alone (problem.hpp), or those of
    // the validation's tension seeds
    int tension = 0;
    if (!problem.tension.fitted()) {
    } else if (set.name == "fit" && problem.tension_at_result_only()) {
        // the path's runs but the result's tension tests are compression runs, spread by seeds
        ExpectedRuns compression = e;
        compression.fitted = std::max(0, e.fitted - problem.tension_runs_per_test());
        tension = static_cast<int>(problem.tension_seeds_of(s).size());
        per_set = fitted_runs_of(problem, compression, s) + tension;
    } else if (set.name == "validation") {
        tension = std::min(per_set, static_cast<int>(problem.validation.seeds_with_tension().size()));
    } else if (set.name == "fit") {  // every evaluation: a compression run per seed, a tension run per tension seed
        const auto seeds = static_cast<int>(problem.seeds_of(s).size()), with = static_cast<int>(problem.tension_seeds_of(s).size());
        tension = per_set * with / std::max(1, seeds + with);
    } else {
        tension = per_set / 2;
    }
    return plan_runs(problem, set, s, start, {per_set - tension, tension}, probe_seconds, specimens);
}

}  // namespace

RunCostPlan plan_runs(const CalibrationProblem& problem, const PlannedSpecimens& set, std::size_t s,
                      const exp::MaterialParams& material, RunCounts counts, double probe_seconds,
                      std::vector<SpecimenPlan>& specimens) {
    exp::CubeConfig config = set.base;
    config.sand = problem.sands[s];
    config.material = material;
    const lab::GradationCurve curve = exp::load_gradation(config);
    RunCostPlan cost{.sand = problem.sands[s], .set = set.name};
    std::optional<exp::Packing> timed;
    const std::vector<std::uint64_t>& seeds = set.seeds.of(s);
    const std::size_t first = specimens.size();
    auto spec_of = [&](std::uint64_t seed) {
        exp::SpecimenSpec spec = config.specimen;
        spec.seed = seed;
        return spec;
    };
    for (std::uint64_t seed : seeds) {
        const exp::SpecimenSpec spec = spec_of(seed);
        SpecimenPlan sp{.sand = cost.sand, .set = set.name, .seed = seed, .packing_key = exp::packing_key(curve, spec)};
        if (auto p = cached_packing(curve, spec, config.cache_dir)) {
            sp.cached = true;
            sp.particles = static_cast<std::int64_t>(p->radius.size());
            if (!timed) timed = std::move(p);
        } else {
            const double edge = spec.genesis.edge;
            const exp::GrainSample grains =
                exp::sample_grains(curve, spec.size_rule, spec.genesis.target_solid_fraction * edge * edge * edge, seed);
            sp.particles = static_cast<std::int64_t>(grains.diameters.size());
            sp.genesis_max_steps = spec.genesis.max_steps;
        }
        specimens.push_back(sp);
    }
    if (!timed) {  // none of the set's packings is cached: its first seed's made now, for the timing
        SpecimenPlan& sp = specimens[first];
        timed = make_packing(curve, spec_of(sp.seed), config.cache_dir, sp.genesis_s);
        sp.cached = true;
        sp.genesis_max_steps = 0;
        sp.particles = static_cast<std::int64_t>(timed->radius.size());
    }
    for (std::size_t k = first; k < specimens.size(); ++k)
        cost.particles += static_cast<double>(specimens[k].particles) / static_cast<double>(seeds.size());
    const Probe probe = probe_engine(*timed, material, config.test, probe_seconds);
    cost.time_step_s = probe.time_step;
    cost.seconds_per_particle_step = probe.seconds_per_particle_step;
    cost.settle_steps = probe.settle_steps;
    const exp::PlatenTestSpec& l = config.test.loading;
    const double rate = config.auto_strain_rate ? exp::quasi_static_strain_rate(*timed, material) : l.strain_rate;
    const std::optional<PlatenTestCost> row = platen_test_cost(problem.bond_model());
    const CompressionStrains strain = compression_strains(row, problem.targets[s], l);
    const double to_peak = loading_steps(strain.peak, l.ramp_strain, rate, probe.time_step);
    const double loading = loading_steps(strain.end, l.ramp_strain, rate, probe.time_step);
    cost.compression_steps = probe.settle_steps + loading;
    // The run's mean cost factor: settling as probed, then the law's before and after the peak.
    const PlatenTestCost factors = row.value_or(PlatenTestCost{});
    cost.compression_cost_factor = (probe.settle_steps + factors.pre_peak_cost_factor * to_peak +
                                    factors.post_peak_cost_factor * (loading - to_peak)) / cost.compression_steps;
    cost.tension_cost_factor = factors.tension_cost_factor;
    cost.compression_runs = counts.compression;
    if (counts.tension > 0) {
        const exp::TensionConfig tension = exp::load_tension_config(config);
        const double expected = tension.auto_peak_strain > 0.0 ? tension.auto_peak_strain : exp::expected_tensile_peak_strain(material);
        const double t_rate = exp::tension_strain_rate(config, tension, *timed);
        cost.tension_steps = probe.settle_steps + loading_steps(factors.tension_end_over_expected * expected, l.ramp_strain, t_rate, probe.time_step);
        cost.tension_runs = counts.tension;
    }
    return cost;
}

namespace {

/// Genesis' wall time per grain [s] measured on the packing the plan made for this sand and set,
/// or 0 when it made none (the set's timing ran on a cached packing).
double measured_genesis_per_grain(const PlanCost& cost, const SpecimenPlan& of) {
    for (const SpecimenPlan& sp : cost.specimens)
        if (sp.sand == of.sand && sp.set == of.set && sp.genesis_s > 0.0 && sp.particles > 0)
            return sp.genesis_s / static_cast<double>(sp.particles);
    return 0.0;
}

}  // namespace

void add_totals(PlanCost& cost) {
    const int parallel = std::max(1, std::min(cost.workers, cost.cores));
    double wall = 0.0, steps = 0.0, bound = 0.0, estimate = 0.0;
    for (const RunCostPlan& r : cost.runs) {
        wall += r.seconds();
        steps += r.particles * (r.compression_runs * r.compression_steps + r.tension_runs * r.tension_steps);
    }
    std::vector<std::uint64_t> made;
    for (const SpecimenPlan& sp : cost.specimens) {
        if (sp.cached || std::find(made.begin(), made.end(), sp.packing_key) != made.end()) continue;
        made.push_back(sp.packing_key);
        if (const double per_grain = measured_genesis_per_grain(cost, sp); per_grain > 0.0) {
            estimate += per_grain * static_cast<double>(sp.particles);
            continue;
        }
        for (const RunCostPlan& r : cost.runs)
            if (r.sand == sp.sand && r.set == sp.set) {
                bound += static_cast<double>(sp.particles) * static_cast<double>(sp.genesis_max_steps) * r.seconds_per_particle_step;
                break;
            }
    }
    cost.run_particle_steps = steps;
    cost.run_wall_s = wall / parallel;
    cost.genesis_wall_s = estimate;
    cost.genesis_wall_max_s = bound / parallel;
}

double RunCostPlan::seconds() const {
    return particles * seconds_per_particle_step *
           (compression_cost_factor * compression_runs * compression_steps + tension_cost_factor * tension_runs * tension_steps);
}

std::string test_cost_assumption(BondModel model) {
    std::ostringstream o;
    if (const auto cost = platen_test_cost(model))
        o << "a compression run peaks at a platen strain of " << cost->compression_peak_over_elastic << " x sigma_lab/E_lab and ends at "
          << cost->compression_end_over_elastic << " x when it stops at " << PlatenTestCost::kMeasuredStopFraction
          << " x its peak (the tail after the peak in proportion to 1 - stop_fraction), and costs " << cost->pre_peak_cost_factor
          << " x per particle-step what the engine timing measured up to its peak, " << cost->post_peak_cost_factor << " x after it, a tension run "
          << cost->tension_cost_factor << " x (the " << to_string(model) << "'s PlatenTestCost)";
    else
        o << "a compression run ends at " << kEndOverPeakStrain << " x the lab's strain at peak and costs per particle-step what the engine timing measured (the "
          << to_string(model) << " has no PlatenTestCost)";
    return o.str();
}

namespace {

/// A set's cube edge over the fitted one (a set's edge 0: the fit's) [-].
double edge_ratio(const CalibrationProblem& problem, double edge) {
    const double fitted_edge = problem.base.specimen.genesis.edge;
    return edge > 0.0 && fitted_edge > 0.0 ? edge / fitted_edge : 1.0;
}

}  // namespace

double run_weight_at_edge(const CalibrationProblem& problem, double edge) {
    // (L/L_f)³ the grains; at the automatic rate L/L_f the steps (a fixed number of wave transits).
    const double ratio = edge_ratio(problem, edge);
    return std::pow(ratio, 3) * (problem.base.auto_strain_rate ? ratio : 1.0);
}

ExpectedRuns expected_runs(const CalibrationProblem& problem) {
    CalibrationProblem dry = problem;
    dry.model = RunModel::analytic;
    dry.ledger = ":memory:";
    dry.workers = 1;
    const auto model = make_model(dry);
    const CalibrationResult r = run_calibration(dry, *model);
    ExpectedRuns e;
    e.fitted = r.runs_used;
    e.evaluations = static_cast<int>(r.history.size());
    e.validation = r.validation_runs;
    e.scale_up = r.scale_up_runs;
    const double validation = edge_ratio(problem, problem.validation.edge);
    e.validation_grains_ratio = std::pow(validation, 3);
    e.validation_steps_ratio = problem.base.auto_strain_rate ? validation : 1.0;
    e.validation_run_weight = run_weight_at_edge(problem, problem.validation.edge);
    e.scale_up_run_weight = run_weight_at_edge(problem, problem.scale_up.edge);
    const bool tension = problem.tension.fitted();
    const double per_test = problem.runs_per_test() + (tension ? problem.tension_runs_per_test() : 0);
    for (std::size_t s = 0; s < problem.sands.size(); ++s) {
        const double own = problem.runs_per_test({s}) + (tension ? problem.tension_runs_per_test({s}) : 0);
        e.fitted_share.push_back(own / per_test);
        e.validation_share.push_back(1.0 / static_cast<double>(problem.sands.size()));
    }
    return e;
}

namespace {

/// Σ over sands of share × the sand's mean run time so far (the mean of all runs where a sand
/// has none yet); the mean of all runs without shares.
double mean_run_seconds(const Progress& p, const std::vector<double>& shares) {
    if (shares.empty()) return p.mean_run_s;
    double sum = 0.0;
    for (std::size_t s = 0; s < shares.size(); ++s) {
        const bool timed = s < p.sand_mean_run_s.size() && p.sand_mean_run_s[s] > 0.0;
        sum += shares[s] * (timed ? p.sand_mean_run_s[s] : p.mean_run_s);
    }
    return sum;
}

}  // namespace

double eta_seconds(const Progress& p, const ExpectedRuns& e, bool upper) {
    if (p.mean_run_s <= 0.0) return std::nan("");
    const int path_left = std::max(0, std::min(p.max_runs, std::max(e.fitted, p.runs_used)) - p.runs_used);
    const int fitted_left = upper ? p.max_runs - p.runs_used : path_left;
    // the scale-up and validation sets run every sand alike
    const double seconds = fitted_left * mean_run_seconds(p, e.fitted_share) +
                           (e.scale_up * e.scale_up_run_weight + e.validation * e.validation_run_weight) *
                               mean_run_seconds(p, e.validation_share);
    return seconds / std::max(1, p.workers);
}

CalibrationPlan plan_calibration(const CalibrationProblem& problem, double probe_seconds) {
    CalibrationPlan plan;
    plan.budget = problem.solver.max_runs;
    plan.tension = problem.tension.fitted();
    plan.tension_at_result = problem.tension_at_result_only();
    plan.workers = problem.workers;
    plan.cores = static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
    const ExpectedRuns e = expected_runs(problem);
    plan.expected_runs = e.fitted;
    plan.expected_evaluations = e.evaluations;
    plan.validation_runs = e.validation;
    plan.scale_up_runs = e.scale_up;
    if (problem.model == RunModel::analytic) {
        plan.assumptions.push_back("model = \"analytic\": the stand-in runs in milliseconds; nothing to estimate");
        return plan;
    }
    const ParameterSpace space(problem.parameters, problem.base.material);
    const exp::MaterialParams start = space.material(space.start());
    for (const PlannedSpecimens& set : specimen_sets(problem))
        for (std::size_t s = 0; s < problem.sands.size(); ++s)
            plan.runs.push_back(plan_sand(problem, set, s, e, start, probe_seconds, plan.specimens));
    add_totals(plan);
    std::ostringstream a;
    a << "the runs follow the solver's path on the analytic stand-in (" << e.fitted << " of the budget's " << plan.budget
      << "); a DEM path may stop earlier or use the whole budget";
    plan.assumptions.push_back(a.str());
    plan.assumptions.push_back(test_cost_assumption(problem.bond_model()) + "; every run costs what the start point costs");
    if (const double ratio = problem.base.test.loading.stop_strain_ratio; ratio > 0.0)
        plan.assumptions.push_back("a compression run ends by " + common::format_significant(ratio, 3) +
                                   " x its expected strain at peak (stop_strain_ratio); a tension run as without it");
    return plan;
}

std::string cost_text(const PlanCost& cost) {
    std::ostringstream o;
    for (const SpecimenPlan& s : cost.specimens)
        o << "specimen " << s.sand << " (" << s.set << "), seed " << s.seed << ": " << s.particles << " grains"
          << (s.genesis_s > 0.0 ? " (made now for the engine timing: genesis " + common::clock_text(s.genesis_s) + ", cached for the run)"
              : s.cached      ? " (cached)"
                              : " (genesis first, at most " + std::to_string(s.genesis_max_steps) + " steps)")
          << "\n";
    for (const RunCostPlan& r : cost.runs) {
        o << "run " << r.sand << " (" << r.set << "): " << r.compression_runs << " compression x "
          << static_cast<long long>(std::llround(r.compression_steps)) << " steps";
        if (r.tension_runs) o << ", " << r.tension_runs << " tension x " << static_cast<long long>(std::llround(r.tension_steps)) << " steps";
        o << "; time step " << r.time_step_s << " s, " << r.seconds_per_particle_step * 1e9 << " ns per particle-step\n";
    }
    o << "particle-steps: " << cost.run_particle_steps << "\n";
    o << "estimated wall time: " << common::clock_text(cost.run_wall_s) << " on " << std::min(cost.workers, cost.cores) << " of "
      << cost.workers << " workers (" << cost.cores << " cores)";
    if (cost.genesis_wall_s > 0.0) o << ", plus genesis about " << common::clock_text(cost.genesis_wall_s);
    if (cost.genesis_wall_max_s > 0.0) o << ", plus genesis at most " << common::clock_text(cost.genesis_wall_max_s);
    o << "\n";
    for (const std::string& a : cost.assumptions) o << "assumed: " << a << "\n";
    return o.str();
}

void add_cost_json(nlohmann::ordered_json& j, const PlanCost& cost) {
    j["workers"] = cost.workers;
    j["cores"] = cost.cores;
    j["particle_steps"] = cost.run_particle_steps;
    j["wall_s"] = cost.run_wall_s;
    j["genesis_wall_s"] = cost.genesis_wall_s;
    j["genesis_wall_max_s"] = cost.genesis_wall_max_s;
    j["specimens"] = nlohmann::ordered_json::array();
    j["runs"] = nlohmann::ordered_json::array();
    for (const SpecimenPlan& s : cost.specimens)
        j["specimens"].push_back({{"sand", s.sand}, {"set", s.set}, {"seed", s.seed}, {"particles", s.particles},
                                  {"cached", s.cached}, {"genesis_max_steps", s.genesis_max_steps}, {"genesis_s", s.genesis_s}});
    for (const RunCostPlan& r : cost.runs)
        j["runs"].push_back({{"sand", r.sand},
                             {"set", r.set},
                             {"particles", r.particles},
                             {"time_step_s", r.time_step_s},
                             {"seconds_per_particle_step", r.seconds_per_particle_step},
                             {"compression_cost_factor", r.compression_cost_factor},
                             {"tension_cost_factor", r.tension_cost_factor},
                             {"settle_steps", r.settle_steps},
                             {"compression_runs", r.compression_runs},
                             {"compression_steps", r.compression_steps},
                             {"tension_runs", r.tension_runs},
                             {"tension_steps", r.tension_steps}});
    j["assumptions"] = cost.assumptions;
}

std::string plan_text(const CalibrationPlan& plan) {
    std::ostringstream o;
    o << "runs: " << plan.expected_runs << " expected of a budget of " << plan.budget << " (" << plan.expected_evaluations
      << " evaluations" << (!plan.tension ? "" : plan.tension_at_result ? ", the tension tests at the result" : ", each compression run with its tension test") << ")";
    if (plan.scale_up_runs) o << ", then " << plan.scale_up_runs << " scale-up runs";
    if (plan.validation_runs) o << ", then " << plan.validation_runs << " validation runs";
    o << "\n" << cost_text(plan);
    return o.str();
}

std::string plan_json(const CalibrationPlan& plan) {
    nlohmann::ordered_json j{{"budget", plan.budget},
                             {"expected_runs", plan.expected_runs},
                             {"expected_evaluations", plan.expected_evaluations},
                             {"scale_up_runs", plan.scale_up_runs},
                             {"validation_runs", plan.validation_runs},
                             {"tension", plan.tension},
                             {"tension_at_result_only", plan.tension_at_result}};
    add_cost_json(j, plan);
    return j.dump(2);
}

}  // namespace gradem::cal
