#include "libs/time/periodic_timer.h"

#include <stdexcept>

namespace ssl::time {
namespace {

Duration checked_period(Duration period) {
  if (period <= Duration::zero()) {
    throw std::invalid_argument("PeriodicTimer: period must be positive, got " + to_string(period));
  }
  return period;
}

}  // namespace

PeriodicTimer::PeriodicTimer(Clock& clock, Duration period)
    : clock_(&clock), period_(checked_period(period)), next_(clock.now() + period) {}

PeriodicTimer::PeriodicTimer(Clock& clock, Duration period, Timestamp first_deadline)
    : clock_(&clock), period_(checked_period(period)), next_(first_deadline) {}

bool PeriodicTimer::wait_next() {
  if (!clock_->sleep_until(next_)) return false;
  schedule_after(clock_->now());
  return true;
}

bool PeriodicTimer::poll(Timestamp now) noexcept {
  if (now < next_) return false;
  schedule_after(now);
  return true;
}

void PeriodicTimer::schedule_after(Timestamp now) noexcept {
  ++ticks_;
  const Timestamp due = next_;
  // Deadlines due + k * period (k >= 1) that are strictly before `now` were missed.
  std::int64_t skipped = 0;
  if (now > due + period_) skipped = (now - due - Duration(1)) / period_;
  missed_ += static_cast<std::uint64_t>(skipped);
  next_ = due + period_ * (skipped + 1);
}

}  // namespace ssl::time
