// gradem-mpi-bench: the MPI executor's own cost per run (GRADEM_MPI builds), under
//   mpirun -np N gradem-mpi-bench [--runs R] [--curve-points P] [--quiet]
// The runs are the analytic stand-in (microseconds each), so the wall time per run is the
// executor's overhead: encoding, two messages, rank 0's bookkeeping, the polling sleeps.
// Prints the message sizes, the latency of a lone run (a sequential solver step) and the
// time per run of full batches (every worker busy). Figures only: nothing is asserted. --quiet
// prints nothing but errors.
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <string>

#include "calibrate/cube_model.hpp"
#include "calibrate/execution/ledger.hpp"
#include "calibrate/execution/mpi_executor.hpp"
#include "calibrate/execution/run_message.hpp"
#include "bench/bench_args.hpp"
#include "common/exit_status.hpp"
#include "common/hash.hpp"

using namespace gradem;
using Clock = std::chrono::steady_clock;

namespace {

/// The stand-in with a thinned curve of `points` points, like a DEM run's.
class CurveModel final : public cal::CubeModel {
public:
    explicit CurveModel(int points) : inner_(cal::make_analytic_model(2)), points_(points) {}
    void prepare(const cal::PackingSeeds&, int, const std::function<void(const std::string&)>&) override {}
    cal::RunOutcome run(const cal::RunRequest& q, double t) const override {
        cal::RunOutcome o = inner_->run(q, t);
        o.curve_strain.resize(points_, 1e-3);
        o.curve_stress_pa.resize(points_, 1e7);
        return o;
    }
    std::string fingerprint() const override { return inner_->fingerprint(); }
    std::string run_fingerprint(cal::CubeTest t) const override { return inner_->run_fingerprint(t); }

private:
    std::unique_ptr<cal::CubeModel> inner_;
    int points_;
};

double seconds_since(Clock::time_point t0) { return std::chrono::duration<double>(Clock::now() - t0).count(); }

}  // namespace

int main(int argc, char** argv) {
    int runs = 2000, points = 200;
    bool quiet = false;
    const std::string usage = "usage: mpirun -np N gradem-mpi-bench [--runs R] [--curve-points P] [--quiet]\n";
    for (int k = 1; k < argc; k += 2) {
        const std::string o = argv[k];
        if (o == "--help" || o == "-h") {
            std::printf("%s\nThe MPI executor's cost per run: lone round trips and full batches over every worker rank.\n\n"
                        "options:\n"
                        "  --runs R              runs of the full batch (default 2000)\n"
                        "  --curve-points P      points of each result's curve (default 200)\n"
                        "%s"
                        "  -h, --help            show this text\n\n%s",
                        usage.c_str(), bench::quiet_help_line("").c_str(), common::exit_status_text("the benchmark run failed").c_str());
            return common::exit_success;
        }
        if (o == "--quiet") {  // a flag: no value follows
            quiet = true;
            --k;
            continue;
        }
        if (k + 1 >= argc || (o != "--runs" && o != "--curve-points")) {
            std::fprintf(stderr, "gradem-mpi-bench: unknown or incomplete option '%s' (see gradem-mpi-bench --help)\n%s",
                         o.c_str(), usage.c_str());
            return common::exit_bad_usage;
        }
        const long v = std::strtol(argv[k + 1], nullptr, 10);
        if (v < 1 || std::to_string(v) != argv[k + 1]) {
            std::fprintf(stderr, "gradem-mpi-bench: %s: '%s' is not a positive integer (see gradem-mpi-bench --help)\n",
                         o.c_str(), argv[k + 1]);
            return common::exit_bad_usage;
        }
        (o == "--runs" ? runs : points) = static_cast<int>(v);
    }
    try {
        if (quiet) bench::be_quiet(false);
        return cal::mpi::run_job(
            [&](int) { return cal::mpi::JobModel{std::make_unique<CurveModel>(points), 1}; },
            [&](cal::CubeModel& model, cal::mpi::MpiExecutor& executor) {
                executor.prepare({1, 2}, {});
                cal::RunRequest q{0, 1, exp::MaterialParams{}};
                cal::wire::Run request{1, cal::code_version(), common::fnv1a_hex(model.fingerprint()), 600.0, q};
                const std::size_t run_bytes = cal::wire::encode(request).size();
                const std::size_t result_bytes = cal::wire::encode(cal::wire::Result{1, model.run(q, 0.0)}).size();
                auto noop = [](std::size_t, const cal::RunOutcome&, const cal::RunPlace&) {};
                // 1. Lone runs: one request at a time (what a sequential solver step waits for).
                const int lone = std::max(50, runs / 10);
                auto t0 = Clock::now();
                for (int k = 0; k < lone; ++k) executor.run({q}, 600.0, noop);
                const double lone_s = seconds_since(t0) / lone;
                // 2. Full batches: `runs` requests at once over every worker.
                std::vector<cal::RunRequest> batch(static_cast<std::size_t>(runs), q);
                t0 = Clock::now();
                executor.run(batch, 600.0, noop);
                const double batch_s = seconds_since(t0);
                std::printf("gradem-mpi-bench: %s\n", executor.describe().c_str());
                std::printf("  run request   %zu bytes\n  run result    %zu bytes (curve of %d points)\n", run_bytes, result_bytes, points);
                std::printf("  lone run      %.1f us round trip (mean of %d)\n", lone_s * 1e6, lone);
                std::printf("  full batches  %.1f us per run, %d runs on %d workers (%.1f us per run per worker)\n",
                            batch_s / runs * 1e6, runs, executor.slots(), batch_s / runs * executor.slots() * 1e6);
                return 0;
            });
    } catch (const std::exception& e) {
        std::fprintf(stderr, "gradem-mpi-bench: the run failed: %s\n", e.what());
        return common::exit_run_failed;
    }
}
