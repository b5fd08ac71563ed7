// The MPI executor (calibrate/execution/mpi_executor.hpp). Only rank 0's main thread and the workers'
// main threads call MPI (MPI_THREAD_FUNNELED). Nobody blocks in MPI: Open MPI busy-polls in
// a blocking receive, which would take a core from the cube tests, so every wait is
// MPI_Iprobe with short sleeps (class Backoff) - and can time out.
#include "calibrate/execution/mpi_executor.hpp"

#include <mpi.h>
#include <unistd.h>
#ifdef _OPENMP
#include <omp.h>
#endif

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <deque>
#include <optional>
#include <thread>

#include "calibrate/execution/code_version.hpp"
#include "calibrate/execution/run_message.hpp"
#include "common/hash.hpp"
#include "common/number_format.hpp"

namespace gradem::cal::mpi {
namespace {

using Clock = std::chrono::steady_clock;
using wire::Kind;

/// Set when rank 0 gives a worker up (or leaves runs in flight): the job must then end without
/// finalizing (Session::~Session).
bool g_rank_lost = false;

/// Rank 0's exit status when it ends a job with a lost rank.
constexpr int kLostRankExitStatus = 5;

struct Message {
    int source = 0;
    std::string bytes;
};

void send(int dest, Kind kind, const std::string& bytes) {
    MPI_Send(bytes.data(), static_cast<int>(bytes.size()), MPI_BYTE, dest, static_cast<int>(kind), MPI_COMM_WORLD);
}

std::optional<Message> poll(int source) {
    int flag = 0;
    MPI_Status status;
    MPI_Iprobe(source, MPI_ANY_TAG, MPI_COMM_WORLD, &flag, &status);
    if (!flag) return std::nullopt;
    int count = 0;
    MPI_Get_count(&status, MPI_BYTE, &count);
    Message m;
    m.source = status.MPI_SOURCE;
    m.bytes.resize(static_cast<std::size_t>(count));
    MPI_Recv(m.bytes.data(), count, MPI_BYTE, status.MPI_SOURCE, status.MPI_TAG, MPI_COMM_WORLD, MPI_STATUS_IGNORE);
    return m;
}

/// Between polls: a few hundred immediate re-polls first (an answer that is on its way costs
/// no sleep, which a loaded node may stretch to a scheduler slice), then sleeps from 20 us
/// doubling to 1 ms when idle.
class Backoff {
public:
    void reset() { spins_ = 0, us_ = 20; }
    void wait() {
        if (spins_ < 256) {
            ++spins_;
            return;
        }
        std::this_thread::sleep_for(std::chrono::microseconds(us_));
        us_ = std::min(us_ * 2, 1000);
    }

private:
    int spins_ = 0, us_ = 20;
};

/// The next message from `source` (MPI_ANY_SOURCE: anyone), or nullopt after `timeout_s`
/// (<= 0: wait for ever).
std::optional<Message> wait_message(int source, double timeout_s) {
    const auto start = Clock::now();
    Backoff backoff;
    while (true) {
        if (auto m = poll(source)) return m;
        if (timeout_s > 0 && std::chrono::duration<double>(Clock::now() - start).count() > timeout_s) return std::nullopt;
        backoff.wait();
    }
}

std::string where(int rank, const std::string& host) { return "rank " + std::to_string(rank) + " on host " + host; }

int world_size() {
    int n = 1;
    MPI_Comm_size(MPI_COMM_WORLD, &n);
    return n;
}

int world_rank() {
    int r = 0;
    MPI_Comm_rank(MPI_COMM_WORLD, &r);
    return r;
}

}  // namespace

bool launched() { return started_by_mpi_launcher(); }

Session::Session() {
    int provided = 0;
    MPI_Init_thread(nullptr, nullptr, MPI_THREAD_FUNNELED, &provided);
    rank_ = world_rank();
    size_ = world_size();
}

Session::~Session() {
    if (g_rank_lost) {
        std::fprintf(stderr, "gradem: a worker rank did not answer; ending the job without MPI_Finalize (a lost rank "
                             "cannot finalize); every finished run is in the ledger\n");
        std::fflush(stderr);
        std::fflush(stdout);
        // Not MPI_Abort: Open MPI 4.1's abort sends mpirun a help message whose unpacking races
        // ("ORTE_ERROR_LOG: Data unpack would read past end of buffer in show_help.c", seen in CI
        // on 2 loaded cores), after which mpirun never ends the job. A rank that exits non-zero
        // without finalizing makes mpirun end the job and kill the other ranks, hung ones too.
        std::_Exit(kLostRankExitStatus);
    }
    MPI_Finalize();
}

// ---- worker ranks ----------------------------------------------------------------------

int serve(CubeModel* model, const std::string& load_error, const WorkerIdentity& identity) {
    const int rank = world_rank();
    wire::Hello hello;
    hello.code_version = identity.code_version.empty() ? code_version() : identity.code_version;
    hello.host = host_name();
    hello.model_fingerprint = model ? model->fingerprint() : "";
    hello.pid = static_cast<std::int64_t>(getpid());
#ifdef _OPENMP
    hello.threads = omp_get_max_threads();
#endif
    hello.error = model || !load_error.empty() ? load_error : "no model";
    send(0, Kind::hello, wire::encode(hello));
    const std::string model_hash = common::fnv1a_hex(hello.model_fingerprint);
    auto refuse = [&](const std::string& why) { send(0, Kind::stop, wire::encode(wire::Stop{where(rank, hello.host) + ": " + why})); };
    while (true) {
        const Message m = *wait_message(0, 0.0);
        try {
            switch (wire::kind_of(m.bytes)) {
                case Kind::prepare: {
                    const auto start = Clock::now();
                    wire::Prepared reply;
                    try {
                        if (!model) throw std::runtime_error(hello.error);
                        model->load_prepared(wire::decode_prepare(m.bytes).seeds);
                    } catch (const std::exception& e) {
                        reply.error = e.what();
                    }
                    reply.seconds = std::chrono::duration<double>(Clock::now() - start).count();
                    send(0, Kind::prepared, wire::encode(reply));
                    break;
                }
                case Kind::run: {
                    const wire::Run run = wire::decode_run(m.bytes);
                    if (run.code_version != hello.code_version) {
                        refuse("runs gradem " + hello.code_version + ", the request comes from gradem " + run.code_version);
                        break;
                    }
                    if (!model || run.model_hash != model_hash) {
                        refuse("the request is for another model (fingerprint hash " + run.model_hash + ", this rank's " + model_hash + ")");
                        break;
                    }
                    wire::Result result;
                    result.job = run.job;
                    try {
                        result.outcome = model->run(run.request, run.timeout_s);
                    } catch (const std::exception& e) {  // a model that throws: a failed run, not a dead rank
                        result.outcome = RunOutcome{};
                        result.outcome.status = OutcomeStatus::failed;
                        result.outcome.reason = where(rank, hello.host) + ": " + e.what();
                    }
                    send(0, Kind::result, wire::encode(result));
                    break;
                }
                // Rank 0 reports and sets the job's exit code; a worker exiting non-zero would
                // make mpirun kill rank 0 before it has said why.
                case Kind::stop: return 0;
                default: refuse(std::string("unexpected '") + to_string(wire::kind_of(m.bytes)) + "' message");
            }
        } catch (const wire::WireError& e) {
            refuse(e.what());
        }
    }
}

void dismiss_workers(const std::string& reason, double timeout_s) {
    const int n = world_size();
    int hellos = 0;
    while (hellos < n - 1) {
        const auto m = wait_message(MPI_ANY_SOURCE, timeout_s);
        if (!m) break;
        ++hellos;
    }
    for (int r = 1; r < n; ++r) send(r, Kind::stop, wire::encode(wire::Stop{reason.empty() ? "rank 0 stopped" : reason}));
}

// ---- rank 0 ------------------------------------------------------------------------------

MpiExecutor::MpiExecutor(CubeModel& model, int threads, double handshake_timeout_s)
    : model_(model), threads_(std::max(1, threads)), model_hash_(common::fnv1a_hex(model.fingerprint())),
      handshake_timeout_s_(handshake_timeout_s) {
    const int n = world_size();
    for (int r = 1; r < n; ++r) workers_.push_back({r, "?", 1, false, false});
    // 1. Every worker's hello, checked against rank 0's build and model.
    std::string problems;
    int received = 0;
    const auto start = Clock::now();
    while (received < n - 1) {
        const double left = handshake_timeout_s_ - std::chrono::duration<double>(Clock::now() - start).count();
        const auto m = wait_message(MPI_ANY_SOURCE, std::max(left, 1e-3));
        if (!m) break;
        Worker& w = workers_[static_cast<std::size_t>(m->source - 1)];
        ++received;
        try {
            const wire::Hello h = wire::decode_hello(m->bytes);
            w.host = h.host;
            w.threads = h.threads;
            if (!h.error.empty())
                problems += "\n  " + where(w.rank, w.host) + " cannot load the problem: " + h.error;
            else if (h.code_version != code_version())
                problems += "\n  " + where(w.rank, w.host) + " runs gradem " + h.code_version + ", rank 0 runs gradem " +
                            code_version() + ": mismatched builds across ranks (run one build, e.g. from a shared path)";
            else if (h.model_fingerprint != model.fingerprint())
                problems += "\n  " + where(w.rank, w.host) + " has another model (fingerprint '" + h.model_fingerprint +
                            "', rank 0: '" + model.fingerprint() + "'): do all ranks read the same config and data?";
        } catch (const wire::WireError& e) {
            problems += "\n  rank " + std::to_string(w.rank) + ": " + e.what();
        }
    }
    if (received < n - 1) {
        for (Worker& w : workers_)
            if (w.host == "?") w.lost = true;
        g_rank_lost = true;
        problems += "\n  " + std::to_string(n - 1 - received) + " worker rank(s) said nothing within " +
                    common::format_significant(handshake_timeout_s_, 6) + " s";
    }
    if (!problems.empty()) {
        stop_all("rank 0 refused the job");
        throw ExecutorError("MPI job: the worker ranks cannot be used:" + problems);
    }
}

MpiExecutor::~MpiExecutor() { stop_all(""); }

void MpiExecutor::stop_all(const std::string& reason) {
    for (Worker& w : workers_)
        if (!w.stopped && !w.lost) {
            send(w.rank, Kind::stop, wire::encode(wire::Stop{reason}));
            w.stopped = true;
        }
}

void MpiExecutor::prepare(const PackingSeeds& seeds, const Log& log) {
    model_.prepare(seeds, threads_, log);  // made once, here, into the shared cache
    const auto start = Clock::now();
    for (const Worker& w : workers_)
        if (!w.lost) send(w.rank, Kind::prepare, wire::encode(wire::Prepare{seeds}));
    std::string problems;
    double slowest = 0.0;
    for (const Worker& w : workers_) {
        if (w.lost) continue;
        const double left = handshake_timeout_s_ - std::chrono::duration<double>(Clock::now() - start).count();
        const auto m = wait_message(w.rank, std::max(left, 1e-3));
        if (!m) {
            problems += "\n  " + where(w.rank, w.host) + " did not load the packings within " +
                        common::format_significant(handshake_timeout_s_, 6) + " s";
            workers_[static_cast<std::size_t>(w.rank - 1)].lost = g_rank_lost = true;
            continue;
        }
        try {
            if (wire::kind_of(m->bytes) == Kind::stop)
                problems += "\n  " + wire::decode_stop(m->bytes).reason;
            else if (const wire::Prepared p = wire::decode_prepared(m->bytes); !p.error.empty())
                problems += "\n  " + where(w.rank, w.host) + " cannot load the packings: " + p.error;
            else
                slowest = std::max(slowest, p.seconds);
        } catch (const wire::WireError& e) {
            problems += "\n  " + where(w.rank, w.host) + ": " + e.what();
        }
    }
    if (!problems.empty()) {
        stop_all("rank 0 stopped the job: packings");
        throw ExecutorError("MPI job:" + problems);
    }
    if (log) {
        char buf[160];
        std::snprintf(buf, sizeof buf, "%zu worker ranks loaded the packings from the cache (slowest %.2f s)", workers_.size(), slowest);
        log(buf);
    }
}

/// One batch of runs on the worker ranks: every idle worker gets the next request, results
/// come back in any order, and a worker past its deadline is given up (its run a timeout).
class MpiExecutor::Batch {
public:
    Batch(MpiExecutor& executor, const std::vector<RunRequest>& requests, double timeout_s, const RunDone& done)
        : x_(executor), requests_(requests), timeout_s_(timeout_s), done_(done),
          limit_(timeout_s > 0 ? timeout_s + grace_seconds(timeout_s) : 0.0), flights_(executor.workers_.size()) {
        for (std::size_t k = 0; k < requests.size(); ++k) pending_.push_back(k);
    }

