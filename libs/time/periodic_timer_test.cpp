#include "libs/time/periodic_timer.h"

#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <future>
#include <stdexcept>
#include <thread>
#include <vector>

namespace ssl::time {
namespace {

using namespace std::chrono_literals;

constexpr auto kWakeTimeout = 10s;

// Polls `condition` until it holds or kWakeTimeout passes (real time).
template <typename Condition>
bool wait_until(Condition condition) {
  const auto give_up = std::chrono::steady_clock::now() + kWakeTimeout;
  while (!condition()) {
    if (std::chrono::steady_clock::now() > give_up) return false;
    std::this_thread::yield();
  }
  return true;
}

TEST(PeriodicTimerTest, RejectsNonPositivePeriods) {
  SimulatedClock clock;
  EXPECT_THROW(PeriodicTimer(clock, 0ms), std::invalid_argument);
  EXPECT_THROW(PeriodicTimer(clock, -1ms), std::invalid_argument);
}

TEST(PeriodicTimerTest, FirstDeadlineIsOnePeriodFromNow) {
  SimulatedClock clock(Timestamp::from_seconds(3.0));
  PeriodicTimer timer(clock, 16ms);
  EXPECT_EQ(timer.next_deadline(), Timestamp::from_seconds(3.016));
  EXPECT_EQ(timer.period(), 16ms);
}

TEST(PeriodicTimerTest, WaitNextOnASimulatedClockProducesExactDeadlines) {
  // 60 Hz does not divide a second into whole milliseconds; integer nanoseconds keep it exact.
  const Duration period = 16'666'667ns;
  SimulatedClock clock;
  PeriodicTimer timer(clock, period);

  std::atomic<int> ticks{0};
  std::promise<std::vector<Timestamp>> done;
  std::future<std::vector<Timestamp>> result = done.get_future();
  std::thread loop([&] {
    std::vector<Timestamp> woke;
    while (woke.size() < 5 && timer.wait_next()) {
      woke.push_back(clock.now());
      ++ticks;
    }
    done.set_value(woke);
  });
  // On a failed ASSERT: release the loop and join it instead of terminating or hanging.
  struct StopAndJoin {
    Clock& clock;
    std::thread& thread;
    ~StopAndJoin() {
      clock.stop();
      if (thread.joinable()) thread.join();
    }
  } stop_and_join{clock, loop};

  // Lockstep driver: once the loop has handled tick i-1 and sleeps again, advance by one period.
  for (int i = 1; i <= 5; ++i) {
    ASSERT_TRUE(wait_until([&] { return ticks.load() == i - 1; })) << "tick " << i;
    ASSERT_TRUE(clock.wait_for_sleepers(1, kWakeTimeout)) << "tick " << i;
    clock.advance(period);
  }
  ASSERT_EQ(result.wait_for(kWakeTimeout), std::future_status::ready);

  const std::vector<Timestamp> woke = result.get();
  ASSERT_EQ(woke.size(), 5u);
  for (int i = 0; i < 5; ++i) EXPECT_EQ(woke[i], Timestamp{} + period * (i + 1)) << i;
  EXPECT_EQ(timer.next_deadline(), Timestamp{} + period * 6);
  EXPECT_EQ(timer.ticks(), 5u);
  EXPECT_EQ(timer.missed_ticks(), 0u);
}

TEST(PeriodicTimerTest, LateWakeUpsDoNotShiftThePhase) {
  SimulatedClock clock;
  PeriodicTimer timer(clock, 10ms, Timestamp{} + 10ms);
  clock.set(Timestamp{} + 13ms);  // 3 ms late
  ASSERT_TRUE(timer.wait_next());
  EXPECT_EQ(timer.next_deadline(), Timestamp{} + 20ms);  // not 23 ms
  EXPECT_EQ(timer.missed_ticks(), 0u);
}

TEST(PeriodicTimerTest, MissedDeadlinesAreSkippedNotBurst) {
  SimulatedClock clock;
  PeriodicTimer timer(clock, 10ms, Timestamp{} + 10ms);
  clock.set(Timestamp{} + 35ms);  // deadlines 20 and 30 ms passed while we were busy
  ASSERT_TRUE(timer.wait_next());
  EXPECT_EQ(timer.missed_ticks(), 2u);
  EXPECT_EQ(timer.next_deadline(), Timestamp{} + 40ms);
}

TEST(PeriodicTimerTest, ADeadlineDueExactlyNowIsNotMissed) {
  SimulatedClock clock;
  PeriodicTimer timer(clock, 10ms, Timestamp{} + 10ms);
  clock.set(Timestamp{} + 20ms);
  ASSERT_TRUE(timer.wait_next());  // the 10 ms tick
  EXPECT_EQ(timer.missed_ticks(), 0u);
  EXPECT_EQ(timer.next_deadline(), Timestamp{} + 20ms);
  ASSERT_TRUE(timer.wait_next());  // the 20 ms tick, at once
  EXPECT_EQ(timer.next_deadline(), Timestamp{} + 30ms);
}

TEST(PeriodicTimerTest, PollFiresOncePerDeadline) {
  SimulatedClock clock;
  PeriodicTimer timer(clock, 1s, Timestamp{} + 1s);
  EXPECT_FALSE(timer.poll(Timestamp{} + 999ms));
  EXPECT_TRUE(timer.poll(Timestamp{} + 1s));
  EXPECT_FALSE(timer.poll(Timestamp{} + 1500ms));
  EXPECT_TRUE(timer.poll(Timestamp{} + 4500ms));
  EXPECT_EQ(timer.missed_ticks(), 2u);  // 3 s and 4 s
  EXPECT_EQ(timer.next_deadline(), Timestamp{} + 5s);
  EXPECT_EQ(timer.ticks(), 2u);
}

TEST(PeriodicTimerTest, WaitNextReturnsFalseOnceTheClockIsStopped) {
  SimulatedClock clock;
  PeriodicTimer timer(clock, 10ms);
  std::future<bool> ticked = std::async(std::launch::async, [&] { return timer.wait_next(); });
  struct StopOnExit {
    Clock& clock;
    ~StopOnExit() { clock.stop(); }
  } stop_on_exit{clock};
  ASSERT_TRUE(clock.wait_for_sleepers(1, kWakeTimeout));
  clock.stop();
  ASSERT_EQ(ticked.wait_for(kWakeTimeout), std::future_status::ready);
  EXPECT_FALSE(ticked.get());
  EXPECT_EQ(timer.next_deadline(), Timestamp{} + 10ms);  // schedule unchanged
}

TEST(PeriodicTimerTest, ResetRestartsTheSchedule) {
  SimulatedClock clock;
  PeriodicTimer timer(clock, 10ms);
  timer.reset(Timestamp{} + 3ms);
  EXPECT_EQ(timer.next_deadline(), Timestamp{} + 3ms);
}

}  // namespace
}  // namespace ssl::time
