// The simulator facade: start formation, teleports, robots on and off the field, the errors a protocol
// client gets for bad requests, and vision that shows what the physics does.
#include "services/simulator/core/simulator.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <optional>
#include <utility>

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

}  // namespace
}  // namespace ssl::sim
