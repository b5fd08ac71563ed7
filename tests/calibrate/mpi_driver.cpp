// calibrate_mpi_driver: `gradem calibrate` under MPI with faults injected on one rank, for
// the MPI tests (test_calibrate_mpi.cpp launches it with mpirun). Same job as the app
// (cal::mpi::run_job, run_calibration, the same outputs); the options break one worker:
//   --slow-ms M                every run sleeps M ms first (so a job can be killed mid-way)
//   --die-rank R --die-after K rank R's process exits (_exit(3), no MPI_Finalize) at its K+1-th run
//   --hang-rank R --hang-after K  rank R stops answering at its K+1-th run
//   --code-version-rank R V    rank R says it runs gradem V (a mismatched build)
//   --cache-dir-rank R DIR     rank R looks for the packings in DIR (a node without the cache)
//   --max-runs N               overrides [solver] max_runs
#include <unistd.h>

#include <atomic>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <thread>

#include "calibrate/calibration.hpp"
#include "calibrate/execution/mpi_executor.hpp"
#include "reports/calibration_report.hpp"

using namespace gradem;

namespace {

struct Faults {
    int slow_ms = 0, die_rank = -1, die_after = 0, hang_rank = -1, hang_after = 0, version_rank = -1, cache_rank = -1;
    std::string version, cache_dir;
};

class FaultyModel final : public cal::CubeModel {
public:
    FaultyModel(std::unique_ptr<cal::CubeModel> inner, int slow_ms, int die_after, int hang_after)
        : inner_(std::move(inner)), slow_ms_(slow_ms), die_after_(die_after), hang_after_(hang_after) {}
    void prepare(const cal::PackingSeeds& s, int w, const std::function<void(const std::string&)>& l) override {
        inner_->prepare(s, w, l);
    }
    void load_prepared(const cal::PackingSeeds& s) override { inner_->load_prepared(s); }
    cal::RunOutcome run(const cal::RunRequest& q, double t) const override {
        const int n = ++runs_;
        if (die_after_ > 0 && n > die_after_) _exit(3);
        if (hang_after_ > 0 && n > hang_after_) std::this_thread::sleep_for(std::chrono::hours(1));
        if (slow_ms_ > 0) std::this_thread::sleep_for(std::chrono::milliseconds(slow_ms_));
        return inner_->run(q, t);
    }
    std::string fingerprint() const override { return inner_->fingerprint(); }
    std::string run_fingerprint(cal::CubeTest t) const override { return inner_->run_fingerprint(t); }

private:
    std::unique_ptr<cal::CubeModel> inner_;
    int slow_ms_, die_after_, hang_after_;
    mutable std::atomic<int> runs_{0};
};

}  // namespace

int main(int argc, char** argv) {
    if (argc < 2) {
        std::fprintf(stderr, "usage: calibrate_mpi_driver <problem.toml> [fault options]\n");
        return 2;
    }
    Faults f;
    int max_runs = 0;
    for (int k = 2; k + 1 < argc; k += 2) {
        const std::string o = argv[k];
        const int v = std::atoi(argv[k + 1]);
        if (o == "--slow-ms") f.slow_ms = v;
        else if (o == "--die-rank") f.die_rank = v;
        else if (o == "--die-after") f.die_after = v;
        else if (o == "--hang-rank") f.hang_rank = v;
        else if (o == "--hang-after") f.hang_after = v;
        else if (o == "--max-runs") max_runs = v;
        else if (o == "--code-version-rank" && k + 2 < argc) f.version_rank = v, f.version = argv[k + 2], ++k;
        else if (o == "--cache-dir-rank" && k + 2 < argc) f.cache_rank = v, f.cache_dir = argv[k + 2], ++k;
        else {
            std::fprintf(stderr, "calibrate_mpi_driver: unknown option %s\n", o.c_str());
            return 2;
        }
    }
    int world_rank = 0;
    if (const char* r = std::getenv("OMPI_COMM_WORLD_RANK")) world_rank = std::atoi(r);
    cal::mpi::WorkerIdentity identity;
    if (world_rank == f.version_rank) identity.code_version = f.version;
    cal::CalibrationProblem problem;
    try {
        return cal::mpi::run_job(
            [&](int rank) {
                problem = cal::load_calibration_problem(argv[1]);
                if (max_runs) problem.solver.max_runs = max_runs;
                if (rank == f.cache_rank) problem.base.cache_dir = f.cache_dir;
                auto model = cal::make_model(problem);
                const bool faulty = rank > 0 && (rank == f.die_rank || rank == f.hang_rank || f.slow_ms > 0);
                if (faulty)
                    model = std::make_unique<FaultyModel>(std::move(model), f.slow_ms, rank == f.die_rank ? f.die_after : 0,
                                                          rank == f.hang_rank ? f.hang_after : 0);
                return cal::mpi::JobModel{std::move(model), problem.workers};
            },
            [&](cal::CubeModel& model, cal::mpi::MpiExecutor& executor) {
                const cal::CalibrationResult r = cal::run_calibration(problem, model, executor, [](const std::string& line) {
                    std::fprintf(stderr, "driver: %s\n", line.c_str());
                });
                report::write_calibration_outputs(problem, r);
                return 0;
            },
            identity);
    } catch (const std::exception& e) {
        std::fprintf(stderr, "gradem: %s\n", e.what());
        return 2;
    }
}
