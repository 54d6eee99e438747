#include "services/planner/core/trajectory_motion.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <vector>

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

TEST(TrajectoryMotion, ARobotFollowingATargetIntoOurDefenseAreaStopsAtTheZonesEdge) {
  // A marker keeps up with an opponent running into our defense area (division A: its front at x = -4.2).
  // The follow mode drives with the target's velocity; the zone still holds the robot's centre outside.
  TrajectoryMotionPlanner motion(MotionLimits{});
  Zones zones;
  zones.our_defense_margin = 0.14;
  const double edge = our_defense_zone(zones).max().x();
  wm::RobotState robot = robot_at({-3.7, 0.3});
  Vec2 sent = Vec2::Zero();
  Vec2 opponent(-3.8, 0.3);
  const Vec2 opponent_velocity(-1.5, 0);
  double deepest = robot.position.x();
  for (int tick = 0; tick < 150; ++tick) {
    zones.robots = {{.id = 1, .ours = true, .position = robot.position, .velocity = sent}};
    MotionIntent intent = go_to(opponent + Vec2(0.3, 0));
    intent.target_velocity = opponent_velocity;
    motion.begin_tick();
    motion.sent(1, sent, 0);
    sent = to_team(motion.plan(robot, intent, zones, 0.01), robot.orientation);
    robot.position += sent * 0.01;
    robot.velocity = sent;
    opponent += opponent_velocity * 0.01;
    deepest = std::min(deepest, robot.position.x());
  }
  EXPECT_GE(deepest, edge - 0.01) << "the robot went " << edge - deepest << " m into the zone";
  EXPECT_LT(deepest, edge + 0.1) << "it kept up with the target as far as the zone";
}

TEST(TrajectoryMotion, TheContactGuardCountsOnAnOpponentRunningAwayButNotOnATeammate) {
  // Following a target at 2 m/s with a robot 0.3 m ahead running the same way at 1.2 m/s: an opponent (to
  // mark) may be closed on as fast as its running away still leaves room to brake; a teammate ahead is not
  // followed closely (the guard counts on no way it goes on).
  const auto forward_speed = [](bool ahead_is_ours) {
    TrajectoryMotionPlanner motion(MotionLimits{});
    const wm::RobotState robot = robot_at({0, 0});
    Zones zones;
    zones.robots = {{.id = 1, .ours = true, .position = robot.position, .velocity = {2.0, 0}},
                    {.id = 2, .ours = ahead_is_ours, .position = {0.3, 0}, .velocity = {1.2, 0}}};
    MotionIntent intent = go_to({0.6, 0});
    intent.target_velocity = Vec2(2.0, 0);
    motion.begin_tick();
    motion.sent(1, Vec2(2.0, 0), 0);
    return to_team(motion.plan(robot, intent, zones, 0.01), robot.orientation).x();
  };
  const double behind_opponent = forward_speed(false);
  const double behind_teammate = forward_speed(true);
  EXPECT_GT(behind_opponent, 1.0);
  EXPECT_LT(behind_teammate, 0.5);
}

TEST(TrajectoryMotion, AFollowerWithARobotBetweenItAndItsMovingTargetGoesRoundIt) {
  // A marker whose moving target lies beyond a teammate standing on the way (two markers whose opponents
  // swapped places): not the follow mode's straight line into the teammate, the searched path round it.
  TrajectoryMotionPlanner motion(MotionLimits{});
  const wm::RobotState robot = robot_at({0, 0});
  Zones zones;
  zones.robots = {{.id = 1, .ours = true, .position = robot.position},
                  {.id = 2, .ours = true, .position = {0.4, 0.02}}};
  MotionIntent intent = go_to({0.8, 0});
  intent.target_velocity = Vec2(0.5, 0);
  motion.begin_tick();
  const Vec2 velocity = to_team(motion.plan(robot, intent, zones, 0.01), robot.orientation);
  // From rest the path's first tick is slow (a tick of acceleration); its direction tells: sideways.
  EXPECT_GT(std::abs(velocity.y()), std::abs(velocity.x()))
      << "round the teammate, not straight at it: " << velocity.transpose();
  // With the way clear the follow mode moves with the target, straight at it.
  zones.robots.pop_back();
  motion.begin_tick();
  const Vec2 clear = to_team(motion.plan(robot, intent, zones, 0.01), robot.orientation);
  EXPECT_NEAR(clear.y(), 0.0, 1e-9);
  EXPECT_GT(clear.x(), 0.5);
}

