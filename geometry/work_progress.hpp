#pragma once
/// How far a long loop is, for a progress line with an estimate of the time left (issue 21:
/// a 20-million-face scan spends minutes in a stage, and a user at a terminal wants to know
/// how many). The loops report by themselves: the parallel loops of the stages
/// (detail/parallel.hpp) and the readers of text meshes. Nothing is reported unless a caller
/// installs an observer with a WorkProgressScope, and the results never depend on it.

#include <atomic>
#include <chrono>
#include <functional>
#include <mutex>

namespace geotex {

/// One report of a loop: `done` of `total` units (indices of a loop, bytes of a file) after
/// `seconds`.
struct WorkProgress {
    long long done = 0;
    long long total = 0;
    double seconds = 0;
};
using WorkObserver = std::function<void(const WorkProgress&)>;

/// While it lives, the loops of at least `min_units` units that run `delay` seconds or more
/// call `observer` about every `interval` seconds, from the thread that finished a part of
/// the work (a worker thread of a parallel loop): never two calls at once. One scope at a
/// time per process; a second one, or one made while loops run, is a programming error
/// (std::logic_error). The observer must not throw.
class WorkProgressScope {
  public:
    explicit WorkProgressScope(WorkObserver observer, double delay = 1.0, double interval = 0.5,
                               long long min_units = 100000);
    ~WorkProgressScope();
    WorkProgressScope(const WorkProgressScope&) = delete;
    WorkProgressScope& operator=(const WorkProgressScope&) = delete;

    /// The settings of the live scope; internal to the loops.
    struct State {
        WorkObserver observer;
        double delay;
        double interval;
        long long min_units;
        std::mutex call;  // one observer call at a time
    };

  private:
    State state_;
};

namespace detail {

/// The meter of one loop of `total` units: add() the units done as parts finish (from any
/// thread). Costs one branch per add() when no scope is installed or the loop is short.
class LoopMeter {
  public:
    explicit LoopMeter(long long total);
    void add(long long units) {
        if (state_ == nullptr) return;
        const long long done = done_.fetch_add(units, std::memory_order_relaxed) + units;
        report(done);
    }

  private:
    using Clock = std::chrono::steady_clock;
    void report(long long done);

    WorkProgressScope::State* state_ = nullptr;
    long long total_ = 0;
    Clock::time_point start_;
    std::atomic<long long> done_{0};
    std::atomic<long long> next_report_ns_{0};  // since start_
};

}  // namespace detail
}  // namespace geotex