    void run() {
        Backoff backoff;
        while (true) {
            const auto [in_flight, live] = dispatch();
            if (in_flight == 0 && (pending_.empty() || error_)) break;
            if (live == 0)
                throw ExecutorError("MPI job: every worker rank is lost; " + std::to_string(pending_.size()) +
                                    " runs of this batch were not run (finished runs are in the ledger)");
            if (receive()) {
                backoff.reset();
                continue;
            }
            backoff.wait();
            expire_overdue();
        }
        if (error_) std::rethrow_exception(error_);
    }

private:
    struct Flight {
        std::size_t index = 0;
        std::uint64_t job = 0;
        Clock::time_point deadline;
    };

    /// 1. Every idle worker gets the next request; returns {runs in flight, live workers}.
    std::pair<std::size_t, std::size_t> dispatch() {
        std::size_t in_flight = 0, live = 0;
        for (std::size_t w = 0; w < x_.workers_.size(); ++w) {
            if (x_.workers_[w].lost || x_.workers_[w].stopped) continue;
            ++live;
            if (!flights_[w] && !pending_.empty() && !error_) {
                wire::Run run;
                run.job = x_.next_job_++;
                run.code_version = code_version();
                run.model_hash = x_.model_hash_;
                run.timeout_s = timeout_s_;
                run.request = requests_[pending_.front()];
                send(x_.workers_[w].rank, Kind::run, wire::encode(run));
                flights_[w] = Flight{pending_.front(), run.job,
                                     Clock::now() + std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(limit_))};
                pending_.pop_front();
            }
            if (flights_[w]) ++in_flight;
        }
        return {in_flight, live};
    }

