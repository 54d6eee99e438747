// When packets leave: inputs at once while the token bucket allows, never above the radio's rate, at
// most one period late; the heartbeat every period when nothing arrives; safety stops at once. Times are
// exact (integer nanoseconds on a SimulatedClock, stepped by the test).
#include "services/robot_link/core/send_schedule.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <optional>
#include <random>
#include <vector>

#include "libs/time/clock.h"

namespace ssl::robot_link {
namespace {

using std::chrono::microseconds;
using std::chrono::milliseconds;
using Waiting = SendSchedule::Waiting;

constexpr time::Duration kPeriod = milliseconds(10);  // a 100 Hz radio
const time::Timestamp kStart = time::Timestamp::from_milliseconds(7'000'000);

/// Drives a schedule like robot_link's loop: at each step of the clock, sends while a packet is due.
class Link {
 public:
  Link() : schedule_(kPeriod, kStart) {}

  /// Sends what is due at the clock's time (an input pending since `arrived`, or the heartbeat).
  void run_until(time::Timestamp end) {
    while (true) {
      const time::Timestamp due = schedule_.next_send(waiting());
      const time::Timestamp at = std::max(due, clock_.now());
      if (at > end) break;
      clock_.set(at);
      sent_.push_back({at, waiting()});
      if (input_since_) input_waits_.push_back(at - *input_since_);
      input_since_.reset();
      stop_ = false;
      schedule_.on_sent(at);
    }
    clock_.set(end);
  }
  void arrive() {
    if (!input_since_) input_since_ = clock_.now();
  }
  void stop() {
    stop_ = true;
    arrive();
  }
  Waiting waiting() const {
    if (stop_) return Waiting::kStop;
    return input_since_ ? Waiting::kInput : Waiting::kNothing;
  }

  struct Sent {
    time::Timestamp at;
    Waiting waiting;
  };
  time::SimulatedClock& clock() { return clock_; }
  const std::vector<Sent>& sent() const { return sent_; }
  const std::vector<time::Duration>& input_waits() const { return input_waits_; }
  const SendSchedule& schedule() const { return schedule_; }

