#include "services/planner/core/motion.h"

#include <gtest/gtest.h>

#include <cmath>

#include "services/planner/core/planner_test_util.h"
#include "services/planner/core/rules.h"
#include "libs/domain/game_state.h"

namespace ssl::planner {
namespace {

using testing::go_to;
using testing::robot_at;

Zones zones_with_ball(const Vec2& ball) {
  Zones zones;
  zones.ball = ball;
  return zones;
}

TEST(PlannerMotionTest, TargetsInForbiddenZonesAreProjectedOut) {
  const Zones zones = zones_with_ball({1, 1});
  MotionIntent intent = go_to({1.1, 1});
  intent.avoid_ball_radius = 0.7;
  EXPECT_NEAR((project_out(intent.target, intent, zones) - Vec2(1, 1)).norm(), 0.7, 1e-9);
  // Inside their defense area (+ margin): moved to its front.
  intent = go_to({5.5, 0.2});
  const Vec2 p = project_out(intent.target, intent, zones);
  EXPECT_LE(p.x(), 6.0 - 1.8 - zones.their_defense_margin + 1e-9);
  // Outside the field: clamped.
  intent = go_to({9, 9});
  const Vec2 q = project_out(intent.target, intent, zones);
  EXPECT_LE(q.x(), 6.0 + zones.field_margin + 1e-9);
  EXPECT_LE(q.y(), 4.5 + zones.field_margin + 1e-9);
  // The keeper may stay in our defense area.
  intent = go_to({-5.8, 0});
  intent.avoid_our_defense_area = false;
  EXPECT_EQ(project_out(intent.target, intent, zones), Vec2(-5.8, 0));
}

TEST(PlannerMotionTest, ApproachRespectsSpeedAndAccelerationLimits) {
  MotionLimits limits;
  SimpleMotionPlanner motion(limits);
  Zones zones;
  MotionIntent intent = go_to({3, 0});
  intent.max_speed = 2.0;
  const double dt = 0.01;
  double last = 0;
  for (int i = 0; i < 200; ++i) {
    const RobotCommand c = motion.plan(robot_at({-3, 0}), intent, zones, dt);
    const double v = std::hypot(c.forward, c.left);
    EXPECT_LE(v, 2.0 + 1e-9);
    EXPECT_LE(v - last, limits.max_acceleration * dt + 1e-9);
    last = v;
  }
  EXPECT_NEAR(last, 2.0, 1e-6);
}

TEST(PlannerMotionTest, SteersAroundTheBallCircleAndLeavesIt) {
  SimpleMotionPlanner motion(MotionLimits{});
  const Zones zones = zones_with_ball({0, 0});
  MotionIntent intent = go_to({2, 0});
  intent.avoid_ball_radius = 0.6;
  RobotCommand c;
  for (int i = 0; i < 100; ++i) c = motion.plan(robot_at({-2, 0}), intent, zones, 0.01);
  EXPECT_GT(std::abs(c.left), 0.1) << "goes around, not through";
  // Inside the circle: the velocity points away from the ball.
  SimpleMotionPlanner inside(MotionLimits{});
  for (int i = 0; i < 50; ++i) c = inside.plan(robot_at({0.2, 0.1}), intent, zones, 0.01);
  EXPECT_GT(to_team(c, 0).dot(Vec2(0.2, 0.1)), 0.0);
}

TEST(PlannerMotionTest, HeadingControlTurnsTheShortWay) {
  SimpleMotionPlanner motion(MotionLimits{});
  MotionIntent intent = go_to({0, 0});
  intent.orientation = 3.0;
  RobotCommand c;
  for (int i = 0; i < 50; ++i) c = motion.plan(robot_at({0, 0}, -3.0), intent, Zones{}, 0.01);
  EXPECT_LT(c.angular, 0.0);  // -3.0 -> 3.0 is shorter clockwise across pi
}

TEST(PlannerRuleLayerTest, EnforcesHaltStopAndKicks) {
  PlannerConfig config;
  wm::GameState game(TeamColor::kBlue);
  wm::RefereeInfo referee;
  referee.command = wm::RefereeCommand::kStop;
  referee.command_counter = 1;
  game.update(referee, wm::TeamFrame{}, Vec2(0, 0));
  const RuleLimits stop = rule_limits(game, config, true, std::nullopt);
  RobotCommand c;
  c.id = 1;
  c.forward = -3.0;  // heading 0 at (0.3, 0): straight towards the ball at the origin
  c.kick = KickType::kFlat;
  c.kick_speed = 5;
  c.dribbler_rpm = 1000;
  const RobotCommand out = enforce(stop, robot_at({0.3, 0}), c, Vec2(0, 0));
  EXPECT_LE(std::hypot(out.forward, out.left), config.stop_speed);
  EXPECT_GT(out.forward, 0.0);  // away from the ball
  EXPECT_EQ(out.kick, KickType::kNone);
  EXPECT_EQ(out.dribbler_rpm, 0.0);

  referee.command = wm::RefereeCommand::kHalt;
  referee.command_counter = 2;
  game.update(referee, wm::TeamFrame{}, Vec2(0, 0));
  const RobotCommand halted =
      enforce(rule_limits(game, config, true, std::nullopt), robot_at({2, 0}), c, Vec2(0, 0));
  EXPECT_EQ(halted.forward, 0.0);
  EXPECT_EQ(halted.left, 0.0);
  EXPECT_EQ(halted.angular, 0.0);
  EXPECT_EQ(halted.kick, KickType::kNone);

  referee.command = wm::RefereeCommand::kForceStart;
  referee.command_counter = 3;
  game.update(referee, wm::TeamFrame{}, Vec2(0, 0));
  const RobotCommand playing =
      enforce(rule_limits(game, config, true, std::nullopt), robot_at({2, 0}), c, Vec2(0, 0));
  EXPECT_EQ(playing.kick, KickType::kFlat);
  EXPECT_NEAR(playing.forward, -3.0, 1e-9);
}

}  // namespace
}  // namespace ssl::planner
