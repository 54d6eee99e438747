// The send loop on a simulated clock: it sleeps between heartbeats (every period when nothing arrives),
// new commands leave at once within the radio's rate, stops at once; the watchdog stops a robot whose
// planner went silent, shutdown sends stops; and the feedback throttle publishes changes at once and
// heartbeats otherwise.
#include "services/robot_link/adapter/link_runner.h"

#include <gtest/gtest.h>

#include <condition_variable>
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
    sent_.notify_all();
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
  /// Waits (real time, bounded) until `count` packets were sent.
  bool wait_for_sends(std::size_t count) const {
    std::unique_lock lock(mutex_);
    return sent_.wait_for(lock, std::chrono::seconds(5), [&] { return sends_.size() >= count; });
  }

 private:
  time::Clock& clock_;
  mutable std::mutex mutex_;
  mutable std::condition_variable sent_;
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

/// A runner on a simulated clock starting at `start`, sending into a FakeBackend.
struct RunnerRig {
  explicit RunnerRig(time::Timestamp start) : clock(start) {}
  time::SimulatedClock clock;
  FakeBackend backend{clock};
  InputMailbox mailbox;
  LinkRunner runner{test_config(), backend, mailbox};
};

TEST(RobotLinkRunnerTest, SleepsBetweenHeartbeatsEveryPeriodAndTheWatchdogStopsASilentPlanner) {
  const time::Timestamp start = time::Timestamp::from_milliseconds(5'000'000);
  RunnerRig rig(start);
  auto& [clock, backend, mailbox, runner] = rig;
  const RobotCommand command{.id = 2, .forward = 0.5};
  mailbox.on_commands(std::span(&command, 1), start);  // the planner's last sample, then silence

  std::thread worker([&] {
    runner.run(
        clock, [] { return true; }, {}, [&](time::Timestamp deadline) { return clock.sleep_until(deadline); }, {});
  });
  for (int ms = 1; ms <= 200; ++ms) {
    // The loop blocks on the clock between packets (a spinning loop would never be a sleeper).
    ASSERT_TRUE(clock.wait_for_sleepers(1, std::chrono::seconds(5))) << "at " << ms << " ms";
    clock.advance(milliseconds(1));
    // The packet due now has left before the clock moves on.
    if (ms % 10 == 0) {
      ASSERT_TRUE(backend.wait_for_sends(static_cast<std::size_t>(ms / 10 + 1))) << ms;
    }
  }
  ASSERT_TRUE(clock.wait_for_sleepers(1, std::chrono::seconds(5)));
  clock.stop();
  worker.join();

  const auto sends = backend.sends();
  ASSERT_EQ(sends.size(), 21u) << "the command at once, then a heartbeat every 10 ms";
  for (std::size_t i = 0; i < sends.size(); ++i) {
    EXPECT_EQ(sends[i].at, start + milliseconds(10 * static_cast<std::int64_t>(i))) << "packet " << i;
    ASSERT_EQ(sends[i].commands.size(), 1u);
    const OutgoingCommand& out = sends[i].commands[0];
    if (sends[i].at - start <= milliseconds(100)) {  // exactly 100 ms old is still fresh
      EXPECT_EQ(out.stop, StopReason::kNone) << "packet " << i;
      EXPECT_DOUBLE_EQ(out.command.forward, 0.5);
    } else {
      EXPECT_EQ(out.stop, StopReason::kStale) << "packet " << i;
      EXPECT_TRUE(is_stop(out.command));
    }
  }
}

