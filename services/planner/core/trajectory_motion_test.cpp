#include "services/planner/core/trajectory_motion.h"

#include <gtest/gtest.h>

#include "services/planner/core/planner_test_util.h"

namespace ssl::planner {
namespace {

using testing::go_to;
using testing::robot_at;

TEST(TrajectoryMotion, PlansFromWhereTheLastCommandTakesTheRobotWithinTheLatency) {
  TrajectoryMotionPlanner motion(MotionLimits{}, {.actuation_latency = 0.02});
  const wm::RobotState robot = robot_at({0, 0});
  const Zones zones;
  motion.begin_tick();
  motion.sent(1, Vec2(1.0, 0.5), 0);
  (void)motion.plan(robot, go_to({2, 0}), zones, 0.01);
  std::vector<Vec2> path;
  std::optional<double> error;
  motion.describe(1, 0.1, path, error);
  ASSERT_FALSE(path.empty());
  EXPECT_NEAR(path.front().x(), 0.02, 1e-12);
  EXPECT_NEAR(path.front().y(), 0.01, 1e-12);
  EXPECT_NEAR(path.back().x(), 2.0, 1e-9);
}

TEST(TrajectoryMotion, ATargetAnOpponentStandsOnMovesToItsEdge) {
  TrajectoryMotionPlanner motion(MotionLimits{});
  const wm::RobotState robot = robot_at({-2, 0});
  Zones zones;
  zones.robots.push_back({.id = 1, .ours = true, .position = robot.position});
  zones.robots.push_back({.id = 4, .ours = false, .position = {0.05, 0}});
  motion.begin_tick();
  (void)motion.plan(robot, go_to({0, 0}), zones, 0.01);
  std::vector<Vec2> path;
  std::optional<double> error;
  motion.describe(1, 0.1, path, error);
  ASSERT_FALSE(path.empty());
  const double apart = (path.back() - Vec2(0.05, 0)).norm();
  EXPECT_NEAR(apart, 2 * 0.09 + 0.05 + 0.01, 1e-9)
      << "the opponent's edge, at rest: two radii, the margin and 1 cm beyond the sweep's chord margin";
  EXPECT_LT(path.back().x(), 0.05) << "on our side of it";
}

TEST(TrajectoryMotion, ARobotInsideAGoalLeavesThroughItsMouthFirst) {
  // Default field (division A): goal line x = 6, mouth |y| < 0.9. A robot deep in the goal, sent to a
  // point beside it: straight out of the mouth (its path ends in front of the line at the same y).
  TrajectoryMotionPlanner motion(MotionLimits{});
  Zones zones;
  const wm::RobotState robot = robot_at({6.1, -0.6});
  zones.robots.push_back({.id = 1, .ours = true, .position = robot.position});
  MotionIntent intent = go_to({5.5, -2.5});
  motion.begin_tick();
  (void)motion.plan(robot, intent, zones, 0.01);
  std::vector<Vec2> path;
  std::optional<double> error;
  motion.describe(1, 0.1, path, error);
  ASSERT_FALSE(path.empty());
  EXPECT_LT(path.back().x(), 6.0) << "out in front of the goal line";
  EXPECT_NEAR(path.back().y(), -0.6, 1e-9) << "straight out, not through the side wall";
}

TEST(TrajectoryMotion, HaltAndInactiveIntentsStopAtOnce) {
  TrajectoryMotionPlanner motion(MotionLimits{});
  const wm::RobotState robot = robot_at({0, 0}, 0, 2);
  motion.begin_tick();
  motion.sent(2, Vec2(2, 0), 0);
  MotionIntent halt = go_to({3, 0});
  halt.halt = true;
  const RobotCommand command = motion.plan(robot, halt, Zones{}, 0.01);
  EXPECT_EQ(command.forward, 0.0);
  EXPECT_EQ(command.left, 0.0);
  EXPECT_EQ(command.angular, 0.0);
}

}  // namespace
}  // namespace ssl::planner
