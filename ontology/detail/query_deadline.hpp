#pragma once
// When a query must stop (QueryParams::timeout). Rasqal 0.9.33 has no way to cancel a query:
// the loops that can run long (reading the data, matching triple patterns, reading rows) ask
// a Deadline, and a pattern whose time is up matches nothing more, so Rasqal's joins unwind;
// run_sparql then throws QueryTimeout instead of returning the rows seen so far.

#include <chrono>
#include <cstdint>

namespace geotex::detail {

class Deadline {
  public:
    using Clock = std::chrono::steady_clock;

    /// No limit.
    Deadline() = default;
    /// `seconds` from now (> 0 and finite; checked by run_sparql).
    explicit Deadline(double seconds)
        : limited_(true),
          seconds_(seconds),
          at_(Clock::now() +
              std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(seconds))) {
    }

    /// Whether the time is up; reads the clock. Safe from several threads.
    bool passed() const { return limited_ && Clock::now() >= at_; }
    double seconds() const { return seconds_; }
    /// Throws the QueryTimeout of this deadline (one line: the limit, and that no result is
    /// written).
    [[noreturn]] void throw_timeout() const;

  private:
    bool limited_ = false;
    double seconds_ = 0;
    Clock::time_point at_{};
};

/// A Deadline asked from one thread in a loop that runs millions of times: it reads the clock
/// once every 1024 calls (a triple pattern's step is a few nanoseconds, the clock about 20),
/// and stays passed once it has seen the time up.
class DeadlineCheck {
  public:
    explicit DeadlineCheck(const Deadline* deadline = nullptr) : deadline_(deadline) {}

    bool passed() {
        if (passed_) return true;
        if (!deadline_ || (++calls_ & 1023u) != 0) return false;
        passed_ = deadline_->passed();
        return passed_;
    }
    /// Reads the clock now (for loops whose steps are slow, e.g. one result row).
    bool passed_now() {
        if (!passed_ && deadline_) passed_ = deadline_->passed();
        return passed_;
    }
    /// Whether a call has seen the time up (without reading the clock).
    bool seen() const { return passed_; }

  private:
    const Deadline* deadline_;
    std::uint32_t calls_ = 0;
    bool passed_ = false;
};

}  // namespace geotex::detail