TEST(TrajectoryMotion, WithAMeasuredDelayTheVelocityIsWrittenInTheFrameTheRobotWillBeTurnedTo) {
  // Turning at 2 rad/s with commands acting 0.1 s late, the robot faces 0.2 rad further round when this
  // command acts: its local velocity is written for that heading, so that it drives where it was planned.
  const auto command_for = [](bool measured) {
    TrajectoryMotionPlanner motion(MotionLimits{});
    motion.set_actuation_latency(0.1, measured);
    const wm::RobotState robot = robot_at({0, 0});
    Zones zones;
    zones.robots = {{.id = 1, .ours = true, .position = robot.position}};
    MotionIntent intent = go_to({2, 0});
    intent.orientation = 1.0;
    motion.begin_tick();
    motion.sent(1, Vec2(1.0, 0), 2.0);
    return motion.plan(robot, intent, zones, 0.01);
  };
  const RobotCommand measured = command_for(true);
  const Vec2 then = to_team(measured, 0.2);
  EXPECT_NEAR(then.y(), 0.0, 1e-9) << "along x in the frame of the heading then";
  EXPECT_GT(then.x(), 0.5);
  const RobotCommand configured = command_for(false);
  EXPECT_NEAR(to_team(configured, 0.0).y(), 0.0, 1e-9) << "a configured latency: the heading now";
}

TEST(TrajectoryMotion, ARobotRunningAtSpeedTurnsSlowlyUnlessItWouldArriveFacingWrong) {
  // Facing +x. At rest it turns at max_angular_speed (6 rad/s). Running at 2 m/s towards a target 9 m
  // ahead (about 3.4 s away) it makes a quarter turn at max_turning_acceleration / 2 = 0.75 rad/s: its wheels
  // hold the velocity, and it still faces right on arrival. A half turn 1 m ahead (braking now, about 0.7
  // s away) needs more than 4 rad/s to face right on arrival: it turns that fast.
  const MotionLimits limits{.max_turning_acceleration = 1.5};
  const auto turn_at = [&](const Vec2& velocity, const Vec2& target, double orientation, double last_turn) {
    TrajectoryMotionPlanner motion(limits);
    wm::RobotState robot = robot_at({-4, 0});
    robot.velocity = velocity;
    Zones zones;
    zones.robots = {{.id = 1, .ours = true, .position = robot.position, .velocity = velocity}};
    MotionIntent intent = go_to(target);
    intent.orientation = orientation;
    motion.begin_tick();
    motion.sent(1, velocity, last_turn);
    return std::abs(motion.plan(robot, intent, zones, 0.01).angular);
  };
  const double quarter = std::numbers::pi / 2;
  EXPECT_GT(turn_at(Vec2::Zero(), {5, 0}, quarter, 6.0), 5.9);
  const double running = turn_at(Vec2(2, 0), {5, 0}, quarter, 0.75);
  EXPECT_LE(running, 0.75 + 1e-9);
  EXPECT_GT(running, 0.7) << "still turning, at the limit";
  EXPECT_GT(turn_at(Vec2(2, 0), {-3, 0}, std::numbers::pi, 5.0), 4.0) << "arriving soon: as fast as needed";
  EXPECT_DOUBLE_EQ(limits.angular_speed_at(0.2), 6.0) << "0.2 m/s * 6 rad/s = 1.2 m/s^2: under the limit";
  EXPECT_DOUBLE_EQ(limits.angular_speed_at(3.0), 0.5);
  EXPECT_DOUBLE_EQ(MotionLimits{}.angular_speed_at(3.0), 6.0) << "no limit by default";
}

