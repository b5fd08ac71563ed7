#include "calibrate/execution/run_executor.hpp"

#include <unistd.h>

#include <climits>
#include <cstdlib>
#include <mutex>
#include <stdexcept>

#include "calibrate/execution/thread_pool.hpp"

namespace gradem::cal {

std::string host_name() {
    char buf[HOST_NAME_MAX + 1] = {};
    if (gethostname(buf, sizeof buf - 1) != 0 || buf[0] == '\0') return "unknown";
    return buf;
}

bool started_by_mpi_launcher() {
    for (const char* var : {"OMPI_COMM_WORLD_SIZE", "PMIX_RANK", "PMI_RANK", "PMI_SIZE"})
        if (std::getenv(var)) return true;
    return false;
}

ThreadExecutor::ThreadExecutor(CubeModel& model, int workers) : ThreadExecutor(static_cast<const CubeModel&>(model), workers) {
    preparable_ = &model;
}

ThreadExecutor::ThreadExecutor(const CubeModel& model, int workers)
    : model_(model), preparable_(nullptr), workers_(std::max(1, workers)) {
    place_.rank = 0;
    place_.host = host_name();
}

void ThreadExecutor::prepare(const PackingSeeds& seeds, const Log& log) {
    if (!preparable_) throw std::logic_error("ThreadExecutor::prepare: the model was given as const (prepare it before)");
    preparable_->prepare(seeds, workers_, log);
}

void ThreadExecutor::run(const std::vector<RunRequest>& requests, double timeout_s, const RunDone& done) {
    std::mutex mutex;
    parallel_for(requests.size(), workers_, [&](std::size_t k) {
        const RunOutcome outcome = model_.run(requests[k], timeout_s);
        const std::lock_guard lock(mutex);
        done(k, outcome, place_);
    });
}

std::string ThreadExecutor::describe() const {
    return std::to_string(workers_) + (workers_ == 1 ? " thread" : " threads") + " on " + place_.host;
}

}  // namespace gradem::cal
