// Injectable clocks. Code that needs "now" or has to wait takes a `Clock&` instead of calling
// std::chrono directly, so that the same code runs on real time in production and on a `SimulatedClock`
// in lockstep simulation and tests (pure cores take `now` as an argument and need no clock at all).
//
//   RealClock       host wall clock, CLOCK_REALTIME, ns since the Unix epoch. Stamps that other processes
//                   on this host compare against; may jump when the system time is set.
//   MonotonicClock  host monotonic clock, CLOCK_MONOTONIC, ns since boot. Timeouts and periods.
//   SimulatedClock  stands still until `advance()` / `set()`; starts at the time given (default: epoch).
//
// Every clock supports `stop()`: it wakes all current sleepers and makes every later sleep return at once
// (returning false), so a service can map SIGINT/SIGTERM to `clock.stop()` and shutdown never hangs in a
// sleep. Stopping is permanent. All member functions are thread-safe.
//
//   void run(ssl::time::Clock& clock) {
//     while (clock.sleep_for(std::chrono::milliseconds(10))) {   // false once clock.stop() was called
//       step(clock.now());
//     }
//   }
//
//   ssl::time::SimulatedClock sim(ssl::time::Timestamp::from_seconds(1000.0));
//   std::thread worker([&] { run(sim); });
//   sim.advance(std::chrono::milliseconds(10));   // wakes the worker exactly once
//   sim.stop();
//   worker.join();
#pragma once

#include <condition_variable>
#include <cstddef>
#include <mutex>

#include "libs/time/time.h"

namespace ssl::time {

/// Abstract clock. Implementations are thread-safe; one clock may be shared by many threads.
class Clock {
 public:
  virtual ~Clock() = default;

  /// The current time on this clock.
  virtual Timestamp now() const = 0;

  /// Blocks until `now() >= deadline` or until `stop()` is called.
  /// @return true if the deadline was reached, false if the clock was stopped (also when stopped before
  ///         the call). A deadline in the past returns true at once (unless stopped).
  virtual bool sleep_until(Timestamp deadline) = 0;

  /// Wakes every sleeper and makes all later sleeps return false immediately. Idempotent, permanent.
  virtual void stop() = 0;

  /// True once `stop()` was called.
  virtual bool stopped() const = 0;

  /// `sleep_until(now() + duration)`; same return value. Non-positive durations do not block.
  bool sleep_for(Duration duration) { return sleep_until(now() + duration); }
};

/// Host wall clock (CLOCK_REALTIME through std::chrono::system_clock), ns since the Unix epoch.
/// Sleeps follow the wall clock: if the time is set forward, sleepers wake early.
class RealClock final : public Clock {
 public:
  Timestamp now() const override;
  bool sleep_until(Timestamp deadline) override;
  void stop() override;
  bool stopped() const override;

 private:
  mutable std::mutex mutex_;
  std::condition_variable wake_;
  bool stopped_ = false;  // guarded by mutex_
};

/// Host monotonic clock (CLOCK_MONOTONIC through std::chrono::steady_clock), ns since boot.
class MonotonicClock final : public Clock {
 public:
  Timestamp now() const override;
  bool sleep_until(Timestamp deadline) override;
  void stop() override;
  bool stopped() const override;

 private:
  mutable std::mutex mutex_;
  std::condition_variable wake_;
  bool stopped_ = false;  // guarded by mutex_
};

/// A clock that only moves when told to. Sleepers block (on a condition variable, not spinning) until the
/// simulated time reaches their deadline or the clock is stopped.
class SimulatedClock final : public Clock {
 public:
  /// @param start the initial simulated time (e.g. a Unix time to look like the wall clock).
  explicit SimulatedClock(Timestamp start = Timestamp{}) noexcept : now_(start) {}

  Timestamp now() const override;
  bool sleep_until(Timestamp deadline) override;
  void stop() override;
  bool stopped() const override;

  /// Moves the time forward by `duration` and wakes every sleeper whose deadline is reached.
  /// Precondition: duration >= 0 (a negative duration is ignored: simulated time never runs backwards
  /// through advance(); use set() for that).
  void advance(Duration duration);

  /// Sets the time. Moving backwards is allowed (e.g. restarting a replay); sleepers then keep waiting
  /// for their deadlines.
  void set(Timestamp time);

  /// Number of threads currently blocked in sleep_until (for tests and lockstep drivers).
  std::size_t sleeper_count() const;

  /// Blocks (in REAL time) until at least `count` threads sleep on this clock, or `real_timeout` passes.
  /// Lets a lockstep driver advance only once its workers are waiting.
  /// @return true if that many sleepers were seen.
  bool wait_for_sleepers(std::size_t count, Duration real_timeout) const;

 private:
  mutable std::mutex mutex_;
  // One condition variable for both "time moved / stopped" and "sleeper count changed"; waiters recheck.
  mutable std::condition_variable changed_;
  Timestamp now_;             // guarded by mutex_
  std::size_t sleepers_ = 0;  // guarded by mutex_
  bool stopped_ = false;      // guarded by mutex_
};

}  // namespace ssl::time
