// The fixed-rate loop on a simulated clock: commands arriving with jitter still leave at exactly the
// configured rate, the watchdog stops a robot whose planner went silent, shutdown sends stops; and the
// feedback throttle publishes changes at once and heartbeats otherwise.
#include "services/robot_link/adapter/link_runner.h"

#include <gtest/gtest.h>

#include <condition_variable>
#include <random>
#include <thread>

namespace ssl::robot_link {
namespace {

using std::chrono::milliseconds;

/// Records what would have been sent, stamped with the clock's time at sending.
class FakeBackend final : public Backend {
 public:
  explicit FakeBackend(time::Clock& clock) : clock_(clock) {}

  Status send(std::span<const OutgoingCommand> commands) override {
    std::lock_guard lock(mutex_);
    sends_.push_back({clock_.now(), {commands.begin(), commands.end()}});
    return {};
  }
  std::vector<FeedbackReport> poll_feedback() override { return {}; }
  BackendCounters counters() const override { return {}; }
  std::string description() const override { return "fake"; }
  std::string last_error() const override { return ""; }

  struct Send {
    time::Timestamp at;
    std::vector<OutgoingCommand> commands;
  };
  std::vector<Send> sends() const {
    std::lock_guard lock(mutex_);
    return sends_;
  }

 private:
  time::Clock& clock_;
  mutable std::mutex mutex_;
  std::vector<Send> sends_;
};

CoreConfig test_config() {
  CoreConfig config;
  config.send_period = milliseconds(10);
  config.startup_stop = time::Duration::zero();
  config.limits.acc_speedup_absolute_max = 1000;
  config.limits.acc_brake_absolute_max = 1000;
  return config;
}

TEST(RobotLinkRunnerTest, SendsAtAFixedRateWhateverTheJitterOfIncomingCommandsAndStopsWhenTheyStop) {
  const time::Timestamp start = time::Timestamp::from_milliseconds(5'000'000);
  time::SimulatedClock clock(start);
  FakeBackend backend(clock);
  InputMailbox mailbox;
  LinkRunner runner(test_config(), backend, mailbox);

  std::mutex mutex;
  std::condition_variable ticked;
  int ticks = 0;
  std::thread worker([&] {
    runner.run(
        clock, [] { return true; }, {},
        [&](const TickResult&) {
          std::lock_guard lock(mutex);
          ++ticks;
          ticked.notify_all();
        });
  });
  const auto wait_for_ticks = [&](int count) {
    std::unique_lock lock(mutex);
    return ticked.wait_for(lock, std::chrono::seconds(5), [&] { return ticks >= count; });
  };
  ASSERT_TRUE(wait_for_ticks(1));

  // Planner samples at seeded, jittered times (3..45 ms apart) for 1.5 s, then silence.
  std::mt19937 random(99);
  std::uniform_int_distribution<int> gap(3, 45);
  std::vector<int> arrivals_ms;
  for (int t = 2; t < 1500; t += gap(random)) arrivals_ms.push_back(t);
  const int last_arrival_ms = arrivals_ms.back();

  std::size_t next = 0;
  for (int ms = 1; ms <= 2000; ++ms) {
    ASSERT_TRUE(clock.wait_for_sleepers(1, std::chrono::seconds(5)));
    clock.advance(milliseconds(1));
    while (next < arrivals_ms.size() && arrivals_ms[next] <= ms) {
      const RobotCommand command{.id = 2, .forward = 0.001 * static_cast<double>(next + 1)};
      mailbox.on_commands(std::span(&command, 1), clock.now());
      ++next;
    }
    if (ms % 10 == 0) {
      ASSERT_TRUE(wait_for_ticks(ms / 10 + 1)) << "tick at " << ms << " ms";
    }
  }
  ASSERT_TRUE(clock.wait_for_sleepers(1, std::chrono::seconds(5)));
  clock.stop();
  worker.join();

  const auto sends = backend.sends();
  // One send per 10 ms, on the period grid: nothing bunched after bursts, nothing skipped in gaps.
  ASSERT_GE(sends.size(), 200u);
  for (std::size_t i = 1; i < sends.size(); ++i) {
    EXPECT_EQ(sends[i].at - sends[i - 1].at, milliseconds(10)) << "send " << i;
  }
  bool stopped = false;
  time::Timestamp first_stop;
  for (const auto& send : sends) {
    ASSERT_EQ(send.commands.size(), 1u);
    const OutgoingCommand& out = send.commands[0];
    const auto since_start = std::chrono::duration_cast<milliseconds>(send.at - start).count();
    if (since_start <= last_arrival_ms + 100) {
      EXPECT_EQ(out.stop, StopReason::kNone) << "at " << since_start << " ms";
      EXPECT_GT(out.command.forward, 0) << "at " << since_start << " ms";
    } else {
      EXPECT_EQ(out.stop, StopReason::kStale) << "at " << since_start << " ms";
      EXPECT_TRUE(is_stop(out.command));
      if (!stopped) first_stop = send.at;
      stopped = true;
    }
  }
  ASSERT_TRUE(stopped);
  const auto silence = first_stop - (start + milliseconds(last_arrival_ms));
  EXPECT_GT(silence, milliseconds(100));
  EXPECT_LE(silence, milliseconds(110)) << "watchdog + at most one send period";
  EXPECT_EQ(runner.missed_ticks(), 0u);
}

TEST(RobotLinkRunnerTest, FinalStopStopsEveryKnownRobotAndEstopLatchesInTheMailbox) {
  time::SimulatedClock clock(time::Timestamp::from_milliseconds(1000));
  FakeBackend backend(clock);
  InputMailbox mailbox;
  LinkRunner runner(test_config(), backend, mailbox);
  const RobotCommand commands[] = {{.id = 1, .forward = 1}, {.id = 6, .left = 1}};
  mailbox.on_commands(commands, clock.now());
  TickResult running = runner.tick(clock.now());
  ASSERT_EQ(running.output.commands.size(), 2u);
  EXPECT_EQ(running.output.commands[0].stop, StopReason::kNone);

  ASSERT_TRUE(runner.send_final_stop(clock.now()));
  const auto last = backend.sends().back();
  ASSERT_EQ(last.commands.size(), 2u);
  for (const auto& out : last.commands) EXPECT_TRUE(is_stop(out.command));

  mailbox.on_estop(true, "console", "test");
  mailbox.on_estop_writer_lost();
  mailbox.on_commands(commands, clock.now());
  EXPECT_EQ(runner.tick(clock.now()).output.commands[0].stop, StopReason::kEstop);
  EXPECT_EQ(mailbox.snapshot().estop_writers_lost_while_engaged, 1u);
  mailbox.on_estop(false, "console", "clear");
  EXPECT_EQ(runner.tick(clock.now()).output.commands[0].stop, StopReason::kNone);

  mailbox.on_wrong_team();
  EXPECT_EQ(mailbox.snapshot().wrong_team, 1u);
}

TEST(RobotLinkFeedbackThrottleTest, ChangesGoOutAtOnceAndUnchangedFeedbackAtTheHeartbeat) {
  FeedbackThrottle throttle(milliseconds(100));
  const auto t = [](int ms) { return time::Timestamp::from_milliseconds(ms); };
  const FeedbackReport contact{.robot_id = 3, .ball_in_dribbler = true};
  EXPECT_EQ(throttle.update(std::span(&contact, 1), t(0)).size(), 1u);
  EXPECT_TRUE(throttle.update(std::span(&contact, 1), t(10)).empty()) << "unchanged, before the heartbeat";
  EXPECT_EQ(throttle.update(std::span(&contact, 1), t(100)).size(), 1u) << "heartbeat";
  EXPECT_TRUE(throttle.update({}, t(300)).empty()) << "a silent robot is not republished";

  const FeedbackReport battery{.robot_id = 3, .battery_voltage = 15.9, .link_quality = 0.8};
  const auto merged = throttle.update(std::span(&battery, 1), t(310));
  ASSERT_EQ(merged.size(), 1u);
  EXPECT_EQ(merged[0].ball_in_dribbler, true) << "fields a report leaves unset keep their last value";
  EXPECT_EQ(merged[0].battery_voltage, 15.9);
  ASSERT_EQ(throttle.link_quality().size(), 1u);
  EXPECT_EQ(throttle.link_quality()[0].first, 3u);

  const FeedbackReport lost{.robot_id = 3, .ball_in_dribbler = false};
  EXPECT_EQ(throttle.update(std::span(&lost, 1), t(311)).size(), 1u) << "a change goes out at once";
}

}  // namespace
}  // namespace ssl::robot_link