    /// 2. A result (true), nothing yet (false), or a refusal or bad message: the job stops.
    bool receive() {
        const auto m = poll(MPI_ANY_SOURCE);
        if (!m) return false;
        const std::size_t w = static_cast<std::size_t>(m->source - 1);
        const Worker& worker = x_.workers_.at(w);
        Kind kind;
        try {
            kind = wire::kind_of(m->bytes);
            if (kind == Kind::result) {
                wire::Result r = wire::decode_result(m->bytes);
                if (flights_[w] && flights_[w]->job == r.job) {
                    const std::size_t index = flights_[w]->index;
                    flights_[w].reset();
                    finish(index, r.outcome, {worker.rank, worker.host});
                }
                return true;
            }
        } catch (const wire::WireError& e) {
            abandon_flights();
            x_.stop_all("rank 0 stopped the job: bad message");
            throw ExecutorError("MPI job: " + where(worker.rank, worker.host) + " sent a bad message: " + e.what());
        }
        abandon_flights();
        x_.stop_all("rank 0 stopped the job");
        throw ExecutorError("MPI job: " + (kind == Kind::stop ? wire::decode_stop(m->bytes).reason
                                                               : where(worker.rank, worker.host) + " sent an unexpected '" +
                                                                     to_string(kind) + "' message"));
    }

