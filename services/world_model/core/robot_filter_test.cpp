// RobotFilter on noise-free synthetic detections: the command history is applied piece by piece, contact
// makes the filter ignore commands, and the uncommanded motion model follows how the robot really moves.
#include "services/world_model/core/robot_filter.h"

#include <gtest/gtest.h>

#include <cmath>

namespace ssl::wm {
namespace {

using namespace std::chrono_literals;

const time::Timestamp kStart = time::Timestamp::from_seconds(2000.0);
constexpr time::Duration kFrame = std::chrono::microseconds(13333);

RobotDetection at(const Vec2& position, double orientation) {
  return {.id = 1, .position = position, .orientation = orientation};
}

// A robot standing still at the origin facing +x, settled by a few detections.
RobotFilter settled_robot(const RobotFilterParams& params = {}) {
  RobotFilter filter(params, at(Vec2::Zero(), 0), kStart);
  for (int i = 1; i <= 20; ++i) filter.update(at(Vec2::Zero(), 0), kStart + i * kFrame);
  return filter;
}

TEST(RobotFilterCommands, PredictionUsesTheCommandInForceForEachPieceNotOnlyTheNewest) {
  RobotFilterParams params;
  params.max_acceleration = 1e6;  // commands reached at once: the positions are easy to check by hand
  RobotFilter filter = settled_robot(params);
  const time::Timestamp t0 = filter.time();
  filter.set_command({.id = 1, .forward = 1.0}, t0);
  filter.set_command({.id = 1, .left = 2.0}, t0 + 20ms);
  // 20 ms forward at 1 m/s, then 20 ms left at 2 m/s.
  const RobotFilter::State x = filter.predict_state(t0 + 40ms);
  EXPECT_NEAR(x(0), 0.020, 1e-3);
  EXPECT_NEAR(x(1), 0.040, 1e-3);
  EXPECT_NEAR(x(3), 0.0, 1e-6);
  EXPECT_NEAR(x(4), 2.0, 1e-6);
  // Only the first piece when predicting to its end.
  const RobotFilter::State half = filter.predict_state(t0 + 20ms);
  EXPECT_NEAR(half(0), 0.020, 1e-3);
  EXPECT_NEAR(half(1), 0.0, 1e-6);
}

TEST(RobotFilterCommands, CommandExpiresAfterTheTimeout) {
  RobotFilterParams params;
  params.max_acceleration = 1e6;
  params.command_timeout = 0.05;
  RobotFilter filter = settled_robot(params);
  const time::Timestamp t0 = filter.time();
  filter.set_command({.id = 1, .forward = 1.0}, t0);
  // In force for 50 ms, then the velocity it left is kept (no command): 0.05 + 0.05 m.
  const RobotFilter::State x = filter.predict_state(t0 + 100ms);
  EXPECT_NEAR(x(0), 0.10, 2e-3);
}

TEST(RobotFilterCommands, ContactIgnoresTheCommand) {
  RobotFilter free_robot = settled_robot();
  RobotFilter pushed = settled_robot();
  const time::Timestamp t0 = free_robot.time();
  for (RobotFilter* f : {&free_robot, &pushed}) f->set_command({.id = 1, .forward = 2.0}, t0);
  // The robot does not move (it is pushing against a wall): the detection stays at the origin.
  for (int i = 1; i <= 10; ++i) {
    free_robot.update(at(Vec2::Zero(), 0), t0 + i * kFrame, false);
    pushed.update(at(Vec2::Zero(), 0), t0 + i * kFrame, true);
  }
  // Trusting the command, the free filter believes in forward speed; the contact filter does not.
  const double free_speed = free_robot.filter().state()(3);
  const double pushed_speed = std::abs(pushed.filter().state()(3));
  EXPECT_GT(free_speed, 0.1);
  EXPECT_LT(pushed_speed, free_speed / 5) << free_speed;
  EXPECT_LT(std::abs(pushed.filter().state()(0)), 0.002);
}

// Detections of a robot turning at `omega` while moving at 1 m/s, either with its velocity turning with
// it (a held local command) or with a constant field velocity.
RobotFilter track_uncommanded(bool velocity_turns) {
  const double omega = 2.0;
  RobotFilter filter({}, at(Vec2::Zero(), 0), kStart);
  for (int i = 1; i <= 150; ++i) {
    const double t = i * time::to_seconds(kFrame);
    const double heading = omega * t;
    // Local: the velocity (1, 0) in the robot frame -> a circle of radius 1/omega.
    const Vec2 position = velocity_turns ? Vec2(std::sin(heading) / omega, (1 - std::cos(heading)) / omega)
                                         : Vec2(t, 0);
    filter.update(at(position, std::remainder(heading, 2 * M_PI)), kStart + i * kFrame);
  }
  return filter;
}

TEST(RobotFilterMotionModel, ChoosesTheTurningVelocityForALocalVelocityRobot) {
  EXPECT_TRUE(track_uncommanded(true).uses_turning_model());
}

TEST(RobotFilterMotionModel, ChoosesTheConstantVelocityForAGloballyControlledRobot) {
  EXPECT_FALSE(track_uncommanded(false).uses_turning_model());
}

TEST(RobotFilterMotionModel, TracksTheCircleWithTheTurningModel) {
  const RobotFilter filter = track_uncommanded(true);
  const double t = 150 * time::to_seconds(kFrame);
  const Vec2 true_velocity(std::cos(2.0 * t), std::sin(2.0 * t));
  EXPECT_LT((filter.filter().state().segment<2>(3) - true_velocity).norm(), 0.02);
}

TEST(RobotFilterMotionModel, TurningModelCarriesTheCentripetalAcceleration) {
  // The acceleration state is the FIELD acceleration in both uncommanded models: on the circle it is the
  // centripetal omega x v (2 rad/s x 1 m/s, towards the centre).
  const RobotFilter filter = track_uncommanded(true);
  const double t = 150 * time::to_seconds(kFrame);
  const Vec2 centripetal = 2.0 * Vec2(-std::sin(2.0 * t), std::cos(2.0 * t));
  EXPECT_LT((filter.filter().state().segment<2>(6) - centripetal).norm(), 0.2);
}

// An enemy speeding up at 1.5 m/s^2 along a fixed field direction (heading fixed) for 1 s.
struct Accelerating {
  Vec2 acceleration = 1.5 * Vec2(std::cos(0.5), std::sin(0.5));
  static constexpr int kFrames = 75;
  double t = kFrames * time::to_seconds(kFrame);
  Vec2 position(double at_t) const { return acceleration * at_t * at_t / 2; }
  RobotFilter track(const RobotFilterParams& params) const {
    RobotFilter filter(params, at(Vec2::Zero(), 0), kStart);
    for (int i = 1; i <= kFrames; ++i) {
      filter.update(at(position(i * time::to_seconds(kFrame)), 0), kStart + i * kFrame);
    }
    return filter;
  }
};

TEST(RobotFilterMotionModel, HeldAccelerationIsEstimatedWithoutLag) {
  const Accelerating robot;
  RobotFilterParams params;
  params.acceleration_time_constant = 0;  // constant acceleration: the model is exact
  const RobotFilter filter = robot.track(params);
  const RobotFilter::State x = filter.filter().state();
  EXPECT_LT((x.segment<2>(6) - robot.acceleration).norm(), 0.05) << x.transpose();
  EXPECT_LT((x.segment<2>(3) - robot.acceleration * robot.t).norm(), 0.005) << x.transpose();
  const RobotFilter::State ahead = filter.predict_state(kStart + Accelerating::kFrames * kFrame + 100ms);
  EXPECT_LT((ahead.head<2>() - robot.position(robot.t + 0.1)).norm(), 0.001) << ahead.transpose();
}

TEST(RobotFilterMotionModel, SingerAccelerationPredictsFarBetterThanConstantVelocity) {
  // The default model lets accelerations decay (they do not last), so it underestimates a held one a
  // little, but 100 ms ahead it is still far closer than a constant velocity (7.5 mm short and lagging).
  const Accelerating robot;
  const RobotFilter filter = robot.track({});
  const RobotFilter::State x = filter.filter().state();
  EXPECT_LT((x.segment<2>(6) - robot.acceleration).norm(), 0.4) << x.transpose();
  const RobotFilter::State ahead = filter.predict_state(kStart + Accelerating::kFrames * kFrame + 100ms);
  const Vec2 constant_velocity = robot.position(robot.t) + 0.1 * robot.acceleration * robot.t;
  const Vec2 truth = robot.position(robot.t + 0.1);
  EXPECT_LT((ahead.head<2>() - truth).norm(), 0.004) << ahead.transpose();
  EXPECT_LT((ahead.head<2>() - truth).norm(), (constant_velocity - truth).norm() / 2);
}

}  // namespace
}  // namespace ssl::wm