 private:
  time::SimulatedClock clock_{kStart};
  SendSchedule schedule_;
  std::optional<time::Timestamp> input_since_;
  bool stop_ = false;
  std::vector<Sent> sent_;
  std::vector<time::Duration> input_waits_;
};

time::Timestamp at_ms(std::int64_t ms) { return kStart + milliseconds(ms); }
time::Timestamp at_us(std::int64_t us) { return kStart + microseconds(us); }

TEST(SendScheduleTest, HeartbeatEveryPeriodExactlyWhenNothingArrives) {
  Link link;
  link.run_until(at_ms(95));
  ASSERT_EQ(link.sent().size(), 10u);
  for (std::size_t i = 0; i < link.sent().size(); ++i) {
    EXPECT_EQ(link.sent()[i].at, at_ms(static_cast<std::int64_t>(10 * i))) << "heartbeat " << i;
    EXPECT_EQ(link.sent()[i].waiting, Waiting::kNothing);
  }
  EXPECT_EQ(link.schedule().next_send(Waiting::kNothing), at_ms(100));
}

TEST(SendScheduleTest, AnInputAfterIdleGoesOutAtOnceAndAlsoRightAfterAHeartbeat) {
  Link link;
  link.run_until(at_us(33'333));  // heartbeats at 0, 10, 20, 30 ms
  link.arrive();
  link.run_until(at_us(33'333));
  ASSERT_EQ(link.sent().size(), 5u);
  EXPECT_EQ(link.sent().back().at, at_us(33'333)) << "no wait for the fixed grid";
  EXPECT_EQ(link.sent().back().waiting, Waiting::kInput);
  // The heartbeat waits for a full bucket: the one at 30 ms and this input took a token each.
  EXPECT_EQ(link.schedule().next_send(Waiting::kNothing), at_ms(50));

  link.run_until(at_ms(50));  // that heartbeat leaves the reserve token...
  EXPECT_EQ(link.sent().back().at, at_ms(50));
  EXPECT_EQ(link.sent().back().waiting, Waiting::kNothing);
  link.arrive();              // ...for an input arriving in the same nanosecond
  link.run_until(at_ms(50));
  EXPECT_EQ(link.sent().back().at, at_ms(50));
  EXPECT_EQ(link.sent().back().waiting, Waiting::kInput);
}

TEST(SendScheduleTest, ABurstOfArrivalsNeverExceedsTheRate) {
  Link link;
  link.run_until(at_ms(5));  // the start's heartbeat at 0; the bucket is full again at 10 ms
  link.run_until(at_ms(10));
  ASSERT_EQ(link.sent().size(), 2u);  // 0 and 10 ms
  // An input every 100 us for 200 ms (a flood: 10 kHz).
  for (std::int64_t us = 10'100; us <= 210'000; us += 100) {
    link.run_until(at_us(us));
    link.arrive();
    link.run_until(at_us(us));
  }
  // The first at once (the heartbeat at 10 ms left the reserve token), then one per period exactly.
  std::vector<time::Timestamp> inputs;
  for (const auto& sent : link.sent()) {
    if (sent.waiting == Waiting::kInput) inputs.push_back(sent.at);
  }
  ASSERT_GE(inputs.size(), 20u);
  EXPECT_EQ(inputs[0], at_us(10'100));
  for (std::size_t i = 2; i < inputs.size(); ++i) EXPECT_EQ(inputs[i] - inputs[i - 1], kPeriod) << i;
  // Any window of length T holds at most kBurst + T / period packets.
  const auto& sent = link.sent();
  for (std::size_t i = 0; i < sent.size(); ++i) {
    for (std::size_t j = i; j < sent.size(); ++j) {
      const auto window = sent[j].at - sent[i].at;
      EXPECT_LE(static_cast<std::int64_t>(j - i + 1), SendSchedule::kBurst + window / kPeriod) << i << ".." << j;
    }
  }
}

TEST(SendScheduleTest, AnInputWaitsAtMostOnePeriodWhateverTheArrivals) {
  Link link;
  std::mt19937 random(17);
  std::uniform_int_distribution<std::int64_t> gap_us(1, 25'000);
  std::int64_t us = 0;
  while (us < 5'000'000) {
    us += gap_us(random);
    link.run_until(at_us(us));
    link.arrive();
  }
  link.run_until(at_us(us + 20'000));
  ASSERT_GT(link.input_waits().size(), 300u);
  const auto longest = *std::max_element(link.input_waits().begin(), link.input_waits().end());
  EXPECT_LE(longest, kPeriod);
  EXPECT_GT(longest, milliseconds(5)) << "the flood parts did have to wait";
  // And packets are never more than kBurst periods apart.
  for (std::size_t i = 1; i < link.sent().size(); ++i) {
    EXPECT_LE(link.sent()[i].at - link.sent()[i - 1].at, SendSchedule::kBurst * kPeriod) << i;
  }
}

TEST(SendScheduleTest, InputsSlowerThanTheRateNeverWaitEvenBetweenHeartbeats) {
  // One camera at 75 Hz: an input every 13.333 ms, with a heartbeat due in each gap (10 ms).
  Link link;
  for (std::int64_t frame = 0; frame < 300; ++frame) {
    link.run_until(at_us(frame * 13'333));
    link.arrive();
  }
  link.run_until(at_us(300 * 13'333));
  ASSERT_EQ(link.input_waits().size(), 300u);
  for (const auto wait : link.input_waits()) EXPECT_EQ(wait, time::Duration::zero());
}

TEST(SendScheduleTest, HeartbeatAfterAnInputThatEmptiedTheBucketWaitsForTheReserveToken) {
  Link link;
  link.run_until(at_ms(0));  // heartbeat at 0: one token left
  link.arrive();
  link.run_until(at_us(1));  // input at 0: none left; one again at 10 ms, two at 20 ms
  ASSERT_EQ(link.sent().size(), 2u);
  EXPECT_EQ(link.schedule().next_send(Waiting::kNothing), at_ms(20));
  EXPECT_EQ(link.schedule().next_send(Waiting::kInput), at_ms(10));
  link.run_until(at_ms(20) - time::Duration(1));
  EXPECT_EQ(link.sent().size(), 2u);
  link.run_until(at_ms(20));
  EXPECT_EQ(link.sent().back().at, at_ms(20));
}

TEST(SendScheduleTest, AStopGoesOutAtOnceWithAnEmptyBucketAndIsPaidBack) {
  Link link;
  link.run_until(at_ms(0));
  link.arrive();
  link.run_until(at_ms(1));  // the bucket is empty: a token again at 10 ms
  EXPECT_EQ(link.schedule().next_send(Waiting::kInput), at_ms(10));
  link.stop();
  link.run_until(at_ms(2));
  ASSERT_EQ(link.sent().size(), 3u);
  EXPECT_EQ(link.sent().back().at, at_ms(1));
  EXPECT_EQ(link.sent().back().waiting, Waiting::kStop);
  // Paid back: the next input waits for the token after the one the stop took.
  link.arrive();
  EXPECT_EQ(link.schedule().next_send(Waiting::kInput), at_ms(20));
  link.run_until(at_ms(20));
  EXPECT_EQ(link.sent().back().at, at_ms(20));
}

TEST(SendScheduleTest, RejectsANonPositivePeriod) {
  EXPECT_THROW(SendSchedule(time::Duration::zero(), kStart), std::invalid_argument);
}

}  // namespace
}  // namespace ssl::robot_link