    /// 3. A worker past its deadline is given up: its run is a timeout, the rank is not used again.
    void expire_overdue() {
        if (limit_ <= 0) return;
        const auto now = Clock::now();
        for (std::size_t w = 0; w < x_.workers_.size(); ++w)
            if (flights_[w] && now > flights_[w]->deadline) {
                Worker& worker = x_.workers_[w];
                worker.lost = g_rank_lost = true;
                RunOutcome o;
                o.status = OutcomeStatus::timeout;
                o.reason = where(worker.rank, worker.host) + " sent no result within " + common::format_significant(limit_, 6) +
                           " s (timeout_s + grace); the rank is no longer used";
                o.wall_seconds = limit_;
                const std::size_t index = flights_[w]->index;
                flights_[w].reset();
                finish(index, o, {worker.rank, worker.host});
            }
    }

    void finish(std::size_t index, const RunOutcome& outcome, const RunPlace& place) {
        if (error_) return;
        try {
            done_(index, outcome, place);
        } catch (...) {
            error_ = std::current_exception();
        }
    }

    /// Runs still in flight when rank 0 gives up: their workers may be blocked sending a
    /// result nobody will receive, so the job cannot finalize; rank 0 exits without it.
    void abandon_flights() const {
        for (const auto& f : flights_)
            if (f) g_rank_lost = true;
    }

