// WorldModel on synthetic, noise-free frames: team frame, teleports, outliers, dribbler, possession.
#include "services/world_model/core/world_model.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

namespace ssl::wm {
namespace {

using namespace std::chrono_literals;

constexpr time::Duration kFrame = std::chrono::microseconds(13333);
const time::Timestamp kStart = time::Timestamp::from_seconds(1000.0);

DetectionFrame frame_at(int i) {
  DetectionFrame f;
  f.camera_id = 0;
  f.frame_number = static_cast<std::uint32_t>(i);
  f.capture_time = kStart + i * kFrame;
  f.sent_time = f.capture_time;
  return f;
}

struct FlipCase {
  TeamColor us;
  bool blue_on_positive_half;
  bool flipped;
};

class WorldModelTeamFrame : public ::testing::TestWithParam<FlipCase> {};

TEST_P(WorldModelTeamFrame, OurGoalAtNegativeXAnglesAndVelocitiesFlipped) {
  const FlipCase c = GetParam();
  WorldModel model({.team = c.us});
  RefereeInfo referee;
  referee.command = RefereeCommand::kStop;
  referee.blue_team_on_positive_half = c.blue_on_positive_half;
  model.on_referee(referee, kStart);
  EXPECT_EQ(model.team_frame().flipped(), c.flipped);
  // Our robot 1 drives at (1, 0.5) m/s from (2, 1), heading 0.3 rad, in the vision frame; the ball rolls.
  const Vec2 v(1.0, 0.5);
  for (int i = 0; i < 60; ++i) {
    DetectionFrame f = frame_at(i);
    const double t = i * time::to_seconds(kFrame);
    RobotDetection ours{.id = 1, .position = Vec2(2, 1) + v * t, .orientation = 0.3};
    RobotDetection theirs{.id = 4, .position = Vec2(-3, -2), .orientation = 2.0};
    (c.us == TeamColor::kBlue ? f.robots_blue : f.robots_yellow).push_back(ours);
    (c.us == TeamColor::kBlue ? f.robots_yellow : f.robots_blue).push_back(theirs);
    f.balls.push_back({.position = Vec2(-1, 0.5)});
    model.on_detection(f, f.capture_time);
  }
  const time::Timestamp t_end = kStart + 59 * kFrame;
  const WorldState world = model.state_at_vision_time(t_end);
  ASSERT_EQ(world.friendly.size(), 1u);
  ASSERT_EQ(world.enemy.size(), 1u);
  const double sign = c.flipped ? -1 : 1;
  const Vec2 expected = Vec2(2, 1) + v * (59 * time::to_seconds(kFrame));
  EXPECT_NEAR(world.friendly[0].position.x(), sign * expected.x(), 1e-3);
  EXPECT_NEAR(world.friendly[0].position.y(), sign * expected.y(), 1e-3);
  EXPECT_NEAR(world.friendly[0].velocity.x(), sign * v.x(), 0.02);
  EXPECT_NEAR(world.friendly[0].velocity.y(), sign * v.y(), 0.02);
  const double heading = c.flipped ? 0.3 - std::numbers::pi : 0.3;
  EXPECT_NEAR(world.friendly[0].orientation, heading, 1e-3);
  EXPECT_NEAR(world.enemy[0].orientation, c.flipped ? 2.0 - std::numbers::pi : 2.0, 1e-3);
  EXPECT_NEAR(world.ball.position.x(), sign * -1.0, 1e-3);
  // Our goal is at negative x: the goal we defend in the vision frame maps to the field's -x end.
  const bool we_defend_positive_vision_x = (c.us == TeamColor::kBlue) == c.blue_on_positive_half;
  const Vec2 our_goal_vision(we_defend_positive_vision_x ? 6.0 : -6.0, 0);
  EXPECT_LT(model.team_frame().point(our_goal_vision).x(), 0);
  EXPECT_EQ(world.flipped, c.flipped);
}

INSTANTIATE_TEST_SUITE_P(AllSidesAndColours, WorldModelTeamFrame,
                         ::testing::Values(FlipCase{TeamColor::kBlue, false, false},
                                           FlipCase{TeamColor::kBlue, true, true},
                                           FlipCase{TeamColor::kYellow, false, true},
                                           FlipCase{TeamColor::kYellow, true, false}));

TEST(WorldModel, TeleportedRobotReinitialisesItsTrack) {
  WorldModel model({.team = TeamColor::kBlue});
  int i = 0;
  for (; i < 30; ++i) {
    DetectionFrame f = frame_at(i);
    f.robots_blue.push_back({.id = 3, .position = Vec2(0, 0), .orientation = 0});
    model.on_detection(f, f.capture_time);
  }
  for (int k = 0; k < 3; ++k, ++i) {
    DetectionFrame f = frame_at(i);
    f.robots_blue.push_back({.id = 3, .position = Vec2(3, 3), .orientation = 1.0});
    model.on_detection(f, f.capture_time);
  }
  const WorldState world = model.state_at_vision_time(frame_at(i - 1).capture_time);
  ASSERT_EQ(world.friendly.size(), 1u);
  EXPECT_NEAR(world.friendly[0].position.x(), 3.0, 1e-3);
  EXPECT_NEAR(world.friendly[0].orientation, 1.0, 1e-3);
  EXPECT_LT(world.friendly[0].velocity.norm(), 0.1);  // no huge velocity from the jump
  EXPECT_EQ(model.counters().teleports, 1u);
  EXPECT_EQ(model.counters().tracks_created, 1u);
}

TEST(WorldModel, SingleFarOffFalseBallDetectionDoesNotMoveTheBall) {
  WorldModel model({.team = TeamColor::kBlue});
  for (int i = 0; i < 60; ++i) {
    DetectionFrame f = frame_at(i);
    f.balls.push_back({.position = i == 30 ? Vec2(-3, 2) : Vec2(1, 1)});
    if (i == 40) f.balls.push_back({.position = Vec2(4, -2)});  // a second, false ball next to the real one
    model.on_detection(f, f.capture_time);
    const WorldState world = model.state_at_vision_time(f.capture_time);
    ASSERT_TRUE(world.has_ball);
    EXPECT_NEAR(world.ball.position.x(), 1.0, 1e-3) << "frame " << i;
    EXPECT_NEAR(world.ball.position.y(), 1.0, 1e-3) << "frame " << i;
  }
  EXPECT_EQ(model.counters().outliers_rejected, 2u);
  EXPECT_EQ(model.counters().kicks_detected, 0u);
}

TEST(WorldModel, BallIsPlacedAtTheDribblerOfTheRobotThatHoldsItByFeedback) {
  WorldModel model({.team = TeamColor::kYellow});
  for (int i = 0; i < 20; ++i) {
    DetectionFrame f = frame_at(i);
    f.robots_yellow.push_back({.id = 2, .position = Vec2(1, 1), .orientation = std::numbers::pi / 2});
    f.balls.push_back({.position = Vec2(-2, -2)});
    model.on_detection(f, f.capture_time);
  }
  model.on_feedback({.id = 2, .ball_in_dribbler = true}, frame_at(20).capture_time);
  DetectionFrame f = frame_at(20);  // the ball is hidden under the robot: no detection
  f.robots_yellow.push_back({.id = 2, .position = Vec2(1, 1), .orientation = std::numbers::pi / 2});
  model.on_detection(f, f.capture_time);
  const WorldState world = model.state_at_vision_time(f.capture_time);
  // Yellow, blue_on_positive_half unknown (false): yellow defends +x, the team frame is turned by pi.
  EXPECT_TRUE(world.ball.in_dribbler);
  const Vec2 dribbler_vision(1.0, 1.0 + 0.078 + 0.0215);
  EXPECT_NEAR(world.ball.position.x(), -dribbler_vision.x(), 1e-6);
  EXPECT_NEAR(world.ball.position.y(), -dribbler_vision.y(), 1e-6);
  EXPECT_EQ(world.possession, Possession::kFriendly);
  ASSERT_TRUE(world.possessing_robot.has_value());
  EXPECT_EQ(*world.possessing_robot, 2u);
}

TEST(WorldModel, PossessionGoesToTheEnemyRobotWhoseDribblerTouchesTheBallAndStays) {
  WorldModel model({.team = TeamColor::kBlue});
  for (int i = 0; i < 40; ++i) {
    DetectionFrame f = frame_at(i);
    f.robots_yellow.push_back({.id = 5, .position = Vec2(0, 0), .orientation = 0});
    f.robots_blue.push_back({.id = 1, .position = Vec2(-2, 0), .orientation = 0});
    f.balls.push_back({.position = i < 20 ? Vec2(0.1, 0) : Vec2(2.0, 0)});
    model.on_detection(f, f.capture_time);
  }
  const WorldState world = model.state_at_vision_time(frame_at(39).capture_time);
  EXPECT_EQ(world.possession, Possession::kEnemy);  // last touched
  EXPECT_EQ(world.possessing_robot.value_or(99), 5u);
}

TEST(WorldModel, LostTrackIsDroppedAndStateIsPredictedToNow) {
  WorldModel model({.team = TeamColor::kBlue});
  for (int i = 0; i < 40; ++i) {
    DetectionFrame f = frame_at(i);
    const double t = i * time::to_seconds(kFrame);
    if (i < 30) f.robots_yellow.push_back({.id = 0, .position = Vec2(1, 0), .orientation = 0});
    f.robots_blue.push_back({.id = 0, .position = Vec2(t, 0), .orientation = 0});
    f.sent_time = f.capture_time + 10ms;
    model.on_detection(f, f.sent_time + 1ms);  // 1 ms network, host clock = vision clock + 0
  }
  // Latency compensation: state(now) is the state at now - offset on the vision clock.
  const time::Timestamp now = frame_at(39).capture_time + 20ms + 1ms;
  const WorldState world = model.state(now);
  ASSERT_EQ(world.friendly.size(), 1u);
  EXPECT_NEAR(world.friendly[0].position.x(), 39 * time::to_seconds(kFrame) + 0.020, 2e-3);
  for (int i = 40; i < 120; ++i) {
    DetectionFrame f = frame_at(i);
    f.robots_blue.push_back({.id = 0, .position = Vec2(0, 0), .orientation = 0});
    model.on_detection(f, f.capture_time);
  }
  EXPECT_EQ(model.counters().tracks_lost, 1u);
  EXPECT_EQ(model.state_at_vision_time(frame_at(119).capture_time).enemy.size(), 0u);
}

TEST(WorldModel, AVisionClockThatRunsSlowerThanOursIsFollowed) {
  // grSim stamps its simulated time, which fell 2 % behind the wall clock on a loaded machine: after 48 s of
  // frames the host is 1 s ahead of the vision clock beyond the fixed offset. state(now) must still be the
  // state at the newest capture (plus the frame's age), not 1 s further along the robot's velocity.
  WorldModel model({.team = TeamColor::kBlue});
  const double rate = 0.98;  // vision seconds per host second
  const time::Timestamp host_start = time::Timestamp::from_seconds(1.8e9);
  time::Timestamp now;
  for (int i = 0; i < 3600; ++i) {  // 75 Hz
    DetectionFrame f = frame_at(i);  // vision clock
    const double t = time::to_seconds(f.capture_time - frame_at(0).capture_time);
    f.robots_blue.push_back({.id = 0, .position = Vec2(-2 + 0.5 * std::sin(t), 0), .orientation = 0});
    f.sent_time = f.capture_time;
    now = host_start + time::duration_from_seconds(t / rate + 0.001);
    model.on_detection(f, now);
  }
  const double newest = 0.5 * std::sin(time::to_seconds(frame_at(3599).capture_time - frame_at(0).capture_time)) - 2;
  const WorldState world = model.state(now);
  ASSERT_EQ(world.friendly.size(), 1u);
  EXPECT_NEAR(world.friendly[0].position.x(), newest, 0.005);
  EXPECT_NEAR(*model.clock_offset(), time::to_seconds(now - frame_at(3599).sent_time), 0.002);
}

}  // namespace
}  // namespace ssl::wm
