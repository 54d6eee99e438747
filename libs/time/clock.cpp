#include "libs/time/clock.h"

namespace ssl::time {
namespace {

template <typename StdClock>
Timestamp now_on() {
  return Timestamp::from_since_epoch(
      std::chrono::duration_cast<Duration>(StdClock::now().time_since_epoch()));
}

// Sleeps on `wake` until StdClock reaches `deadline` or `stopped` is set. Loops because the condition
// variable may wake spuriously and the wall clock may be set while we wait.
template <typename StdClock>
bool sleep_on(std::mutex& mutex, std::condition_variable& wake, const bool& stopped, Timestamp deadline) {
  const typename StdClock::time_point until{
      std::chrono::duration_cast<typename StdClock::duration>(deadline.since_epoch())};
  std::unique_lock lock(mutex);
  while (!stopped) {
    if (StdClock::now() >= until) return true;
    wake.wait_until(lock, until);
  }
  return false;
}

}  // namespace

Timestamp RealClock::now() const { return now_on<std::chrono::system_clock>(); }

bool RealClock::sleep_until(Timestamp deadline) {
  return sleep_on<std::chrono::system_clock>(mutex_, wake_, stopped_, deadline);
}

void RealClock::stop() {
  {
    std::lock_guard lock(mutex_);
    stopped_ = true;
  }
  wake_.notify_all();
}

bool RealClock::stopped() const {
  std::lock_guard lock(mutex_);
  return stopped_;
}

Timestamp MonotonicClock::now() const { return now_on<std::chrono::steady_clock>(); }

bool MonotonicClock::sleep_until(Timestamp deadline) {
  return sleep_on<std::chrono::steady_clock>(mutex_, wake_, stopped_, deadline);
}

void MonotonicClock::stop() {
  {
    std::lock_guard lock(mutex_);
    stopped_ = true;
  }
  wake_.notify_all();
}

bool MonotonicClock::stopped() const {
  std::lock_guard lock(mutex_);
  return stopped_;
}

Timestamp SimulatedClock::now() const {
  std::lock_guard lock(mutex_);
  return now_;
}

bool SimulatedClock::sleep_until(Timestamp deadline) {
  std::unique_lock lock(mutex_);
  if (stopped_) return false;
  if (now_ >= deadline) return true;
  ++sleepers_;
  changed_.notify_all();  // wait_for_sleepers() may be waiting for us
  changed_.wait(lock, [&] { return stopped_ || now_ >= deadline; });
  --sleepers_;
  return !stopped_;
}

void SimulatedClock::stop() {
  {
    std::lock_guard lock(mutex_);
    stopped_ = true;
  }
  changed_.notify_all();
}

bool SimulatedClock::stopped() const {
  std::lock_guard lock(mutex_);
  return stopped_;
}

void SimulatedClock::advance(Duration duration) {
  if (duration <= Duration::zero()) return;
  {
    std::lock_guard lock(mutex_);
    now_ += duration;
  }
  changed_.notify_all();
}

void SimulatedClock::set(Timestamp time) {
  {
    std::lock_guard lock(mutex_);
    now_ = time;
  }
  changed_.notify_all();
}

std::size_t SimulatedClock::sleeper_count() const {
  std::lock_guard lock(mutex_);
  return sleepers_;
}

bool SimulatedClock::wait_for_sleepers(std::size_t count, Duration real_timeout) const {
  std::unique_lock lock(mutex_);
  return changed_.wait_for(lock, real_timeout, [&] { return sleepers_ >= count; });
}

}  // namespace ssl::time