TEST(RobotLinkRunnerTest, NewCommandsGoOutAtOnceWithinTheRadiosRateAndAtMostOnePeriodLate) {
  const time::Timestamp start = time::Timestamp::from_milliseconds(5'000'000);
  RunnerRig rig(start);
  auto& [clock, backend, mailbox, runner] = rig;
  const auto arrive = [&](double forward) {
    const RobotCommand command{.id = 2, .forward = forward};
    mailbox.on_commands(std::span(&command, 1), clock.now());
  };
  ASSERT_TRUE(runner.poll(clock.now()));  // the first poll sends (startup stops)
  EXPECT_EQ(runner.next_send(), start + milliseconds(10)) << "the heartbeat";

  // After idle: out in the same nanosecond, not at the next heartbeat.
  clock.advance(std::chrono::microseconds(3'333));
  arrive(0.1);
  EXPECT_EQ(runner.next_send(), start + milliseconds(10)) << "nothing polled the mailbox yet";
  const auto sent = runner.poll(clock.now());
  ASSERT_TRUE(sent);
  EXPECT_EQ(sent->cause, SendSchedule::Waiting::kInput);
  EXPECT_EQ(backend.sends().back().at, clock.now());
  EXPECT_DOUBLE_EQ(backend.sends().back().commands[0].command.forward, 0.1);

  // A flood (every 0.5 ms): the bucket is empty now; the newest command leaves at each token, exactly.
  clock.advance(std::chrono::microseconds(500));
  arrive(0.2);
  EXPECT_FALSE(runner.poll(clock.now()));
  const time::Timestamp token = runner.next_send();
  EXPECT_EQ(token, start + milliseconds(10)) << "the 100 Hz bucket's next token";
  while (clock.now() + std::chrono::microseconds(500) < token) {
    clock.advance(std::chrono::microseconds(500));
    arrive(0.3);
    EXPECT_FALSE(runner.poll(clock.now()));
  }
  clock.set(token - time::Duration(1));
  EXPECT_FALSE(runner.poll(clock.now()));
  clock.set(token);
  ASSERT_TRUE(runner.poll(clock.now()));
  EXPECT_DOUBLE_EQ(backend.sends().back().commands[0].command.forward, 0.3) << "the newest";
  // (The first poll had no robot to command: nothing reached the backend.)
  EXPECT_EQ(backend.sends().size(), 2u) << "the input at 3.3 ms, then the flood once: never above the rate";
  EXPECT_EQ(runner.next_send(), token + milliseconds(20)) << "nothing new: the heartbeat once the bucket is full";
}

TEST(RobotLinkRunnerTest, EstopAndHaltGoOutAtOnceEvenWhenTheRateIsUsedUp) {
  RunnerRig rig(time::Timestamp::from_milliseconds(1000));
  auto& [clock, backend, mailbox, runner] = rig;
  const RobotCommand command{.id = 4, .forward = 1};
  mailbox.on_commands(std::span(&command, 1), clock.now());
  ASSERT_TRUE(runner.poll(clock.now()));
  clock.advance(std::chrono::microseconds(100));
  mailbox.on_commands(std::span(&command, 1), clock.now());
  ASSERT_TRUE(runner.poll(clock.now()));  // the burst's second token: the bucket is empty now

  clock.advance(std::chrono::microseconds(100));
  mailbox.on_estop(true, "console", "test");
  auto stopped = runner.poll(clock.now());
  ASSERT_TRUE(stopped);
  EXPECT_EQ(stopped->cause, SendSchedule::Waiting::kStop);
  EXPECT_EQ(stopped->output.commands[0].stop, StopReason::kEstop);

  clock.advance(std::chrono::microseconds(100));
  mailbox.on_estop(false, "console", "clear");
  mailbox.on_referee(true);  // e-stop released and HALT in one go: still a new stop
  auto halted = runner.poll(clock.now());
  ASSERT_TRUE(halted);
  EXPECT_EQ(halted->cause, SendSchedule::Waiting::kStop);
  EXPECT_EQ(halted->output.commands[0].stop, StopReason::kHalt);

  clock.advance(std::chrono::microseconds(100));
  mailbox.on_referee(false);  // lifting HALT is no stop: it waits for a token
  EXPECT_FALSE(runner.poll(clock.now()));
  EXPECT_GT(runner.next_send(), clock.now());
}

TEST(RobotLinkRunnerTest, FinalStopStopsEveryKnownRobotAndEstopLatchesInTheMailbox) {
  RunnerRig rig(time::Timestamp::from_milliseconds(1000));
  auto& [clock, backend, mailbox, runner] = rig;
  const RobotCommand commands[] = {{.id = 1, .forward = 1}, {.id = 6, .left = 1}};
  mailbox.on_commands(commands, clock.now());
  TickResult running = runner.send(clock.now());
  ASSERT_EQ(running.output.commands.size(), 2u);
  EXPECT_EQ(running.output.commands[0].stop, StopReason::kNone);

  ASSERT_TRUE(runner.send_final_stop(clock.now()));
  const auto last = backend.sends().back();
  ASSERT_EQ(last.commands.size(), 2u);
  for (const auto& out : last.commands) EXPECT_TRUE(is_stop(out.command));

  mailbox.on_estop(true, "console", "test");
  mailbox.on_estop_writer_lost();
  mailbox.on_commands(commands, clock.now());
  EXPECT_EQ(runner.send(clock.now()).output.commands[0].stop, StopReason::kEstop);
  EXPECT_EQ(mailbox.snapshot().estop_writers_lost_while_engaged, 1u);
  mailbox.on_estop(false, "console", "clear");
  EXPECT_EQ(runner.send(clock.now()).output.commands[0].stop, StopReason::kNone);

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
