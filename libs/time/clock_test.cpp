#include "libs/time/clock.h"

#include <gtest/gtest.h>

#include <chrono>
#include <future>

namespace ssl::time {
namespace {

using namespace std::chrono_literals;

// Generous bound for "a woken thread reports back"; only reached when the test fails.
constexpr auto kWakeTimeout = 10s;
// Short real-time window in which a thread that should stay asleep must not report back. A sleeper that
// is woken wrongly would report within microseconds, so this cannot produce a false pass in practice.
constexpr auto kStillAsleepWindow = 50ms;

// Stops the clock when the test leaves scope. Declared AFTER the futures of sleeping threads, it runs
// before their destructors (which wait for the thread), so a failed ASSERT never hangs the test.
struct StopOnExit {
  Clock& clock;
  ~StopOnExit() { clock.stop(); }
};

TEST(SimulatedClockTest, StandsStillUntilAdvanced) {
  SimulatedClock clock(Timestamp::from_seconds(100.0));
  EXPECT_EQ(clock.now(), Timestamp::from_seconds(100.0));
  clock.advance(16ms);
  EXPECT_EQ(clock.now(), Timestamp::from_seconds(100.016));
  clock.advance(-1s);  // ignored: advance never goes backwards
  EXPECT_EQ(clock.now(), Timestamp::from_seconds(100.016));
  clock.set(Timestamp::from_seconds(5.0));
  EXPECT_EQ(clock.now(), Timestamp::from_seconds(5.0));
}

TEST(SimulatedClockTest, SleepUntilAPastOrPresentDeadlineReturnsAtOnce) {
  SimulatedClock clock(Timestamp::from_seconds(1.0));
  EXPECT_TRUE(clock.sleep_until(Timestamp::from_seconds(0.5)));
  EXPECT_TRUE(clock.sleep_until(Timestamp::from_seconds(1.0)));
  EXPECT_TRUE(clock.sleep_for(0s));
}

TEST(SimulatedClockTest, AdvanceWakesASleeperOnlyOnceItsDeadlineIsReached) {
  SimulatedClock clock;
  const Timestamp deadline = Timestamp{} + 100ms;
  std::future<Timestamp> woke = std::async(
      std::launch::async, [&] { return clock.sleep_until(deadline) ? clock.now() : Timestamp::min(); });
  StopOnExit stop_on_exit{clock};

  ASSERT_TRUE(clock.wait_for_sleepers(1, kWakeTimeout));
  clock.advance(60ms);  // not enough
  EXPECT_EQ(woke.wait_for(kStillAsleepWindow), std::future_status::timeout);
  EXPECT_EQ(clock.sleeper_count(), 1u);

  clock.advance(40ms);  // exactly at the deadline
  ASSERT_EQ(woke.wait_for(kWakeTimeout), std::future_status::ready);
  EXPECT_EQ(woke.get(), deadline);
  EXPECT_EQ(clock.sleeper_count(), 0u);
}

TEST(SimulatedClockTest, SetForwardWakesSleepers) {
  SimulatedClock clock;
  std::future<bool> woke = std::async(std::launch::async, [&] { return clock.sleep_for(1s); });
  StopOnExit stop_on_exit{clock};
  ASSERT_TRUE(clock.wait_for_sleepers(1, kWakeTimeout));
  clock.set(Timestamp::from_seconds(5.0));
  ASSERT_EQ(woke.wait_for(kWakeTimeout), std::future_status::ready);
  EXPECT_TRUE(woke.get());
}

TEST(SimulatedClockTest, StopReleasesEverySleeperWithFalse) {
  SimulatedClock clock;
  std::future<bool> first = std::async(std::launch::async, [&] { return clock.sleep_for(1h); });
  std::future<bool> second =
      std::async(std::launch::async, [&] { return clock.sleep_until(Timestamp::max()); });
  StopOnExit stop_on_exit{clock};
  ASSERT_TRUE(clock.wait_for_sleepers(2, kWakeTimeout));

  clock.stop();
  ASSERT_EQ(first.wait_for(kWakeTimeout), std::future_status::ready);
  ASSERT_EQ(second.wait_for(kWakeTimeout), std::future_status::ready);
  EXPECT_FALSE(first.get());
  EXPECT_FALSE(second.get());
  EXPECT_TRUE(clock.stopped());
  // Later sleeps return at once, even for deadlines already reached.
  EXPECT_FALSE(clock.sleep_for(1h));
  EXPECT_FALSE(clock.sleep_until(Timestamp::min()));
}

TEST(SimulatedClockTest, WaitForSleepersTimesOutWhenNobodySleeps) {
  SimulatedClock clock;
  EXPECT_FALSE(clock.wait_for_sleepers(1, 10ms));
}

TEST(RealClockTest, IsUnixTime) {
  RealClock clock;
  // Any host running this test is past 2020-01-01 (1577836800 s) and before 2100.
  EXPECT_GT(clock.now(), Timestamp::from_seconds(1577836800.0));
  EXPECT_LT(clock.now(), Timestamp::from_seconds(4102444800.0));
}

TEST(RealClockTest, SleepForReachesItsDeadline) {
  RealClock clock;
  const Timestamp start = clock.now();
  EXPECT_TRUE(clock.sleep_for(5ms));
  EXPECT_GE(clock.now() - start, 5ms);
}

TEST(RealClockTest, StopReleasesASleeper) {
  RealClock clock;
  std::future<bool> woke = std::async(std::launch::async, [&] { return clock.sleep_for(1h); });
  clock.stop();
  ASSERT_EQ(woke.wait_for(kWakeTimeout), std::future_status::ready);
  EXPECT_FALSE(woke.get());
}

TEST(MonotonicClockTest, NeverGoesBackwardsAndSleeps) {
  MonotonicClock clock;
  const Timestamp a = clock.now();
  EXPECT_TRUE(clock.sleep_until(a + 2ms));
  const Timestamp b = clock.now();
  EXPECT_GE(b - a, 2ms);
}

TEST(MonotonicClockTest, StopReleasesASleeper) {
  MonotonicClock clock;
  std::future<bool> woke = std::async(std::launch::async, [&] { return clock.sleep_for(1h); });
  clock.stop();
  ASSERT_EQ(woke.wait_for(kWakeTimeout), std::future_status::ready);
  EXPECT_FALSE(woke.get());
  EXPECT_TRUE(clock.stopped());
}

}  // namespace
}  // namespace ssl::time
