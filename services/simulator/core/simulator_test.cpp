// The simulator facade: start formation, teleports, robots on and off the field, the errors a protocol
// client gets for bad requests, and vision that shows what the physics does.
#include "services/simulator/core/simulator.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <optional>
#include <utility>
#include <vector>

namespace ssl::sim {
namespace {

using std::chrono::milliseconds;

SimulatorOptions perfect_vision(std::uint32_t robots_per_team) {
  SimulatorOptions options;
  options.robots_per_team = robots_per_team;
  options.vision.realism = RealismConfig::none();
  return options;
}

std::optional<RobotState> find(const WorldSnapshot& world, RobotKey key) {
  for (const auto& robot : world.robots) {
    if (robot.key == key) return robot;
  }
  return std::nullopt;
}

TEST(SimulatorTest, StartsWithBothTeamsInTheirHalvesAndNoOverlaps) {
  Simulator sim(perfect_vision(11));
  const WorldSnapshot world = sim.snapshot();
  ASSERT_EQ(world.robots.size(), 22u);
  for (const auto& robot : world.robots) {
    if (robot.key.team == TeamColor::kBlue) {
      EXPECT_LT(robot.position.x(), 0) << robot.key.id;
    } else {
      EXPECT_GT(robot.position.x(), 0) << robot.key.id;
    }
    for (const auto& other : world.robots) {
      if (other.key == robot.key) continue;
      EXPECT_GT((other.position - robot.position).norm(), 0.18) << robot.key.id << " overlaps " << other.key.id;
    }
  }
}

TEST(SimulatorTest, RobotsLeaveAndJoinTheFieldThroughTeleports) {
  Simulator sim(perfect_vision(2));
  ControlRequest remove;
  remove.robots.push_back({.key = {TeamColor::kBlue, 1}, .present = false});
  EXPECT_TRUE(sim.apply(remove).empty());
  EXPECT_FALSE(find(sim.snapshot(), {TeamColor::kBlue, 1}));

  ControlRequest add;
  add.robots.push_back({.key = {TeamColor::kYellow, 7}, .x = 1.0, .y = 2.0, .orientation = 0.5, .present = true});
  EXPECT_TRUE(sim.apply(add).empty());
  const auto added = find(sim.snapshot(), {TeamColor::kYellow, 7});
  ASSERT_TRUE(added);
  EXPECT_NEAR(added->position.x(), 1.0, 1e-6);
  EXPECT_NEAR(added->position.y(), 2.0, 1e-6);
  EXPECT_NEAR(added->orientation, 0.5, 1e-6);
}

TEST(SimulatorTest, BadRequestsGetNamedErrorsAndChangeNothing) {
  Simulator sim(perfect_vision(2));
  const WorldSnapshot before = sim.snapshot();
  ControlRequest request;
  request.robots.push_back({.key = {TeamColor::kBlue, 9}, .x = 0.0, .y = 0.0});            // not on the field
  request.robots.push_back({.key = {TeamColor::kBlue, 16}, .x = 0.0, .y = 0.0});           // no such id
  request.robots.push_back({.key = {TeamColor::kBlue, 0}, .x = std::nan("")});             // not a number
  request.robots.push_back({.key = {TeamColor::kBlue, 1}, .x = 1.0, .by_force = true});    // unsupported
  request.simulation_speed = -1;
  const auto errors = sim.apply(request);
  ASSERT_EQ(errors.size(), 5u);
  EXPECT_EQ(errors[0].code, "UNKNOWN_ROBOT");
  EXPECT_EQ(errors[1].code, "INVALID_ROBOT_ID");
  EXPECT_EQ(errors[2].code, "INVALID_VALUE");
  EXPECT_EQ(errors[3].code, "UNSUPPORTED_BY_FORCE");
  EXPECT_EQ(errors[4].code, "INVALID_SIMULATION_SPEED");
  EXPECT_DOUBLE_EQ(sim.simulation_speed(), 1.0);
  const WorldSnapshot after = sim.snapshot();
  ASSERT_EQ(after.robots.size(), before.robots.size());
  for (std::size_t i = 0; i < after.robots.size(); ++i) EXPECT_EQ(after.robots[i].position, before.robots[i].position);

  RobotCommand nan_command;
  nan_command.move = RobotCommand::Move::kLocalVelocity;
  nan_command.velocity.x() = std::numeric_limits<double>::infinity();
  const auto command_errors = sim.set_commands(TeamColor::kYellow, {{0, nan_command}, {12, RobotCommand{}}});
  ASSERT_EQ(command_errors.size(), 2u);
  EXPECT_EQ(command_errors[0].code, "INVALID_VALUE");
  EXPECT_EQ(command_errors[1].code, "UNKNOWN_ROBOT");
}

TEST(SimulatorTest, SafeBallTeleportPushesRobotsOutOfTheWay) {
  Simulator sim(perfect_vision(1));
  const auto keeper = find(sim.snapshot(), {TeamColor::kBlue, 0});
  ASSERT_TRUE(keeper);
  ControlRequest request;
  request.ball = BallTeleport{.x = keeper->position.x(), .y = keeper->position.y(), .teleport_safely = true};
  EXPECT_TRUE(sim.apply(request).empty());
  const WorldSnapshot world = sim.snapshot();
  const auto moved = find(world, {TeamColor::kBlue, 0});
  ASSERT_TRUE(moved);
  EXPECT_GT((moved->position - world.ball.position.head<2>()).norm(), 0.09 + 0.0215);
}

TEST(SimulatorTest, PerfectVisionShowsWhatThePhysicsDoes) {
  Simulator sim(perfect_vision(1));
  ControlRequest request;
  request.ball = BallTeleport{.x = 1.0, .y = -2.0};
  ASSERT_TRUE(sim.apply(request).empty());
  std::vector<DetectionFrame> frames;
  bool geometry = false;
  for (int i = 0; i < 10; ++i) {
    auto output = sim.step(milliseconds(10));
    geometry |= output.geometry_due;
    frames.insert(frames.end(), output.frames.begin(), output.frames.end());
  }
  EXPECT_TRUE(geometry);
  ASSERT_FALSE(frames.empty());
  const WorldSnapshot world = sim.snapshot();
  bool ball_seen = false;
  for (const auto& frame : frames) {
    for (const auto& ball : frame.balls) {
      ball_seen = true;
      EXPECT_NEAR(ball.x, 1.0, 1e-3);
      EXPECT_NEAR(ball.y, -2.0, 1e-3);
    }
  }
  EXPECT_TRUE(ball_seen);
  EXPECT_NEAR(world.ball.position.x(), 1.0, 1e-3);
}

TEST(SimulatorTest, ARobotWhoseCommandsStopIsStoppedAfterTheCommandTimeout) {
  // Blue robot 1 driven forward at 1 m/s, its command renewed every 10 ms for 1 s, then no more. With a
  // 0.2 s timeout it keeps its speed for 0.2 s after the last command and stands 0.7 s later; without a
  // timeout (the default) it keeps going.
  const auto speed_after = [](std::optional<time::Duration> timeout, double since_last_command) {
    SimulatorOptions options = perfect_vision(2);
    options.command_timeout = timeout;
    Simulator sim(options);
    ControlRequest clear_run;  // along y = 2.5 in our half, nobody and no ball in the way
    clear_run.robots = {RobotTeleport{.key = {TeamColor::kBlue, 1}, .x = -3.0, .y = 2.5, .orientation = 0.0}};
    EXPECT_TRUE(sim.apply(clear_run).empty());
    RobotCommand forward{.move = RobotCommand::Move::kLocalVelocity};
    forward.velocity.x() = 1.0;
    for (int i = 0; i < 100; ++i) {
      EXPECT_TRUE(sim.set_commands(TeamColor::kBlue, {{1, forward}}).empty());
      sim.step(milliseconds(10));
    }
    for (int i = 0; i < static_cast<int>(std::lround(since_last_command * 100)); ++i) sim.step(milliseconds(10));
    const auto robot = find(sim.snapshot(), {TeamColor::kBlue, 1});
    EXPECT_TRUE(robot);
    return std::make_pair(robot ? robot->velocity.norm() : -1.0, sim.command_timeouts());
  };
  const auto timeout = std::chrono::duration_cast<time::Duration>(milliseconds(200));
  EXPECT_NEAR(speed_after(timeout, 0.18).first, 1.0, 0.05) << "within the timeout the command holds";
  const auto [stopped, timeouts] = speed_after(timeout, 0.9);
  EXPECT_LT(stopped, 0.01);
  EXPECT_EQ(timeouts, 1u);
  EXPECT_NEAR(speed_after(std::nullopt, 0.9).first, 1.0, 0.05);
}

TEST(SimulatorTest, ANewFieldRebuildsTheWorldAndKeepsTheRobots) {
  Simulator sim(perfect_vision(2));
  ControlRequest request;
  request.field = FieldGeometry::division_b();
  EXPECT_TRUE(sim.apply(request).empty());
  EXPECT_DOUBLE_EQ(sim.geometry().field.field_length, 9.0);
  EXPECT_EQ(sim.snapshot().robots.size(), 4u);
}

// --- robot response (robot_response.h) ---

/// Blue robot 1 on a clear run along y = 2.5, commanded forward at 1 m/s every 10 ms from t = 0; its speed
/// after each 2 ms step (m/s), over `duration` seconds.
std::vector<double> forward_speeds(const RobotResponse& response, double duration, std::uint64_t seed = 1) {
  SimulatorOptions options = perfect_vision(2);
  options.response = response;
  options.seed = seed;
  Simulator sim(options);
  ControlRequest clear_run;
  clear_run.robots = {RobotTeleport{.key = {TeamColor::kBlue, 1}, .x = -3.0, .y = 2.5, .orientation = 0.0}};
  EXPECT_TRUE(sim.apply(clear_run).empty());
  RobotCommand forward{.move = RobotCommand::Move::kLocalVelocity};
  forward.velocity.x() = 1.0;
  std::vector<double> speeds;
  for (int step = 0; step < static_cast<int>(std::lround(duration / 0.002)); ++step) {
    if (step % 5 == 0) {
      EXPECT_TRUE(sim.set_commands(TeamColor::kBlue, {{1, forward}}).empty());
    }
    sim.step(milliseconds(2));
    speeds.push_back(find(sim.snapshot(), {TeamColor::kBlue, 1})->velocity.norm());
  }
  return speeds;
}

/// Seconds until `speeds` (one per 2 ms step) first reach `level`, or -1.
double time_to_reach(const std::vector<double>& speeds, double level) {
  for (std::size_t i = 0; i < speeds.size(); ++i) {
    if (speeds[i] >= level) return 0.002 * static_cast<double>(i + 1);
  }
  return -1;
}

TEST(SimulatorRobotResponse, IdealCommandsActAtOnceUnderTheAccelerationLimit) {
  // 3 m/s^2 speed-up: 1 m/s after 0.333 s, moving after the first step.
  const std::vector<double> speeds = forward_speeds(RobotResponse::ideal(), 0.6);
  EXPECT_GT(speeds.front(), 0.005);
  EXPECT_NEAR(time_to_reach(speeds, 0.999), 0.334, 0.004);
}

TEST(SimulatorRobotResponse, ADelayedCommandActsThatMuchLater) {
  const RobotResponse delayed{.command_delay = 0.04};
  const std::vector<double> speeds = forward_speeds(delayed, 0.6);
  EXPECT_EQ(speeds[18], 0.0) << "still standing at 38 ms";
  EXPECT_GT(speeds[21], 0.0) << "moving at 44 ms";
  EXPECT_NEAR(time_to_reach(speeds, 0.999), 0.374, 0.004);
}

TEST(SimulatorRobotResponse, TheVelocityLagsTheCommandWithItsTimeConstant) {
  // A 0.1 s first-order lag under the 3 m/s^2 ramp: the set point rises at 10 m/s^2 at first, faster than
  // the ramp, so the robot ramps until about 0.31 s (0.95 m/s), then follows the set point's exponential:
  // 0.999 m/s only after tau ln 1000 = 0.69 s, where the ideal robot is there at 0.333 s.
  const RobotResponse lagging{.velocity_time_constant = 0.1};
  const std::vector<double> speeds = forward_speeds(lagging, 1.0);
  const double at_95 = time_to_reach(speeds, 0.95);
  EXPECT_GT(at_95, 0.30);
  EXPECT_LT(at_95, 0.40);
  EXPECT_GT(time_to_reach(speeds, 0.999), 0.6) << "the last per mille takes several time constants";
  EXPECT_NEAR(speeds.back(), 1.0, 0.002);
}

TEST(SimulatorRobotResponse, EachRobotHasItsOwnLimitsWithinTheSpreadAndTheSameOnesForTheSameSeed) {
  const RobotResponse spread{.limit_spread = 0.2};
  // Commanded 5 m/s, each robot settles at its own speed limit: 3 m/s x [0.8, 1.2].
  auto top_speeds = [&](std::uint64_t seed) {
    SimulatorOptions options = perfect_vision(4);
    options.response = spread;
    options.seed = seed;
    Simulator sim(options);
    std::vector<RobotCommandFor> commands;
    for (std::uint32_t id = 1; id < 4; ++id) {
      ControlRequest lane;
      lane.robots = {RobotTeleport{.key = {TeamColor::kBlue, id}, .x = -5.5, .y = -3.0 + 1.5 * id, .orientation = 0.0}};
      EXPECT_TRUE(sim.apply(lane).empty());
      RobotCommand fast{.move = RobotCommand::Move::kLocalVelocity};
      fast.velocity.x() = 5.0;
      commands.push_back({id, fast});
    }
    for (int i = 0; i < 150; ++i) {
      sim.set_commands(TeamColor::kBlue, commands);
      sim.step(milliseconds(10));
    }
    std::vector<double> speeds;
    for (std::uint32_t id = 1; id < 4; ++id) speeds.push_back(find(sim.snapshot(), {TeamColor::kBlue, id})->velocity.norm());
    return speeds;
  };
  const std::vector<double> speeds = top_speeds(3);
  for (double speed : speeds) {
    EXPECT_GE(speed, 2.4 - 1e-6);
    EXPECT_LE(speed, 3.6 + 1e-6);
  }
  EXPECT_GT(std::abs(speeds[0] - speeds[1]) + std::abs(speeds[1] - speeds[2]), 0.05) << "the robots differ";
  EXPECT_EQ(speeds, top_speeds(3));
  EXPECT_NE(speeds, top_speeds(4));
}

TEST(SimulatorRobotResponse, LostCommandsAreCountedAndTheRobotKeepsItsLast) {
  SimulatorOptions options = perfect_vision(2);
  options.response = RobotResponse{.command_loss = 0.5};
  Simulator sim(options);
  RobotCommand forward{.move = RobotCommand::Move::kLocalVelocity};
  forward.velocity.x() = 0.5;
  for (int i = 0; i < 200; ++i) {
    EXPECT_TRUE(sim.set_commands(TeamColor::kBlue, {{1, forward}}).empty());
    sim.step(milliseconds(10));
  }
  EXPECT_GT(sim.commands_lost(), 70u);
  EXPECT_LT(sim.commands_lost(), 130u);
  EXPECT_NEAR(find(sim.snapshot(), {TeamColor::kBlue, 1})->velocity.norm(), 0.5, 0.01);
}

TEST(SimulatorRobotResponse, TheProfilesAreValidAndBadValuesAreRejectedWithTheReason) {
  for (const char* name : {"ideal", "realistic", "harsh"}) {
    ASSERT_TRUE(RobotResponse::profile(name)) << name;
    EXPECT_FALSE(RobotResponse::profile(name)->invalid_reason()) << name;
  }
  EXPECT_FALSE(RobotResponse::profile("perfect"));
  EXPECT_EQ(RobotResponse::profile("ideal"), RobotResponse{});
  SimulatorOptions options = perfect_vision(1);
  options.response.command_loss = 1.5;
  EXPECT_THROW(Simulator{options}, std::invalid_argument);
  options.response = RobotResponse{.command_delay = std::numeric_limits<double>::quiet_NaN()};
  EXPECT_THROW(Simulator{options}, std::invalid_argument);
  options.response = RobotResponse{.limit_spread = 1.0};
  EXPECT_THROW(Simulator{options}, std::invalid_argument);
}

TEST(SimulatorRobotResponse, AKickWithANegativeSpeedIsAnInvalidValueNotAnUnknownRobot) {
  Simulator sim(perfect_vision(1));
  RobotCommand bad{.kick_speed = -1};
  const std::vector<SimError> errors = sim.set_commands(TeamColor::kBlue, {{0, bad}});
  ASSERT_EQ(errors.size(), 1u);
  EXPECT_EQ(errors[0].code, "INVALID_VALUE");
}

}  // namespace
}  // namespace ssl::sim