TEST(TrajectoryMotion, ARobotInsideAZoneWhoseExitARobotStandsByDrivesStraightOut) {
  // Their defense area's STOP zone (division A: the area's front at x = 4.2, the zone 0.39 m before it). Our
  // robot 0.09 m inside it, an opponent beside the exit point: the searched paths all count as colliding and
  // the best of them did not lead out; the robot drives out anyway, along the shortest way.
  TrajectoryMotionPlanner motion(MotionLimits{});
  Zones zones;
  zones.their_defense_margin = 0.39;
  const double edge = their_defense_zone(zones).min().x();
  const wm::RobotState robot = robot_at({edge + 0.09, 0.0}, M_PI);
  zones.robots = {{.id = 1, .ours = true, .position = robot.position},
                  {.id = 5, .ours = false, .position = {edge - 0.05, 0.23}}};
  motion.begin_tick();
  const Vec2 command = to_team(motion.plan(robot, go_to({edge - 1.0, 0.0}), zones, 0.01), robot.orientation);
  EXPECT_LT(command.x(), -0.1) << "out of the zone towards the field";
}

TEST(TrajectoryMotion, ARobotKeepingOffTheBallLetsARollingBallPassInFrontOfIt) {
  // Our robot runs from (0, -1) to (0, 1); the ball rolls along y = 0 at 2 m/s, timed to be at the crossing
  // when the robot's straight path reaches it. Keeping off the ball, no point of the planned path (every
  // 0.02 s) comes within touching distance of where the ball is then; not keeping off, the path runs into it.
  constexpr double kStep = 0.02;  // s
  const wm::RobotState robot = robot_at({0.0, -1.0}, M_PI / 2);
  const Vec2 ball_velocity(2.0, 0.0);
  const auto plan = [&](const Vec2& ball, bool keep_off) {
    TrajectoryMotionPlanner motion(MotionLimits{});
    Zones zones;
    zones.robots = {{.id = 1, .ours = true, .position = robot.position}};
    zones.ball = ball;
    zones.ball_velocity = ball_velocity;
    MotionIntent intent = go_to({0.0, 1.0});
    intent.keep_off_ball = keep_off;
    motion.begin_tick();
    (void)motion.plan(robot, intent, zones, 0.01);
    std::vector<Vec2> path;
    std::optional<double> error;
    motion.describe(1, kStep, path, error);
    return path;
  };
  const std::vector<Vec2> straight = plan({-20.0, 0.0}, false);
  const auto crossing = std::find_if(straight.begin(), straight.end(), [](const Vec2& p) { return p.y() >= 0; });
  ASSERT_NE(crossing, straight.end());
  const double crossing_time = kStep * static_cast<double>(crossing - straight.begin());
  const Vec2 ball = -ball_velocity * crossing_time;
  const auto nearest_approach = [&](const std::vector<Vec2>& path) {
    double nearest = 1e9;
    for (std::size_t k = 0; k < path.size(); ++k) {
      nearest = std::min(nearest, (path[k] - (ball + ball_velocity * (kStep * static_cast<double>(k)))).norm());
    }
    return nearest;
  };
  const double touching = 0.09 + Zones{}.field.size().ball_radius;  // the params' robot radius + the ball's
  EXPECT_LT(nearest_approach(plan(ball, false)), touching);
  EXPECT_GT(nearest_approach(plan(ball, true)), touching);
}

TEST(TrajectoryMotion, ARobotInsideAZoneNeverDrivesDeeper) {
  // Pushed 4 cm into our zone while driving into it at 0.8 m/s, towards a target beyond the area: the
  // command has no component deeper into the zone, so the robot leaves it.
  TrajectoryMotionPlanner motion(MotionLimits{});
  Zones zones;
  zones.our_defense_margin = 0.14;
  const double edge = our_defense_zone(zones).max().x();
  wm::RobotState robot = robot_at({edge - 0.04, -1.0});
  robot.velocity = Vec2(-0.8, 0.1);
  zones.robots = {{.id = 1, .ours = true, .position = robot.position, .velocity = robot.velocity}};
  motion.begin_tick();
  motion.sent(1, robot.velocity, 0);
  const Vec2 command = to_team(motion.plan(robot, go_to({-5.5, -2.5}), zones, 0.01), robot.orientation);
  EXPECT_GE(command.x(), 0.0);
}

}  // namespace
}  // namespace ssl::planner
