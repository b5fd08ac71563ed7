#include "calibrate/evaluator.hpp"

#include <algorithm>
#include <cmath>
#include <nlohmann/json.hpp>

#include "common/hash.hpp"

namespace gradem::cal {
namespace {

/// Seed mean and sample standard deviation of q over the runs (NaN: none, or one for the std).
void mean_and_std(const std::vector<const RunOutcome*>& runs, Quantity q, double& mean, double& std) {
    const double n = static_cast<double>(runs.size());
    double sum = 0.0, sq = 0.0;
    for (const RunOutcome* r : runs) sum += outcome_value(*r, q);
    mean = n > 0 ? sum / n : std::nan("");
    for (const RunOutcome* r : runs) sq += (outcome_value(*r, q) - mean) * (outcome_value(*r, q) - mean);
    std = n > 1 ? std::sqrt(sq / (n - 1.0)) : std::nan("");
}

/// The primary test, then the tension companion when a compression calibration fits tension.
std::vector<CubeTest> tests_of(const CalibrationProblem& problem, CubeTest primary) {
    if (primary == CubeTest::compression && problem.tension.fitted()) return {CubeTest::compression, CubeTest::tension};
    return {primary};
}

}  // namespace

double outcome_value(const RunOutcome& r, Quantity q) {
    return q == Quantity::modulus ? r.modulus_pa : q == Quantity::peak || q == Quantity::tension ? r.peak_pa : r.strain_at_peak;
}

Evaluator::Evaluator(const CalibrationProblem& problem, const ParameterSpace& space, RunExecutor& executor, Ledger& ledger,
                     const CubeModel& model, std::function<void(const Progress&)> progress, CubeTest primary)
    : problem_(problem), space_(space), executor_(executor), ledger_(ledger), primary_(primary),
      tests_(tests_of(problem, primary)), progress_(std::move(progress)), start_(std::chrono::steady_clock::now()) {
    for (CubeTest t : tests()) fingerprint_[static_cast<int>(t)] = model.run_fingerprint(t);
}

Evaluator::Evaluator(const CalibrationProblem& problem, const ParameterSpace& space, const CubeModel& model, Ledger& ledger,
                     std::function<void(const Progress&)> progress, CubeTest primary)
    : problem_(problem), space_(space), own_executor_(std::make_unique<ThreadExecutor>(model, problem.workers)),
      executor_(*own_executor_), ledger_(ledger), primary_(primary),
      tests_(tests_of(problem, primary)), progress_(std::move(progress)), start_(std::chrono::steady_clock::now()) {
    for (CubeTest t : tests()) fingerprint_[static_cast<int>(t)] = model.run_fingerprint(t);
}


bool Evaluator::runs_test(CubeTest test, std::uint64_t seed) const {
    return test == primary_ || problem_.runs_tension_on(seed);
}

void Evaluator::set_tension_companion(bool on) {
    tests_ = on ? tests_of(problem_, primary_) : std::vector<CubeTest>{primary_};
}

double Evaluator::seconds() const {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
}

std::string Evaluator::run_key(const exp::MaterialParams& m, std::size_t sand, std::uint64_t seed, CubeTest test) const {
    return common::fnv1a_hex(fingerprint_[static_cast<int>(test)] + "|sand " + problem_.sands[sand] + "|seed " + std::to_string(seed) +
                             "|" + material_key(m));
}

std::string Evaluator::parameters_json(const std::vector<double>& values) const {
    nlohmann::json j;
    for (std::size_t k = 0; k < values.size(); ++k) j[space_.free(k).name] = values[k];
    return j.dump();
}

int Evaluator::runs_needed(const std::vector<std::vector<double>>& points, const std::vector<std::size_t>& sands) const {
    std::set<std::string> fresh;
    for (const auto& p : points) {
        const exp::MaterialParams m = space_.material(p);
        for (std::size_t s : sands)
            for (std::uint64_t seed : problem_.seeds_of(s))
                for (CubeTest t : tests())
                    if (runs_test(t, seed))
                        if (const std::string key = run_key(m, s, seed, t); !used_.count(key)) fresh.insert(key);
    }
    return static_cast<int>(fresh.size());
}

SandOutcome Evaluator::summarise(std::size_t sand, const std::vector<RunOutcome>& runs,
                                 const std::vector<RunOutcome>& tension_runs) const {
    SandOutcome s;
    s.sand = sand;
    std::vector<const RunOutcome*> good, good_tension;
    for (const auto& [list, into] : {std::pair{&runs, &good}, std::pair{&tension_runs, &good_tension}})
        for (const RunOutcome& r : *list) {
            if (r.ok()) into->push_back(&r);
            else if (s.failed++ == 0)
                s.failure = std::string(list == &tension_runs ? "tension test " : "") + to_string(r.status) + ": " + r.reason;
        }
    s.ok = static_cast<int>(good.size());
    s.tension_ok = static_cast<int>(good_tension.size());
    for (Quantity q : kQuantities) mean_and_std(good, q, s.mean[static_cast<int>(q)], s.std[static_cast<int>(q)]);
    const int t = static_cast<int>(Quantity::tension);
    mean_and_std(good_tension, Quantity::tension, s.mean[t], s.std[t]);
    double nu = 0.0;
    int n_nu = 0;
    for (const RunOutcome* r : good)
        if (std::isfinite(r->poisson)) nu += r->poisson, ++n_nu;
    s.poisson = n_nu ? nu / n_nu : std::nan("");
    return s;
}

std::optional<RunOutcome> Evaluator::served_outcome(const std::string& key) const {
    std::optional<RunOutcome> found = ledger_.find(key);
    // A run that timed out under a shorter limit than today's runs again (and replaces its
    // row): it would not time out now. One that ran as long as today's limit is served.
    if (found && found->status == OutcomeStatus::timeout && found->wall_seconds < problem_.timeout_s) return std::nullopt;
    return found;
}

std::vector<Evaluator::Job> Evaluator::jobs_of(const std::vector<std::vector<double>>& points,
                                               const std::vector<std::size_t>& sands) const {
    std::vector<Job> jobs;
    for (std::size_t p = 0; p < points.size(); ++p) {
        const exp::MaterialParams m = space_.material(points[p]);
        for (std::size_t s : sands)
            for (std::uint64_t seed : problem_.seeds_of(s))
                for (CubeTest t : tests())
                    if (runs_test(t, seed)) jobs.push_back({p, s, seed, t, m, run_key(m, s, seed, t), {}, false});
    }
    return jobs;
}

/// The jobs the ledger serves are done; the others are queued, each distinct key once.
std::vector<std::size_t> Evaluator::serve_from_ledger(std::vector<Job>& jobs) {
    std::vector<std::size_t> queue;
    std::set<std::string> queued;
    for (std::size_t j = 0; j < jobs.size(); ++j) {
        if (auto found = served_outcome(jobs[j].key)) {
            jobs[j].outcome = *found;
            jobs[j].done = true;
            if (used_.insert(jobs[j].key).second) {
                ++served_;
                cost_.add_served(*found);
            }
        } else if (queued.insert(jobs[j].key).second) {
            queue.push_back(j);
        }
    }
    return queue;
}

std::vector<RunRequest> Evaluator::queue(const std::vector<std::vector<double>>& points,
                                         const std::vector<std::size_t>& sands, const std::string& label) {
    if (pending_) throw std::logic_error("Evaluator::queue: the last queue was not collected");
    const int needed = runs_needed(points, sands);
    if (needed > runs_remaining())
        throw BudgetExhausted("budget: " + std::to_string(needed) + " more runs needed, " + std::to_string(runs_remaining()) +
                              " of solver.max_runs = " + std::to_string(problem_.solver.max_runs) + " left");
    Pending p{points, sands, label, jobs_of(points, sands), {}};
    p.queue = serve_from_ledger(p.jobs);
    std::vector<RunRequest> requests;
    for (std::size_t j : p.queue) requests.push_back({p.jobs[j].sand, p.jobs[j].seed, p.jobs[j].material, p.jobs[j].test});
    pending_ = std::move(p);
    return requests;
}

/// The k-th queued run ended: its outcome into its job and the ledger at once (the executor
/// calls back one run at a time), and the progress line.
void Evaluator::record(std::size_t k, const RunOutcome& outcome, const RunPlace& place) {
    Pending& p = *pending_;
    Job& job = p.jobs[p.queue[k]];
    job.outcome = outcome;
    ledger_.record(job.key, problem_.sands[job.sand], job.seed, parameters_json(p.points[job.point]), material_key(job.material),
                   job.outcome, place);
    job.done = true;
    used_.insert(job.key);
    ++executed_;
    cost_.add_run(job.outcome);
    if (!job.outcome.ok()) ++failed_;
    run_seconds_ += job.outcome.wall_seconds;
    if (sand_runs_.size() <= job.sand) {
        sand_runs_.resize(job.sand + 1, 0);
        sand_run_seconds_.resize(job.sand + 1, 0.0);
    }
    sand_run_seconds_[job.sand] += job.outcome.wall_seconds;
    ++sand_runs_[job.sand];
    report(static_cast<int>(history_.size() + p.points.size()));
}

/// The duplicates of a queued run inside the batch take its outcome; then each point's evaluation.
std::vector<Evaluation> Evaluator::collect() {
    Pending p = std::move(*pending_);
    pending_.reset();
    for (Job& job : p.jobs)
        if (!job.done)
            for (const Job& other : p.jobs)
                if (other.done && other.key == job.key) job.outcome = other.outcome, job.done = true;
    std::vector<Evaluation> out;
    for (std::size_t i = 0; i < p.points.size(); ++i) {
        history_.push_back(evaluation_of(p.jobs, i, p.points[i], p.sands, p.label));
        out.push_back(history_.back());
    }
    if (p.queue.empty()) report(static_cast<int>(history_.size()));  // served from the ledger: no line yet
    return out;
}

/// One point's evaluation: per-sand means over seeds; it fails if any of its runs failed.
Evaluation Evaluator::evaluation_of(const std::vector<Job>& jobs, std::size_t point, const std::vector<double>& values,
                                    const std::vector<std::size_t>& sands, const std::string& label) {
    Evaluation e;
    e.index = static_cast<int>(history_.size()) + 1;
    e.values = values;
    e.label = label;
    for (std::size_t s : sands) {
        std::vector<RunOutcome> runs, tension_runs;
        for (const Job& job : jobs)
            if (job.point == point && job.sand == s) (job.test == primary_ ? runs : tension_runs).push_back(job.outcome);
        e.sands.push_back(summarise(s, runs, tension_runs));
        if (e.sands.back().failed && !e.failed) {
            e.failed = true;
            e.failure = problem_.sands[s] + ": " + e.sands.back().failure;
        }
        e.runs.insert(e.runs.end(), runs.begin(), runs.end());
        e.tension_runs.insert(e.tension_runs.end(), tension_runs.begin(), tension_runs.end());
    }
    e.runs_used = runs_used();
    e.seconds = seconds();
    return e;
}

std::vector<Evaluation> Evaluator::evaluate(const std::vector<std::vector<double>>& points,
                                            const std::vector<std::size_t>& sands, const std::string& label) {
    const std::vector<RunRequest> requests = queue(points, sands, label);
    try {
        executor_.run(requests, problem_.timeout_s,
                      [&](std::size_t k, const RunOutcome& outcome, const RunPlace& place) { record(k, outcome, place); });
    } catch (...) {
        pending_.reset();  // the next evaluation starts afresh (the runs recorded stay in the ledger)
        throw;
    }
    return collect();
}

void run_together(RunExecutor& executor, const std::vector<QueuedRuns>& batches, double timeout_s) {
    struct Owned {
        std::size_t batch, index;
        double expected;
    };
    std::vector<Owned> order;
    for (std::size_t b = 0; b < batches.size(); ++b)
        for (std::size_t k = 0; k < batches[b].requests.size(); ++k)
            order.push_back({b, k, k < batches[b].expected_seconds.size() ? batches[b].expected_seconds[k] : 0.0});
    std::stable_sort(order.begin(), order.end(), [](const Owned& x, const Owned& y) { return x.expected > y.expected; });
    std::vector<RunRequest> all;
    for (const Owned& o : order) {
        all.push_back(batches[o.batch].requests[o.index]);
        all.back().sand += batches[o.batch].sand_offset;
    }
    executor.run(all, timeout_s, [&](std::size_t k, const RunOutcome& outcome, const RunPlace& place) {
        batches[order[k].batch].evaluator->record(order[k].index, outcome, place);
    });
}

double Evaluator::sand_mean_run_seconds(std::size_t sand) const {
    return sand < sand_runs_.size() && sand_runs_[sand] > 0 ? sand_run_seconds_[sand] / sand_runs_[sand] : 0.0;
}

void Evaluator::report(int evaluations) {
    if (!progress_) return;
    Progress p;
    p.runs_used = runs_used();
    p.max_runs = problem_.solver.max_runs;
    p.from_ledger = served_;
    p.evaluations = evaluations;
    p.elapsed_s = seconds();
    p.mean_run_s = executed_ ? run_seconds_ / executed_ : 0.0;
    for (std::size_t s = 0; s < sand_runs_.size(); ++s) p.sand_mean_run_s.push_back(sand_mean_run_seconds(s));
    p.best_objective = best_objective_;
    p.workers = executor_.slots();
    progress_(p);
}

}  // namespace gradem::cal
