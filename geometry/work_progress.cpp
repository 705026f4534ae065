#include "geometry/work_progress.hpp"

#include <algorithm>
#include <stdexcept>

namespace geotex {

namespace {
// The live scope's state, or nullptr. Loops read it once, when they start.
std::atomic<WorkProgressScope::State*> g_state{nullptr};
}  // namespace

WorkProgressScope::WorkProgressScope(WorkObserver observer, double delay, double interval,
                                     long long min_units)
    : state_{std::move(observer), delay, interval, min_units, {}} {
    WorkProgressScope::State* none = nullptr;
    if (!g_state.compare_exchange_strong(none, &state_))
        throw std::logic_error("WorkProgressScope: another scope is live");
}

WorkProgressScope::~WorkProgressScope() { g_state.store(nullptr); }

namespace detail {

LoopMeter::LoopMeter(long long total) : total_(total), start_(Clock::now()) {
    WorkProgressScope::State* state = g_state.load();
    if (state == nullptr || total < state->min_units || !state->observer) return;
    state_ = state;
    next_report_ns_ = static_cast<long long>(state->delay * 1e9);
}

void LoopMeter::report(long long done) {
    const long long now =
        std::chrono::duration_cast<std::chrono::nanoseconds>(Clock::now() - start_).count();
    long long due = next_report_ns_.load(std::memory_order_relaxed);
    if (now < due) return;
    // One thread wins the report of this moment; the others go back to work.
    if (!next_report_ns_.compare_exchange_strong(
            due, now + static_cast<long long>(state_->interval * 1e9)))
        return;
    std::lock_guard<std::mutex> lock(state_->call);
    state_->observer({std::min(done, total_), total_, static_cast<double>(now) * 1e-9});
}

}  // namespace detail
}  // namespace geotex
