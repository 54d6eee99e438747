// The safety core: watchdog timing, HALT and e-stop overrides, the e-stop latch, limits and clamping with
// their counters, and a fixed output per tick whatever the timing of the inputs.
#include "services/robot_link/core/robot_link_core.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>

namespace ssl::robot_link {
namespace {

using std::chrono::milliseconds;

constexpr double kInf = std::numeric_limits<double>::infinity();
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

time::Timestamp at_ms(std::int64_t ms) { return time::Timestamp::from_milliseconds(1'000'000 + ms); }

/// Limits loose enough that acceleration never interferes unless a test wants it to.
CoreConfig config_without_ramps() {
  CoreConfig config;
  config.limits.acc_speedup_absolute_max = 1000;
  config.limits.acc_brake_absolute_max = 1000;
  config.limits.acc_speedup_angular_max = 10000;
  config.limits.acc_brake_angular_max = 10000;
  config.startup_stop = time::Duration::zero();
  return config;
}

RobotCommand forward(std::uint32_t id, double speed) { return RobotCommand{.id = id, .forward = speed}; }

const OutgoingCommand* find(const TickOutput& output, std::uint32_t id) {
  for (const OutgoingCommand& out : output.commands) {
    if (out.command.id == id) return &out;
  }
  return nullptr;
}

TEST(RobotLinkWatchdogTest, CommandOlderThan100MsIsStoppedAnd99MsIsNot) {
  RobotLinkCore core(config_without_ramps());
  CommandTable table;
  const RobotCommand busy{
      .id = 0, .forward = 1.0, .kick = KickType::kFlat, .kick_speed = 3.0, .dribbler_rpm = 5000};
  table.update(std::span(&busy, 1), at_ms(0));

  TickOutput fresh = core.step({.latest = table.latest()}, at_ms(99));
  ASSERT_EQ(fresh.commands.size(), 1u);
  EXPECT_EQ(fresh.commands[0].stop, StopReason::kNone);
  EXPECT_DOUBLE_EQ(fresh.commands[0].command.forward, 1.0);
  EXPECT_EQ(fresh.commands[0].command.kick, KickType::kFlat);
  EXPECT_EQ(core.counters().stale_robots, 0u);

  TickOutput still_fresh = core.step({.latest = table.latest()}, at_ms(100));  // exactly 100 ms: fresh
  EXPECT_EQ(still_fresh.commands[0].stop, StopReason::kNone);

  TickOutput stale = core.step({.latest = table.latest()}, at_ms(101));
  ASSERT_EQ(stale.commands.size(), 1u);
  EXPECT_EQ(stale.commands[0].stop, StopReason::kStale);
  EXPECT_TRUE(is_stop(stale.commands[0].command)) << "zero velocity, dribbler and kicker off";
  EXPECT_EQ(stale.commands[0].command.id, 0u);
  EXPECT_EQ(core.counters().stale_robots, 1u);
  EXPECT_EQ(core.counters().stale_events, 1u);
  EXPECT_EQ(core.counters().stale_robot_ticks, 1u);

  // Stays stopped (and in the output) until a fresh command arrives; one stale event, many stale ticks.
  (void)core.step({.latest = table.latest()}, at_ms(500));
  EXPECT_EQ(core.counters().stale_events, 1u);
  EXPECT_EQ(core.counters().stale_robot_ticks, 2u);
  table.update(std::span(&busy, 1), at_ms(510));
  TickOutput again = core.step({.latest = table.latest()}, at_ms(511));
  EXPECT_EQ(again.commands[0].stop, StopReason::kNone);
  EXPECT_DOUBLE_EQ(again.commands[0].command.forward, 1.0);
}

TEST(RobotLinkWatchdogTest, EachRobotHasItsOwnWatchdog) {
  RobotLinkCore core(config_without_ramps());
  CommandTable table;
  const RobotCommand both[] = {forward(1, 0.5), forward(4, 0.7)};
  table.update(both, at_ms(0));
  const RobotCommand only_four[] = {forward(4, 0.8)};
  table.update(only_four, at_ms(60));  // the planner stopped commanding robot 1

  TickOutput output = core.step({.latest = table.latest()}, at_ms(150));
  ASSERT_EQ(output.commands.size(), 2u);
  EXPECT_EQ(find(output, 1)->stop, StopReason::kStale);
  EXPECT_EQ(find(output, 4)->stop, StopReason::kNone);
  EXPECT_DOUBLE_EQ(find(output, 4)->command.forward, 0.8);
  EXPECT_EQ(core.counters().stale_robots, 1u);
  EXPECT_EQ(core.counters().fresh_robots, 1u);
}

TEST(RobotLinkWatchdogTest, TimeoutComesFromConfig) {
  CoreConfig config = config_without_ramps();
  config.command_timeout = milliseconds(30);
  RobotLinkCore core(config);
  CommandTable table;
  const RobotCommand command = forward(2, 1.0);
  table.update(std::span(&command, 1), at_ms(0));
  EXPECT_EQ(core.step({.latest = table.latest()}, at_ms(30)).commands[0].stop, StopReason::kNone);
  EXPECT_EQ(core.step({.latest = table.latest()}, at_ms(31)).commands[0].stop, StopReason::kStale);
}

TEST(RobotLinkOverrideTest, HaltStopsEveryRobotWhateverThePlannerSays) {
  RobotLinkCore core(config_without_ramps());
  CommandTable table;
  const RobotCommand commands[] = {
      forward(0, 2.0),
      RobotCommand{.id = 3, .angular = 4, .kick = KickType::kChip, .kick_speed = 3, .chip_angle = 0.5}};
  table.update(commands, at_ms(0));
  TickOutput halted = core.step({.latest = table.latest(), .halt = true}, at_ms(10));
  ASSERT_EQ(halted.commands.size(), 2u);
  for (const OutgoingCommand& out : halted.commands) {
    EXPECT_EQ(out.stop, StopReason::kHalt);
    EXPECT_TRUE(is_stop(out.command));
  }
  EXPECT_EQ(core.counters().halted_ticks, 1u);

  // Fresh commands during HALT change nothing; lifting HALT lets them through.
  table.update(commands, at_ms(15));
  EXPECT_EQ(core.step({.latest = table.latest(), .halt = true}, at_ms(20)).commands[0].stop,
            StopReason::kHalt);
  TickOutput running = core.step({.latest = table.latest(), .halt = false}, at_ms(30));
  EXPECT_EQ(running.commands[0].stop, StopReason::kNone);
  EXPECT_DOUBLE_EQ(running.commands[0].command.forward, 2.0);
  EXPECT_EQ(core.counters().halted_ticks, 2u);
}

TEST(RobotLinkOverrideTest, EstopOverridesEverythingIncludingHaltAndFreshCommands) {
  RobotLinkCore core(config_without_ramps());
  CommandTable table;
  const RobotCommand command = forward(5, 1.5);
  table.update(std::span(&command, 1), at_ms(0));
  TickOutput output = core.step({.latest = table.latest(), .halt = true, .estop_engaged = true}, at_ms(1));
  ASSERT_EQ(output.commands.size(), 1u);
  EXPECT_EQ(output.commands[0].stop, StopReason::kEstop);
  EXPECT_TRUE(is_stop(output.commands[0].command));
  EXPECT_EQ(core.counters().estop_ticks, 1u);
  EXPECT_EQ(core.counters().halted_ticks, 0u);  // counted under the stronger reason only
}

TEST(RobotLinkEstopLatchTest, EngagedStaysEngagedThroughLivelinessLossAndNewCommands) {
  EstopLatch latch;
  EXPECT_FALSE(latch.engaged()) << "no e-stop source at all must not block a match";
  latch.on_sample(true, "sslctl@42", "robot 3 on fire");
  EXPECT_TRUE(latch.engaged());
  EXPECT_EQ(latch.source(), "sslctl@42");
  EXPECT_EQ(latch.reason(), "robot 3 on fire");

  latch.on_writer_lost();  // the console crashed / the button's cable was cut
  EXPECT_TRUE(latch.engaged());
  EXPECT_EQ(latch.writers_lost_while_engaged(), 1u);

  // The planner keeps sending: the core still stops every robot.
  RobotLinkCore core(config_without_ramps());
  CommandTable table;
  for (int tick = 0; tick < 20; ++tick) {
    const RobotCommand command = forward(0, 1.0);
    table.update(std::span(&command, 1), at_ms(tick * 10));
    TickOutput output =
        core.step({.latest = table.latest(), .estop_engaged = latch.engaged()}, at_ms(tick * 10 + 1));
    ASSERT_EQ(output.commands.size(), 1u);
    EXPECT_EQ(output.commands[0].stop, StopReason::kEstop) << "tick " << tick;
  }
  latch.on_sample(true, "console", "again");  // repeated engagement is not a new engagement
  EXPECT_EQ(latch.engagements(), 1u);

  latch.on_sample(false, "sslctl@43", "all clear");
  EXPECT_FALSE(latch.engaged());
  EXPECT_EQ(latch.releases(), 1u);
  const RobotCommand command = forward(0, 1.0);
  table.update(std::span(&command, 1), at_ms(300));
  TickOutput released = core.step({.latest = table.latest(), .estop_engaged = latch.engaged()}, at_ms(301));
  EXPECT_EQ(released.commands[0].stop, StopReason::kNone);
}

TEST(RobotLinkEstopLatchTest, LivelinessLossWhileReleasedChangesNothing) {
  EstopLatch latch;
  latch.on_sample(false, "console", "");
  latch.on_writer_lost();
  EXPECT_FALSE(latch.engaged());
  EXPECT_EQ(latch.writers_lost_while_engaged(), 0u);
}

TEST(RobotLinkLimitsTest, NanAndInfinityBecomeZeroAndAreCounted) {
  RobotLinkCore core(config_without_ramps());
  CommandTable table;
  const RobotCommand bad{.id = 1,
                         .forward = kNaN,
                         .left = kInf,
                         .angular = -kInf,
                         .kick = KickType::kFlat,
                         .kick_speed = kNaN,
                         .dribbler_rpm = kNaN};
  table.update(std::span(&bad, 1), at_ms(0));
  TickOutput output = core.step({.latest = table.latest()}, at_ms(1));
  ASSERT_EQ(output.commands.size(), 1u);
  const RobotCommand& sent = output.commands[0].command;
  EXPECT_EQ(sent.forward, 0);
  EXPECT_EQ(sent.left, 0);
  EXPECT_EQ(sent.angular, 0);
  EXPECT_EQ(sent.kick, KickType::kNone) << "a kick of speed 0 is no kick";
  EXPECT_EQ(sent.kick_speed, 0);
  EXPECT_EQ(sent.dribbler_rpm, 0);
  EXPECT_EQ(core.counters().non_finite_values, 5u);
  EXPECT_EQ(core.counters().clamped_values, 5u);
}

TEST(RobotLinkLimitsTest, TooFastIsScaledToTheSpecKeepingDirection) {
  CoreConfig config = config_without_ramps();
  config.limits.vel_absolute_max = 2.0;
  config.limits.vel_angular_max = 5.0;
  RobotLinkCore core(config);
  CommandTable table;
  const RobotCommand fast{.id = 2, .forward = 3.0, .left = 4.0, .angular = -9.0};  // 5 m/s
  table.update(std::span(&fast, 1), at_ms(0));
  const TickOutput output = core.step({.latest = table.latest()}, at_ms(1));
  const RobotCommand& sent = output.commands[0].command;
  EXPECT_NEAR(sent.forward, 1.2, 1e-12);
  EXPECT_NEAR(sent.left, 1.6, 1e-12);
  EXPECT_DOUBLE_EQ(sent.angular, -5.0);
  EXPECT_EQ(core.counters().clamped_values, 2u);
  EXPECT_EQ(core.counters().non_finite_values, 0u);
}

TEST(RobotLinkLimitsTest, TooFastKickAndBadChipAndDribblerAreClamped) {
  CoreConfig config = config_without_ramps();
  config.limits.max_linear_kick_speed = 6.5;
  config.limits.max_chip_kick_speed = 5.0;
  config.limits.max_chip_angle = 1.0;
  config.limits.max_dribbler_rpm = 10000;
  RobotLinkCore core(config);
  CommandTable table;
  const RobotCommand commands[] = {
      RobotCommand{.id = 0, .kick = KickType::kFlat, .kick_speed = 12.0, .chip_angle = 0.7},
      RobotCommand{
          .id = 1, .kick = KickType::kChip, .kick_speed = 8.0, .chip_angle = 2.0, .dribbler_rpm = 30000},
      RobotCommand{.id = 2, .kick = KickType::kFlat, .kick_speed = -1.0, .dribbler_rpm = -5},
      RobotCommand{.id = 3, .kick = KickType::kNone, .kick_speed = 99.0},  // ignored, not clamped
      RobotCommand{
          .id = 4, .kick = KickType::kChip, .kick_speed = 4.0, .chip_angle = 0.5, .dribbler_rpm = 3000},
  };
  table.update(commands, at_ms(0));
  TickOutput output = core.step({.latest = table.latest()}, at_ms(1));
  ASSERT_EQ(output.commands.size(), 5u);
  EXPECT_EQ(output.commands[0].command.kick, KickType::kFlat);
  EXPECT_DOUBLE_EQ(output.commands[0].command.kick_speed, 6.5);
  EXPECT_EQ(output.commands[0].command.chip_angle, 0) << "a flat kick has no chip angle";
  EXPECT_DOUBLE_EQ(output.commands[1].command.kick_speed, 5.0);
  EXPECT_DOUBLE_EQ(output.commands[1].command.chip_angle, 1.0);
  EXPECT_DOUBLE_EQ(output.commands[1].command.dribbler_rpm, 10000);
  EXPECT_EQ(output.commands[2].command.kick, KickType::kNone);
  EXPECT_EQ(output.commands[2].command.kick_speed, 0);
  EXPECT_EQ(output.commands[2].command.dribbler_rpm, 0);
  EXPECT_EQ(output.commands[3].command.kick, KickType::kNone);
  EXPECT_EQ(output.commands[3].command.kick_speed, 0);
  EXPECT_EQ(output.commands[4].command, commands[4]) << "a command within limits passes unchanged";
  EXPECT_EQ(core.counters().clamped_values, 6u);  // 12 -> 6.5, 8 -> 5, 2 -> 1, 30000 -> 1e4, -1 -> 0, -5 -> 0
}

TEST(RobotLinkLimitsTest, AccelerationIsLimitedPerTickAndStopsAreImmediate) {
  CoreConfig config;
  config.startup_stop = time::Duration::zero();
  config.limits.acc_speedup_absolute_max = 3.0;  // m/s^2: 0.03 m/s per 10 ms tick
  config.limits.acc_brake_absolute_max = 4.0;
  RobotLinkCore core(config);
  CommandTable table;
  const RobotCommand go = forward(0, 1.0);
  double last = 0;
  for (int tick = 0; tick < 10; ++tick) {
    table.update(std::span(&go, 1), at_ms(tick * 10));
    last = core.step({.latest = table.latest()}, at_ms(tick * 10)).commands[0].command.forward;
  }
  EXPECT_NEAR(last, 0.3, 1e-9);  // 10 ticks x 0.03 m/s
  EXPECT_EQ(core.counters().accel_limited, 10u);
  EXPECT_EQ(core.counters().clamped_values, 0u) << "ramping is not clamping";

  // Braking uses the brake limit.
  const RobotCommand halt_wish = forward(0, 0.0);
  table.update(std::span(&halt_wish, 1), at_ms(100));
  EXPECT_NEAR(core.step({.latest = table.latest()}, at_ms(100)).commands[0].command.forward, 0.26, 1e-9);

  // A safety stop is exactly zero at once, and the ramp restarts from zero afterwards.
  EXPECT_EQ(core.step({.latest = table.latest(), .halt = true}, at_ms(110)).commands[0].command.forward, 0);
  table.update(std::span(&go, 1), at_ms(120));
  EXPECT_NEAR(core.step({.latest = table.latest()}, at_ms(120)).commands[0].command.forward, 0.03, 1e-9);
}

TEST(RobotLinkLimitsTest, InvalidRobotIdsAreDroppedAndCounted) {
  CommandTable table;
  const RobotCommand commands[] = {forward(3, 1), forward(16, 1), forward(1000, 1), forward(3, 2)};
  table.update(commands, at_ms(0));
  EXPECT_EQ(table.invalid_ids(), 2u);
  ASSERT_EQ(table.latest().size(), 1u);
  EXPECT_DOUBLE_EQ(table.latest()[0].command.forward, 2) << "a robot listed twice keeps its last entry";
}

TEST(RobotLinkStartupTest, UncommandedRobotsAreStoppedOnlyDuringTheStartupWindow) {
  CoreConfig config = config_without_ramps();
  config.startup_stop = milliseconds(500);
  RobotLinkCore core(config);
  CommandTable table;
  TickOutput first = core.step({.latest = table.latest()}, at_ms(0));
  ASSERT_EQ(first.commands.size(), kMaxRobots);
  for (const OutgoingCommand& out : first.commands) EXPECT_EQ(out.stop, StopReason::kStartup);
  const RobotCommand command = forward(7, 1.0);
  table.update(std::span(&command, 1), at_ms(100));
  TickOutput mixed = core.step({.latest = table.latest()}, at_ms(100));
  EXPECT_EQ(mixed.commands.size(), kMaxRobots);
  EXPECT_EQ(find(mixed, 7)->stop, StopReason::kNone);
  table.update(std::span(&command, 1), at_ms(500));
  TickOutput after = core.step({.latest = table.latest()}, at_ms(500));
  ASSERT_EQ(after.commands.size(), 1u);
  EXPECT_EQ(after.commands[0].command.id, 7u);
}

TEST(RobotLinkRateTest, EveryTickSendsEveryRobotWhateverTheJitterOfIncomingCommands) {
  // Commands arrive at jittered times (seeded: 5..60 ms apart, sometimes in bursts); the core is stepped
  // at a fixed 10 ms rate and must output exactly one command per known robot per tick: the newest one
  // received by then, held between arrivals, never a burst and never a stop while the newest is fresh.
  RobotLinkCore core(config_without_ramps());
  CommandTable table;
  std::mt19937 random(1234);
  std::uniform_int_distribution<int> gap_ms(5, 60);
  std::uniform_int_distribution<int> burst(1, 3);

  std::vector<std::pair<std::int64_t, double>> arrivals;  // (time ms, forward speed)
  std::int64_t t = 0;
  double speed = 0.1;
  while (t < 5000) {
    for (int i = burst(random); i > 0; --i) arrivals.emplace_back(t, speed += 0.001);
    t += gap_ms(random);
  }

  std::size_t next_arrival = 0;
  double newest = 0;
  std::int64_t newest_ms = -1;
  int ticks = 0;
  for (std::int64_t tick_ms = 0; tick_ms < 5000; tick_ms += 10) {
    while (next_arrival < arrivals.size() && arrivals[next_arrival].first <= tick_ms) {
      const RobotCommand command = forward(0, arrivals[next_arrival].second);
      table.update(std::span(&command, 1), at_ms(arrivals[next_arrival].first));
      newest = arrivals[next_arrival].second;
      newest_ms = arrivals[next_arrival].first;
      ++next_arrival;
    }
    TickOutput output = core.step({.latest = table.latest()}, at_ms(tick_ms));
    ++ticks;
    if (newest_ms < 0) {
      EXPECT_TRUE(output.commands.empty());
      continue;
    }
    ASSERT_EQ(output.commands.size(), 1u) << "at " << tick_ms << " ms";
    EXPECT_EQ(output.commands[0].stop, StopReason::kNone) << "at " << tick_ms << " ms (gaps are <= 60 ms)";
    EXPECT_DOUBLE_EQ(output.commands[0].command.forward, newest) << "at " << tick_ms << " ms";
  }
  EXPECT_EQ(ticks, 500);
  EXPECT_EQ(core.counters().ticks, 500u);
  EXPECT_EQ(core.counters().commands_sent, 500u);
  EXPECT_EQ(core.counters().stale_events, 0u);
}

TEST(RobotLinkCoreTest, InvalidConfigIsRejectedWithTheFieldName) {
  CoreConfig config;
  config.limits.vel_absolute_max = -1;
  Status status = validate(config);
  ASSERT_FALSE(status);
  EXPECT_NE(status.error().message.find("vel_absolute_max"), std::string::npos);
  EXPECT_THROW(RobotLinkCore{config}, std::invalid_argument);
  config = CoreConfig{};
  config.command_timeout = time::Duration::zero();
  EXPECT_FALSE(validate(config));
}

}  // namespace
}  // namespace ssl::robot_link
