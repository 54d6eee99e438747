// PeriodicTimer: runs a loop at a fixed rate on an injected Clock without drift. Deadlines are
// `first + k * period` exactly (integer nanoseconds), never "last wake-up + period", so wake-up latency
// does not accumulate.
//
// Overrun policy: if the loop falls behind by a whole period or more, the missed deadlines are SKIPPED
// (counted in `missed_ticks()`), keeping the phase; the timer never fires a burst to catch up. A deadline
// that is due exactly now is not missed.
//
// Blocking style (a service's main loop; stops when the clock is stopped):
//   ssl::time::PeriodicTimer timer(clock, std::chrono::milliseconds(16));
//   while (timer.wait_next()) publish(core.step(inputs, clock.now()));
//
// Polling style (e.g. publish health once a second from inside a receive loop):
//   ssl::time::PeriodicTimer health(clock, std::chrono::seconds(1));
//   if (health.poll(clock.now())) publish_health();
//
// Not thread-safe: use one timer from one thread. The Clock must outlive the timer.
#pragma once

#include <cstdint>

#include "libs/time/clock.h"
#include "libs/time/time.h"

namespace ssl::time {

class PeriodicTimer {
 public:
  /// First deadline = clock.now() + period.
  /// @throws std::invalid_argument if period <= 0.
  PeriodicTimer(Clock& clock, Duration period);

  /// First deadline = `first_deadline` (e.g. aligned to a whole second, or `now` to fire at once).
  /// @throws std::invalid_argument if period <= 0.
  PeriodicTimer(Clock& clock, Duration period, Timestamp first_deadline);

  /// The deadline the next wait_next()/poll() waits for.
  Timestamp next_deadline() const noexcept { return next_; }

  Duration period() const noexcept { return period_; }

  /// Sleeps until the next deadline, then schedules the one after it (skipping deadlines already past).
  /// @return true when a tick is due, false if the clock was stopped (the schedule is then unchanged).
  bool wait_next();

  /// Non-blocking: if `now` has reached the next deadline, schedules the following one and returns true.
  bool poll(Timestamp now) noexcept;

  /// Ticks delivered by wait_next()/poll() so far.
  std::uint64_t ticks() const noexcept { return ticks_; }

  /// Deadlines skipped because the loop was late by at least a whole period.
  std::uint64_t missed_ticks() const noexcept { return missed_; }

  /// Restarts the schedule at `first_deadline` (counters are kept).
  void reset(Timestamp first_deadline) noexcept { next_ = first_deadline; }

 private:
  // Called once the deadline `next_` is due at time `now`; moves `next_` to the first deadline > now,
  // or to next_ + period if that is later.
  void schedule_after(Timestamp now) noexcept;

  Clock* clock_;
  Duration period_;
  Timestamp next_;
  std::uint64_t ticks_ = 0;
  std::uint64_t missed_ = 0;
};

}  // namespace ssl::time