    MpiExecutor& x_;
    const std::vector<RunRequest>& requests_;
    double timeout_s_;
    const RunDone& done_;
    double limit_;
    std::deque<std::size_t> pending_;
    std::vector<std::optional<Flight>> flights_;
    std::exception_ptr error_;
};

void MpiExecutor::run(const std::vector<RunRequest>& requests, double timeout_s, const RunDone& done) {
    Batch(*this, requests, timeout_s, done).run();
}

int MpiExecutor::slots() const {
    int n = 0;
    for (const Worker& w : workers_) n += !w.lost && !w.stopped;
    return std::max(1, n);
}

std::string MpiExecutor::describe() const {
    std::vector<std::string> hosts;
    std::int64_t threads = 0;
    for (const Worker& w : workers_) {
        if (std::find(hosts.begin(), hosts.end(), w.host) == hosts.end()) hosts.push_back(w.host);
        threads = std::max(threads, w.threads);
    }
    return "MPI: " + std::to_string(workers_.size()) + " worker ranks on " + std::to_string(hosts.size()) +
           (hosts.size() == 1 ? " host" : " hosts") + " (" + std::to_string(threads) + " OpenMP thread" + (threads == 1 ? "" : "s") +
           " each), rank 0 coordinates";
}

std::vector<int> MpiExecutor::lost_ranks() const {
    std::vector<int> out;
    for (const Worker& w : workers_)
        if (w.lost) out.push_back(w.rank);
    return out;
}

// ---- the job -----------------------------------------------------------------------------

int run_job(const std::function<JobModel(int rank)>& make_model, const std::function<int(CubeModel&, MpiExecutor&)>& coordinate,
            const WorkerIdentity& identity) {
    std::exception_ptr error;
    int code = 0;
    {
        Session session;
        if (session.size() < 2) {
            error = std::make_exception_ptr(ExecutorError(
                "MPI launched with one rank: rank 0 coordinates and ranks 1..N-1 run the cube tests, so an MPI job needs "
                "at least 2 ranks (e.g. mpirun -np 3 gradem calibrate ...); for threads, run gradem without mpirun"));
        } else if (session.rank() != 0) {
            JobModel job;
            std::string load_error;
            try {
                job = make_model(session.rank());
            } catch (const std::exception& e) {
                load_error = e.what();
            }
            code = serve(job.model.get(), load_error, identity);
        } else {
            JobModel job;
            try {
                job = make_model(0);
            } catch (const std::exception& e) {
                dismiss_workers(std::string("rank 0 cannot load the problem: ") + e.what());
                error = std::current_exception();
            }
            if (!error) {
                try {
                    MpiExecutor executor(*job.model, job.threads);
                    code = coordinate(*job.model, executor);
                } catch (...) {
                    error = std::current_exception();
                }
            }
            if (error && g_rank_lost) {  // the Session exits without finalizing: say why first
                try {
                    std::rethrow_exception(error);
                } catch (const std::exception& e) {
                    std::fprintf(stderr, "gradem: %s\n", e.what());
                }
            }
        }
    }
    if (error) std::rethrow_exception(error);
    return code;
}

}  // namespace gradem::cal::mpi
