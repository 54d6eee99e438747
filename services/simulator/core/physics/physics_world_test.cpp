// Behaviour of PhysicsWorld against closed-form predictions and the RobotLimits / kick / dribbler contracts.
#include "services/simulator/core/physics/physics_world.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <numbers>
#include <ostream>
#include <random>
#include <stdexcept>
#include <string>

#include "services/simulator/core/physics/robot_kinematics.h"

namespace ssl::sim {
namespace {

using namespace std::chrono_literals;

constexpr RobotKey kBlue0{TeamColor::kBlue, 0};
constexpr RobotKey kBlue1{TeamColor::kBlue, 1};
constexpr RobotKey kYellow0{TeamColor::kYellow, 0};
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr double kInf = std::numeric_limits<double>::infinity();

void run(PhysicsWorld& world, double seconds) { world.step(time::duration_from_seconds(seconds)); }

Vec2 xy(const Vec3& v) { return v.head<2>(); }

// By value, so that `robot_in(world.snapshot(), key)` never dangles.
RobotState robot_in(const WorldSnapshot& snapshot, RobotKey key) {
  for (const RobotState& robot : snapshot.robots) {
    if (robot.key == key) return robot;
  }
  throw std::out_of_range("robot not in snapshot");
}

// Where the ball touches the front of a robot at `position` facing `orientation`.
Vec3 ball_at_front(const PhysicsWorld& world, Vec2 position, double orientation) {
  const double reach = world.team_spec(TeamColor::kBlue).center_to_dribbler + world.params().ball_radius;
  return {position.x() + reach * std::cos(orientation), position.y() + reach * std::sin(orientation),
          world.params().ball_radius};
}

// Moves the ball from the centre mark to where no test robot is.
void park_ball(PhysicsWorld& world) {
  ASSERT_TRUE(world.teleport_ball(Vec3(0, -4, world.params().ball_radius), Vec3::Zero()));
}

RobotCommand local_velocity(double forward, double left, double angular) {
  RobotCommand command;
  command.move = RobotCommand::Move::kLocalVelocity;
  command.velocity = Vec3(forward, left, angular);
  return command;
}

RobotCommand global_velocity(double x, double y, double angular) {
  RobotCommand command;
  command.move = RobotCommand::Move::kGlobalVelocity;
  command.velocity = Vec3(x, y, angular);
  return command;
}

// Closed-form stopping distance of a ball that starts sliding (no spin) at v0 (physics_params.h).
double stopping_distance(const PhysicsParams& p, double v0) {
  const double k = p.ball_inertia_factor;
  const double t_slide = v0 * k / ((1 + k) * p.ball_sliding_deceleration);
  const double d_slide = v0 * t_slide - p.ball_sliding_deceleration * t_slide * t_slide / 2;
  const double v_roll = v0 / (1 + k);
  return d_slide + v_roll * v_roll / (2 * p.ball_rolling_deceleration);
}

// A field big enough for a 4 m/s ball (13 m) to stop in the open.
FieldGeometry big_field() {
  FieldGeometry field;
  field.field_length = 30;
  field.field_width = 20;
  return field;
}

// ---------------------------------------------------------------------------------------------------------
// Ball on the open field

struct BallRunCase {
  double speed;    // m/s
  double sliding;  // m/s^2
  double rolling;  // m/s^2
};

void PrintTo(const BallRunCase& c, std::ostream* out) {
  *out << c.speed << " m/s, sliding " << c.sliding << " m/s^2, rolling " << c.rolling << " m/s^2";
}

class SimPhysicsBallStop : public testing::TestWithParam<BallRunCase> {};

TEST_P(SimPhysicsBallStop, StopsAtTheClosedFormDistanceWithBothDecelerations) {
  PhysicsParams params;
  params.ball_sliding_deceleration = GetParam().sliding;
  params.ball_rolling_deceleration = GetParam().rolling;
  PhysicsWorld world(big_field(), params);
  const double v0 = GetParam().speed;
  const Vec2 direction = Vec2(3, -1).normalized();
  const Vec2 start(-10, 2);
  ASSERT_TRUE(world.teleport_ball(Vec3(start.x(), start.y(), params.ball_radius),
                                  Vec3(v0 * direction.x(), v0 * direction.y(), 0)));

  const double k = params.ball_inertia_factor;
  const double t_slide = v0 * k / ((1 + k) * params.ball_sliding_deceleration);
  const double v_roll = v0 / (1 + k);
  const double t_stop = t_slide + v_roll / params.ball_rolling_deceleration;

  // Sliding phase: speed falls at the sliding deceleration.
  run(world, 0.2 * t_slide);
  const WorldSnapshot a = world.snapshot();
  run(world, 0.6 * t_slide);
  const WorldSnapshot b = world.snapshot();
  const double sliding = (a.ball.velocity.norm() - b.ball.velocity.norm()) / (b.time - a.time).count() * 1e9;
  EXPECT_NEAR(sliding, params.ball_sliding_deceleration, 0.01 * params.ball_sliding_deceleration);

  // Rolling phase: starts at v0 / (1 + k), falls at the rolling deceleration.
  run(world, 0.2 * t_slide + 0.1 * (t_stop - t_slide));
  const WorldSnapshot c = world.snapshot();
  const double expected_c = v_roll - params.ball_rolling_deceleration * (c.time.to_seconds() - t_slide);
  EXPECT_NEAR(c.ball.velocity.norm(), expected_c, 0.01 * v0);
  run(world, 0.5 * (t_stop - t_slide));
  const WorldSnapshot d = world.snapshot();
  const double rolling = (c.ball.velocity.norm() - d.ball.velocity.norm()) / (d.time - c.time).count() * 1e9;
  EXPECT_NEAR(rolling, params.ball_rolling_deceleration, 0.01 * params.ball_rolling_deceleration);

  // Stop: the distance travelled along the kick direction, and the time it took.
  run(world, 0.5 * (t_stop - t_slide) + 0.5);
  const WorldSnapshot end = world.snapshot();
  EXPECT_EQ(end.ball.velocity, Vec3::Zero());
  const Vec2 travelled = xy(end.ball.position) - start;
  const double expected = stopping_distance(params, v0);
  EXPECT_NEAR(travelled.norm(), expected, 0.02 * expected);
  EXPECT_NEAR(travelled.normalized().dot(direction), 1.0, 1e-9);
  EXPECT_NEAR(end.ball.position.z(), params.ball_radius, 1e-4);
}

INSTANTIATE_TEST_SUITE_P(SimPhysicsSpeeds, SimPhysicsBallStop,
                         testing::Values(BallRunCase{4.0, 3.0, 0.35}, BallRunCase{1.5, 3.0, 0.35},
                                         BallRunCase{4.0, 2.0, 0.6}),
                         [](const testing::TestParamInfo<BallRunCase>& param_info) {  // in hundredths
                           const auto centi = [](double v) { return std::to_string(std::lround(v * 100)); };
                           const BallRunCase& c = param_info.param;
                           return "speed" + centi(c.speed) + "_slide" + centi(c.sliding) + "_roll" +
                                  centi(c.rolling);
                         });

TEST(SimPhysicsBall, RollingTeleportOnlyRolls) {
  PhysicsParams params;
  PhysicsWorld world(FieldGeometry::division_a(), params);
  ASSERT_TRUE(world.teleport_ball(Vec3(-3, 0, params.ball_radius), Vec3(2.0, 0, 0), BallSpin::kRolling));
  run(world, 10.0);
  const double expected = 2.0 * 2.0 / (2 * params.ball_rolling_deceleration);
  EXPECT_NEAR(world.snapshot().ball.position.x() + 3, expected, 0.02 * expected);
}

TEST(SimPhysicsBall, RestingBallStaysPut) {
  PhysicsWorld world(FieldGeometry::division_a(), PhysicsParams{});
  ASSERT_TRUE(world.teleport_ball(Vec3(1, 2, 0.0215), Vec3::Zero()));
  run(world, 3.0);
  const WorldSnapshot snapshot = world.snapshot();
  EXPECT_NEAR((snapshot.ball.position - Vec3(1, 2, 0.0215)).norm(), 0.0, 1e-4);
  EXPECT_EQ(xy(snapshot.ball.velocity), Vec2::Zero());
}

// ---------------------------------------------------------------------------------------------------------
// Kicks

// Steps one sub-step at a time until the ball's speed exceeds `threshold`; returns that first speed.
double speed_after_kick(PhysicsWorld& world, double threshold) {
  const auto substep = time::duration_from_seconds(world.params().step);
  for (int i = 0; i < 500; ++i) {
    world.step(substep);
    const double speed = world.snapshot().ball.velocity.norm();
    if (speed > threshold) return speed;
  }
  return 0.0;
}

class SimPhysicsKick : public testing::Test {
 protected:
  SimPhysicsKick() : world_(FieldGeometry::division_a(), PhysicsParams{}) {
    world_.add_robot(kBlue0, Vec2(-2, 1), 0.5);
    world_.teleport_ball(ball_at_front(world_, Vec2(-2, 1), 0.5), Vec3::Zero());
  }
  PhysicsWorld world_;
};

TEST_F(SimPhysicsKick, FlatKickLeavesAtTheRequestedSpeedAlongTheHeading) {
  RobotCommand command;
  command.kick_speed = 4.2;
  ASSERT_TRUE(world_.set_command(kBlue0, command));
  const double speed = speed_after_kick(world_, 1.0);
  // One sub-step of sliding friction has acted already.
  EXPECT_NEAR(speed, 4.2, 0.02);
  const Vec3 velocity = world_.snapshot().ball.velocity;
  EXPECT_NEAR(std::atan2(velocity.y(), velocity.x()), 0.5, 1e-6);
  EXPECT_NEAR(velocity.z(), 0.0, 1e-6);
}

TEST_F(SimPhysicsKick, FlatKickIsClampedToTheSpecMaximum) {
  RobotCommand command;
  command.kick_speed = 12.0;
  ASSERT_TRUE(world_.set_command(kBlue0, command));
  EXPECT_NEAR(speed_after_kick(world_, 1.0), 6.5, 0.02);

  // A spec that allows more: the new maximum applies to the robot that is already on the field.
  RobotSpec spec = world_.team_spec(TeamColor::kBlue);
  spec.max_linear_kick_speed = 8.0;
  ASSERT_TRUE(world_.set_team_spec(TeamColor::kBlue, spec));
  ASSERT_TRUE(world_.teleport_robot(kBlue0, Vec2(-2, 1), 0.5, Vec2::Zero(), 0));
  ASSERT_TRUE(world_.teleport_ball(ball_at_front(world_, Vec2(-2, 1), 0.5), Vec3::Zero()));
  EXPECT_NEAR(speed_after_kick(world_, 1.0), 8.0, 0.02);
}

TEST_F(SimPhysicsKick, ChipIsClampedToTheChipMaximumAndLeavesAtItsAngle) {
  RobotSpec spec = world_.team_spec(TeamColor::kBlue);
  spec.max_chip_kick_speed = 3.0;
  ASSERT_TRUE(world_.set_team_spec(TeamColor::kBlue, spec));
  RobotCommand command;
  command.kick_speed = 5.0;
  command.kick_angle = std::numbers::pi / 6;
  ASSERT_TRUE(world_.set_command(kBlue0, command));
  EXPECT_NEAR(speed_after_kick(world_, 1.0), 3.0, 0.02);
  const Vec3 velocity = world_.snapshot().ball.velocity;
  EXPECT_NEAR(std::atan2(velocity.z(), xy(velocity).norm()), std::numbers::pi / 6, 0.01);
}

TEST_F(SimPhysicsKick, HeldKickCommandFiresOnlyOnceUntilTheBallHasLeft) {
  // A kick so weak that friction stops the ball still touching the front: it must not fire again.
  RobotCommand command;
  command.kick_speed = 0.05;
  ASSERT_TRUE(world_.set_command(kBlue0, command));
  const Vec3 start = world_.snapshot().ball.position;
  run(world_, 1.0);
  WorldSnapshot snapshot = world_.snapshot();
  const double moved = (snapshot.ball.position - start).norm();
  EXPECT_GT(moved, 1e-5);  // it did fire
  // ... once: 0.4 mm sliding + 1.8 mm rolling (firing every sub-step would push it out of contact, 10 mm).
  EXPECT_LT(moved, 0.004);
  EXPECT_TRUE(robot_in(snapshot, kBlue0).ball_contact);

  // Re-sending the same command does not re-arm it either.
  ASSERT_TRUE(world_.set_command(kBlue0, command));
  run(world_, 0.5);
  EXPECT_NEAR((world_.snapshot().ball.position - start).norm(), moved, 1e-6);

  // Once the ball has left the front, touching it again fires again.
  command.move = RobotCommand::Move::kLocalVelocity;
  command.velocity = Vec3(-0.5, 0, 0);
  ASSERT_TRUE(world_.set_command(kBlue0, command));
  run(world_, 0.3);
  EXPECT_FALSE(robot_in(world_.snapshot(), kBlue0).ball_contact);
  command.velocity = Vec3(0.5, 0, 0);
  command.kick_speed = 2.0;
  ASSERT_TRUE(world_.set_command(kBlue0, command));
  run(world_, 0.6);
  EXPECT_GT(world_.snapshot().ball.velocity.norm(), 1.0);
}

TEST_F(SimPhysicsKick, NoKickWithoutContact) {
  ASSERT_TRUE(world_.teleport_ball(Vec3(0, -2, 0.0215), Vec3::Zero()));
  RobotCommand command;
  command.kick_speed = 5.0;
  ASSERT_TRUE(world_.set_command(kBlue0, command));
  run(world_, 0.5);
  EXPECT_EQ(world_.snapshot().ball.velocity, Vec3::Zero());
  EXPECT_FALSE(robot_in(world_.snapshot(), kBlue0).ball_contact);
}

TEST(SimPhysicsChip, FirstTouchdownMatchesTheBallisticPrediction) {
  PhysicsWorld world(FieldGeometry::division_a(), PhysicsParams{});
  const double yaw = -2.5;
  world.add_robot(kBlue0, Vec2(3, 2), yaw);
  ASSERT_TRUE(world.teleport_ball(ball_at_front(world, Vec2(3, 2), yaw), Vec3::Zero()));
  const double speed = 4.0;
  const double angle = std::numbers::pi / 4;
  RobotCommand command;
  command.kick_speed = speed;
  command.kick_angle = angle;
  ASSERT_TRUE(world.set_command(kBlue0, command));

  const double g = world.params().gravity;
  const double r = world.params().ball_radius;
  const auto substep = time::duration_from_seconds(world.params().step);
  Vec3 launch = Vec3::Zero();
  double apex = 0;
  bool launched = false;
  std::optional<Vec3> touchdown;
  Vec3 previous = world.snapshot().ball.position;
  for (int i = 0; i < 2000 && !touchdown; ++i) {
    world.step(substep);
    const BallState ball = world.snapshot().ball;
    if (!launched && ball.velocity.z() > 0) {
      launched = true;
      launch = previous;
    }
    apex = std::max(apex, ball.position.z());
    if (launched && ball.velocity.z() > 0 && ball.position.z() < r + 0.005 && apex > 0.1) {
      touchdown = ball.position;
    }
    previous = ball.position;
  }
  ASSERT_TRUE(touchdown.has_value());
  const double expected_range = speed * speed * std::sin(2 * angle) / g;
  const double expected_apex = std::pow(speed * std::sin(angle), 2) / (2 * g);
  EXPECT_NEAR((xy(*touchdown) - xy(launch)).norm(), expected_range, 0.02 * expected_range);
  EXPECT_NEAR(apex - r, expected_apex, 0.02 * expected_apex);
  const Vec2 direction = xy(*touchdown) - xy(launch);
  EXPECT_NEAR(std::atan2(direction.y(), direction.x()), yaw, 1e-3);

  // It bounces lower, then rolls and stops.
  double second_apex = 0;
  for (int i = 0; i < 200; ++i) {
    world.step(substep);
    second_apex = std::max(second_apex, world.snapshot().ball.position.z() - r);
  }
  const double restitution = world.params().ball_restitution_ground;
  EXPECT_NEAR(second_apex, restitution * restitution * expected_apex, 0.1 * expected_apex);
  run(world, 15.0);
  EXPECT_EQ(world.snapshot().ball.velocity, Vec3::Zero());
  EXPECT_NEAR(world.snapshot().ball.position.z(), r, 1e-4);
}

// ---------------------------------------------------------------------------------------------------------
// Robot motion

RobotSpec asymmetric_spec() {
  RobotSpec spec;
  spec.limits.acc_speedup_absolute_max = 2.0;
  spec.limits.acc_brake_absolute_max = 5.0;
  spec.limits.vel_absolute_max = 2.5;
  spec.limits.acc_speedup_angular_max = 20.0;
  spec.limits.acc_brake_angular_max = 40.0;
  spec.limits.vel_angular_max = 6.0;
  return spec;
}

TEST(SimPhysicsRobot, SpeedUpAndBrakeAreBoundedAndTheSpeedIsClamped) {
  PhysicsWorld world(FieldGeometry::division_a(), PhysicsParams{});
  park_ball(world);
  const RobotSpec spec = asymmetric_spec();
  ASSERT_TRUE(world.set_team_spec(TeamColor::kBlue, spec));
  ASSERT_TRUE(world.add_robot(kBlue0, Vec2(-4, -3), 0.3));
  ASSERT_TRUE(world.set_command(kBlue0, global_velocity(8.0, 6.0, 0)));  // 10 m/s: clamped to 2.5

  const double eps = 1e-9;
  double max_speedup = 0;
  double max_brake = 0;
  WorldSnapshot previous = world.snapshot();
  for (int i = 0; i < 150; ++i) {  // 2 s
    if (i == 100) {
      ASSERT_TRUE(world.set_command(kBlue0, global_velocity(0, 0, 0)));
    }
    run(world, 1.0 / 75);
    const WorldSnapshot now = world.snapshot();
    const double dt = (now.time - previous.time).count() * 1e-9;
    const double change = robot_in(now, kBlue0).velocity.norm() - robot_in(previous, kBlue0).velocity.norm();
    EXPECT_LE(change, spec.limits.acc_speedup_absolute_max * dt + eps) << i;
    EXPECT_GE(change, -spec.limits.acc_brake_absolute_max * dt - eps) << i;
    max_speedup = std::max(max_speedup, change / dt);
    max_brake = std::max(max_brake, -change / dt);
    EXPECT_LE(robot_in(now, kBlue0).velocity.norm(), spec.limits.vel_absolute_max + eps);
    if (i == 99) {
      // Reached and held the clamped speed in the commanded direction.
      EXPECT_NEAR((robot_in(now, kBlue0).velocity - Vec2(2.0, 1.5)).norm(), 0.0, 1e-9);
    }
    previous = now;
  }
  // The limits are really used, not just respected.
  EXPECT_NEAR(max_speedup, spec.limits.acc_speedup_absolute_max, 1e-6);
  EXPECT_NEAR(max_brake, spec.limits.acc_brake_absolute_max, 1e-6);
  EXPECT_EQ(robot_in(previous, kBlue0).velocity, Vec2::Zero());
}

TEST(SimPhysicsRobot, AngularSpeedUpAndBrakeAreBoundedAndClamped) {
  PhysicsWorld world(FieldGeometry::division_a(), PhysicsParams{});
  park_ball(world);
  const RobotSpec spec = asymmetric_spec();
  ASSERT_TRUE(world.set_team_spec(TeamColor::kYellow, spec));
  ASSERT_TRUE(world.add_robot(kYellow0, Vec2(1, 1), 0));
  ASSERT_TRUE(world.set_command(kYellow0, local_velocity(0, 0, -50.0)));
  const double eps = 1e-9;
  double max_speedup = 0;
  double max_brake = 0;
  WorldSnapshot previous = world.snapshot();
  for (int i = 0; i < 100; ++i) {
    if (i == 60) {
      ASSERT_TRUE(world.set_command(kYellow0, local_velocity(0, 0, 0)));
    }
    run(world, 1.0 / 60);
    const WorldSnapshot now = world.snapshot();
    const double dt = (now.time - previous.time).count() * 1e-9;
    const double change = std::abs(robot_in(now, kYellow0).angular_velocity) -
                          std::abs(robot_in(previous, kYellow0).angular_velocity);
    EXPECT_LE(change, spec.limits.acc_speedup_angular_max * dt + eps);
    EXPECT_GE(change, -spec.limits.acc_brake_angular_max * dt - eps);
    EXPECT_LE(std::abs(robot_in(now, kYellow0).angular_velocity), spec.limits.vel_angular_max + eps);
    max_speedup = std::max(max_speedup, change / dt);
    max_brake = std::max(max_brake, -change / dt);
    if (i == 59) {
      EXPECT_NEAR(robot_in(now, kYellow0).angular_velocity, -6.0, 1e-9);
    }
    previous = now;
  }
  EXPECT_NEAR(max_speedup, spec.limits.acc_speedup_angular_max, 1e-6);
  EXPECT_NEAR(max_brake, spec.limits.acc_brake_angular_max, 1e-6);
  EXPECT_EQ(robot_in(previous, kYellow0).angular_velocity, 0.0);
  EXPECT_NEAR(robot_in(previous, kYellow0).position.x(), 1.0, 1e-9);  // turned in place
}

TEST(SimPhysicsRobot, LocalVelocityIsInTheRobotFrameAndGlobalInTheFieldFrame) {
  PhysicsWorld world(FieldGeometry::division_a(), PhysicsParams{});
  park_ball(world);
  const double facing_y = std::numbers::pi / 2;
  ASSERT_TRUE(world.add_robot(kBlue0, Vec2(0, 0), facing_y));
  ASSERT_TRUE(world.add_robot(kBlue1, Vec2(-2, 0), facing_y));
  ASSERT_TRUE(world.add_robot(kYellow0, Vec2(2, 0), facing_y));
  ASSERT_TRUE(world.set_command(kBlue0, local_velocity(1.0, 0, 0)));     // forward = +y
  ASSERT_TRUE(world.set_command(kBlue1, local_velocity(0, 1.0, 0)));     // left = -x
  ASSERT_TRUE(world.set_command(kYellow0, global_velocity(1.0, 0, 0)));  // +x whatever the heading
  run(world, 1.0);
  const WorldSnapshot snapshot = world.snapshot();
  EXPECT_NEAR((robot_in(snapshot, kBlue0).velocity - Vec2(0, 1)).norm(), 0.0, 1e-9);
  EXPECT_NEAR((robot_in(snapshot, kBlue1).velocity - Vec2(-1, 0)).norm(), 0.0, 1e-9);
  EXPECT_NEAR((robot_in(snapshot, kYellow0).velocity - Vec2(1, 0)).norm(), 0.0, 1e-9);
  EXPECT_GT(robot_in(snapshot, kBlue0).position.y(), 0.6);
  EXPECT_NEAR(robot_in(snapshot, kBlue0).position.x(), 0.0, 1e-9);
  EXPECT_NEAR(robot_in(snapshot, kBlue0).orientation, facing_y, 1e-9);
}

TEST(SimPhysicsRobot, LocalVelocityTurnsWithTheRobotWhileGlobalDoesNot) {
  PhysicsWorld world(FieldGeometry::division_a(), PhysicsParams{});
  park_ball(world);
  ASSERT_TRUE(world.add_robot(kBlue0, Vec2(-1, 0), 0));
  ASSERT_TRUE(world.add_robot(kBlue1, Vec2(1, 0), 0));
  ASSERT_TRUE(world.set_command(kBlue0, local_velocity(0.5, 0, 1.0)));
  ASSERT_TRUE(world.set_command(kBlue1, global_velocity(0.5, 0, 1.0)));
  run(world, 2.0);
  const WorldSnapshot snapshot = world.snapshot();
  const RobotState local = robot_in(snapshot, kBlue0);
  const RobotState global = robot_in(snapshot, kBlue1);
  // The heading is sampled once per sub-step, so the velocity lags the turn by at most omega * step.
  EXPECT_NEAR(std::atan2(local.velocity.y(), local.velocity.x()), local.orientation,
              1.0 * world.params().step);
  EXPECT_NEAR((global.velocity - Vec2(0.5, 0)).norm(), 0.0, 1e-9);
  EXPECT_GT(local.orientation, 1.5);
}

TEST(SimPhysicsRobot, WheelVelocitiesDriveTheMotionTheyEncode) {
  PhysicsParams params;
  PhysicsWorld world(FieldGeometry::division_a(), params);
  park_ball(world);
  const double heading = 0.7;
  ASSERT_TRUE(world.add_robot(kBlue0, Vec2(0, 0), heading));
  const RobotSpec& spec = world.team_spec(TeamColor::kBlue);
  const Vec3 local(1.0, -0.5, 0);
  RobotCommand command;
  command.move = RobotCommand::Move::kWheelVelocity;
  command.wheel_velocity =
      wheel_velocities_from_local(spec, spec.radius * params.wheel_distance_fraction, local);
  ASSERT_TRUE(world.set_command(kBlue0, command));
  run(world, 1.0);
  const RobotState robot = robot_in(world.snapshot(), kBlue0);
  const Vec2 expected = geom::rotate(Vec2(local.x(), local.y()), geom::Angle::from_radians(heading));
  EXPECT_NEAR((robot.velocity - expected).norm(), 0.0, 1e-9);
  EXPECT_NEAR(robot.angular_velocity, 0.0, 1e-9);

  // Equal wheel speeds turn the robot in place, CCW for positive speeds.
  command.wheel_velocity = {0.2, 0.2, 0.2, 0.2};
  ASSERT_TRUE(world.set_command(kBlue0, command));
  run(world, 1.0);
  const RobotState turning = robot_in(world.snapshot(), kBlue0);
  EXPECT_NEAR(turning.angular_velocity, 0.2 / (spec.radius * params.wheel_distance_fraction), 1e-9);
  EXPECT_NEAR(turning.velocity.norm(), 0.0, 1e-9);
}

TEST(SimPhysicsRobot, NoCommandMeansBrakingToAStandstill) {
  PhysicsWorld world(FieldGeometry::division_a(), PhysicsParams{});
  park_ball(world);
  ASSERT_TRUE(world.add_robot(kBlue0, Vec2(0, 0), 0));
  ASSERT_TRUE(world.teleport_robot(kBlue0, Vec2(0, 0), 0, Vec2(2, 0), 3.0));
  run(world, 1.0);
  const RobotState robot = robot_in(world.snapshot(), kBlue0);
  EXPECT_EQ(robot.velocity, Vec2::Zero());
  EXPECT_EQ(robot.angular_velocity, 0.0);
  EXPECT_NEAR(robot.position.x(), 2.0 * 2.0 / (2 * 4.0), 0.01);  // braked at acc_brake_absolute_max
}

// ---------------------------------------------------------------------------------------------------------
// Dribbler

TEST(SimPhysicsDribbler, KeepsTheBallWhileTurningHalfAroundAndDrivingThenReleasesIt) {
  PhysicsWorld world(FieldGeometry::division_a(), PhysicsParams{});
  ASSERT_TRUE(world.add_robot(kBlue0, Vec2(1, 1), 0));
  ASSERT_TRUE(world.teleport_ball(ball_at_front(world, Vec2(1, 1), 0), Vec3::Zero()));
  const double reach = world.team_spec(TeamColor::kBlue).center_to_dribbler + world.params().ball_radius;
  RobotCommand command = local_velocity(0, 0, 3.0);
  command.dribbler_rpm = 5000;
  ASSERT_TRUE(world.set_command(kBlue0, command));

  // The ball stays at the front, within a few millimetres, during the whole turn.
  const auto check_held = [&](const WorldSnapshot& snapshot, int i) {
    const RobotState robot = robot_in(snapshot, kBlue0);
    const Vec2 front =
        robot.position + reach * Vec2(std::cos(robot.orientation), std::sin(robot.orientation));
    EXPECT_TRUE(robot.ball_contact) << i;
    EXPECT_LT((xy(snapshot.ball.position) - front).norm(), 0.005) << i;
  };
  double turned = 0;
  double previous_orientation = 0;
  int i = 0;
  for (; turned < std::numbers::pi && i < 200; ++i) {
    run(world, 1.0 / 75);
    const WorldSnapshot snapshot = world.snapshot();
    const double orientation = robot_in(snapshot, kBlue0).orientation;
    turned += std::remainder(orientation - previous_orientation, 2 * std::numbers::pi);
    previous_orientation = orientation;
    check_held(snapshot, i);
  }
  EXPECT_GE(turned, std::numbers::pi);
  EXPECT_GE(std::abs(robot_in(world.snapshot(), kBlue0).angular_velocity), 2.9);  // at speed, not creeping

  // Drive slowly forwards (now towards -x) and sideways.
  command.velocity = Vec3(0.5, 0.2, 0);
  ASSERT_TRUE(world.set_command(kBlue0, command));
  for (int j = 0; j < 75; ++j) {
    run(world, 1.0 / 75);
    check_held(world.snapshot(), 1000 + j);
  }
  EXPECT_LT(robot_in(world.snapshot(), kBlue0).position.x(), 0.8);

  // Stop, dribbler off, back away: the ball stays behind.
  command.velocity = Vec3::Zero();
  ASSERT_TRUE(world.set_command(kBlue0, command));
  run(world, 0.5);
  command.dribbler_rpm = 0;
  command.velocity = Vec3(-0.5, 0, 0);
  ASSERT_TRUE(world.set_command(kBlue0, command));
  const Vec3 ball_before = world.snapshot().ball.position;
  run(world, 1.0);
  const WorldSnapshot end = world.snapshot();
  EXPECT_FALSE(robot_in(end, kBlue0).ball_contact);
  EXPECT_GT((xy(end.ball.position) - robot_in(end, kBlue0).position).norm(), reach + 0.2);
  EXPECT_LT((end.ball.position - ball_before).norm(), 0.02);
}

TEST(SimPhysicsDribbler, WithoutTheDribblerATurningRobotLosesTheBall) {
  PhysicsWorld world(FieldGeometry::division_a(), PhysicsParams{});
  ASSERT_TRUE(world.add_robot(kBlue0, Vec2(1, 1), 0));
  ASSERT_TRUE(world.teleport_ball(ball_at_front(world, Vec2(1, 1), 0), Vec3::Zero()));
  ASSERT_TRUE(world.set_command(kBlue0, local_velocity(0, 0, 3.0)));
  run(world, 1.0);
  EXPECT_FALSE(robot_in(world.snapshot(), kBlue0).ball_contact);
}

TEST(SimPhysicsDribbler, ContactOnlyAtTheFlatFront) {
  PhysicsWorld world(FieldGeometry::division_a(), PhysicsParams{});
  ASSERT_TRUE(world.add_robot(kBlue0, Vec2(0, 0), 0));
  const double r = world.params().ball_radius;
  ASSERT_TRUE(world.teleport_ball(ball_at_front(world, Vec2(0, 0), 0), Vec3::Zero()));
  EXPECT_TRUE(robot_in(world.snapshot(), kBlue0).ball_contact);
  ASSERT_TRUE(world.teleport_ball(Vec3(-0.09 - r, 0, r), Vec3::Zero()));  // touching the back
  EXPECT_FALSE(robot_in(world.snapshot(), kBlue0).ball_contact);
  ASSERT_TRUE(world.teleport_ball(Vec3(0.078 + r, 0.04, r), Vec3::Zero()));  // beside the dribbler
  EXPECT_FALSE(robot_in(world.snapshot(), kBlue0).ball_contact);
}

// ---------------------------------------------------------------------------------------------------------
// Walls, goals, collisions

TEST(SimPhysicsField, BallBouncesOffTheWallSlowerAndNeverLeaves) {
  PhysicsParams params;
  PhysicsWorld world(FieldGeometry::division_a(), params);
  const FieldGeometry& field = world.field();
  const double wall_y = field.field_width / 2 + field.boundary_width;
  ASSERT_TRUE(world.teleport_ball(Vec3(1, 3.8, params.ball_radius), Vec3(0, 3.0, 0)));
  double max_y = 0;
  double speed_in = 0;
  double speed_out = 0;
  bool bounced = false;
  const auto substep = time::duration_from_seconds(params.step);
  for (int i = 0; i < 1000; ++i) {
    const double vy_before = world.snapshot().ball.velocity.y();
    world.step(substep);
    const BallState ball = world.snapshot().ball;
    max_y = std::max(max_y, ball.position.y());
    if (!bounced && ball.velocity.y() < 0) {
      bounced = true;
      speed_in = vy_before;
      speed_out = -ball.velocity.y();
    }
  }
  ASSERT_TRUE(bounced);
  EXPECT_NEAR(speed_out, params.ball_restitution_wall * speed_in, 0.05 * speed_in);
  // Contacts are solved once touching, so the ball may sink into the wall by one sub-step of motion.
  EXPECT_LE(max_y, wall_y - params.ball_radius + speed_in * params.step + 0.0005);
  EXPECT_LT(world.snapshot().ball.position.y(), wall_y - 0.1);  // it came back

  // Fast balls at every wall and corner, flat and chipped, stay inside.
  for (int k = 0; k < 16; ++k) {
    const double a = 2 * std::numbers::pi * k / 16 + 0.1;
    const double vz = k % 2 == 0 ? 0.0 : 3.0;
    ASSERT_TRUE(
        world.teleport_ball(Vec3(0, 0, params.ball_radius), Vec3(7 * std::cos(a), 7 * std::sin(a), vz)));
    for (int i = 0; i < 600; ++i) {
      world.step(10ms);
      const Vec3 p = world.snapshot().ball.position;
      ASSERT_LT(std::abs(p.x()), field.field_length / 2 + field.boundary_width_goal_line) << k;
      ASSERT_LT(std::abs(p.y()), wall_y) << k;
      ASSERT_GT(p.z(), params.ball_radius - 0.002) << k;
    }
  }
}

TEST(SimPhysicsField, BallRollingIntoAGoalStaysInside) {
  for (double sign : {1.0, -1.0}) {
    PhysicsParams params;
    PhysicsWorld world(FieldGeometry::division_b(), params);
    const FieldGeometry& field = world.field();
    const double goal_line = field.field_length / 2;
    ASSERT_TRUE(world.teleport_ball(Vec3(sign * (goal_line - 1.5), 0.2, params.ball_radius),
                                    Vec3(sign * 4.0, 0.1, 0)));
    run(world, 6.0);
    const BallState ball = world.snapshot().ball;
    EXPECT_GT(sign * ball.position.x(), goal_line + params.ball_radius) << sign;
    EXPECT_LT(sign * ball.position.x(), goal_line + field.goal_depth) << sign;
    EXPECT_LT(std::abs(ball.position.y()), field.goal_width / 2) << sign;
    EXPECT_EQ(ball.velocity, Vec3::Zero()) << sign;
  }
}

TEST(SimPhysicsField, BallBesideTheGoalHitsItsSideWallFromOutside) {
  PhysicsParams params;
  PhysicsWorld world(FieldGeometry::division_a(), params);
  const FieldGeometry& field = world.field();
  // Rolling along +x at y just outside the goal's side wall: stopped by the wall's front (the goal line),
  // never inside the goal.
  const double y = field.goal_width / 2 + field.goal_wall_thickness / 2;
  ASSERT_TRUE(world.teleport_ball(Vec3(5.0, y, params.ball_radius), Vec3(3.0, 0, 0)));
  for (int i = 0; i < 300; ++i) {
    world.step(10ms);
    const Vec3 p = world.snapshot().ball.position;
    ASSERT_LT(p.x(), field.field_length / 2 - params.ball_radius + 0.003) << i;
  }
}

TEST(SimPhysicsCollision, RobotsCollideInsteadOfOverlapping) {
  PhysicsWorld world(FieldGeometry::division_a(), PhysicsParams{});
  ASSERT_TRUE(world.add_robot(kBlue0, Vec2(-1, 0.03), 0));
  ASSERT_TRUE(world.add_robot(kYellow0, Vec2(1, 0), std::numbers::pi));
  ASSERT_TRUE(world.set_command(kBlue0, global_velocity(2.0, 0, 0)));
  ASSERT_TRUE(world.set_command(kYellow0, global_velocity(-2.0, 0, 0)));
  const double radius = world.team_spec(TeamColor::kBlue).radius;
  const double front = world.team_spec(TeamColor::kBlue).center_to_dribbler;
  double closest = 10;
  for (int i = 0; i < 300; ++i) {
    world.step(10ms);
    const WorldSnapshot s = world.snapshot();
    closest = std::min(closest, (robot_in(s, kBlue0).position - robot_in(s, kYellow0).position).norm());
  }
  // Front to front (flat faces) they can come as close as 2 * center_to_dribbler, never closer.
  EXPECT_GT(closest, 2 * front - 0.005);
  EXPECT_LT(closest, 2 * radius);  // they did meet

  // Driving into a wall: stopped at it.
  ASSERT_TRUE(world.set_command(kBlue0, global_velocity(0, 3.0, 0)));
  run(world, 4.0);
  const double wall_y = world.field().field_width / 2 + world.field().boundary_width;
  EXPECT_LT(robot_in(world.snapshot(), kBlue0).position.y(), wall_y - radius + 0.005);
  EXPECT_GT(robot_in(world.snapshot(), kBlue0).position.y(), wall_y - radius - 0.02);
}

TEST(SimPhysicsCollision, ATeamSpecReshapesTheRobotsAlreadyOnTheField) {
  PhysicsParams params;
  PhysicsWorld world(FieldGeometry::division_a(), params);
  park_ball(world);
  ASSERT_TRUE(world.add_robot(kYellow0, Vec2(0, 3), std::numbers::pi / 2));
  RobotSpec spec;
  spec.radius = 0.08;
  spec.center_to_dribbler = 0.06;
  ASSERT_TRUE(world.set_team_spec(TeamColor::kYellow, spec));
  // Driven front first into the touch-line wall, it stops with its new flat front against it; driven
  // backwards into the goal-line wall, with its new radius.
  ASSERT_TRUE(world.set_command(kYellow0, global_velocity(0, 2.0, 0)));
  run(world, 2.0);
  const double wall_y = world.field().field_width / 2 + world.field().boundary_width;
  EXPECT_NEAR(robot_in(world.snapshot(), kYellow0).position.y(), wall_y - spec.center_to_dribbler, 0.003);
  ASSERT_TRUE(world.teleport_robot(kYellow0, Vec2(5.5, 3), std::numbers::pi, Vec2::Zero(), 0));
  ASSERT_TRUE(world.set_command(kYellow0, local_velocity(-2.0, 0, 0)));
  run(world, 2.0);
  const double wall_x = world.field().field_length / 2 + world.field().boundary_width_goal_line;
  EXPECT_NEAR(robot_in(world.snapshot(), kYellow0).position.x(), wall_x - spec.radius, 0.003);
  // Its front moved in: a ball at the old front distance no longer touches it, one at the new does.
  ASSERT_TRUE(world.teleport_robot(kYellow0, Vec2(0, 0), 0, Vec2::Zero(), 0));
  ASSERT_TRUE(world.set_command(kYellow0, RobotCommand{}));
  ASSERT_TRUE(world.teleport_ball(Vec3(0.078 + params.ball_radius, 0, params.ball_radius), Vec3::Zero()));
  EXPECT_FALSE(robot_in(world.snapshot(), kYellow0).ball_contact);
  ASSERT_TRUE(world.teleport_ball(Vec3(0.06 + params.ball_radius, 0, params.ball_radius), Vec3::Zero()));
  EXPECT_TRUE(robot_in(world.snapshot(), kYellow0).ball_contact);
  run(world, 0.5);
  EXPECT_NEAR(world.snapshot().ball.position.x(), 0.06 + params.ball_radius, 0.001);  // touching, not pushed
}

TEST(SimPhysicsCollision, RobotPushesTheBallAndTheBallBouncesOffAStandingRobot) {
  PhysicsParams params;
  PhysicsWorld world(FieldGeometry::division_a(), params);
  ASSERT_TRUE(world.add_robot(kBlue0, Vec2(0, 0), 0));
  ASSERT_TRUE(world.teleport_ball(Vec3(-1, 0, params.ball_radius), Vec3(3.0, 0, 0)));
  for (int i = 0; i < 100; ++i) {
    world.step(10ms);
    ASSERT_LT(world.snapshot().ball.position.x(), -0.09 - params.ball_radius + 0.003);
  }
  EXPECT_LT(world.snapshot().ball.position.x(), -0.2);  // bounced back
}

// ---------------------------------------------------------------------------------------------------------
// World bookkeeping, determinism, invalid input

TEST(SimPhysicsWorld, RobotsAreAddedOnceSortedByKeyAndRemoved) {
  PhysicsWorld world(FieldGeometry::division_a(), PhysicsParams{});
  EXPECT_TRUE(world.add_robot(kYellow0, Vec2(1, 0), 0));
  EXPECT_TRUE(world.add_robot(kBlue1, Vec2(2, 0), 0));
  EXPECT_TRUE(world.add_robot(kBlue0, Vec2(3, 0), 0));
  EXPECT_FALSE(world.add_robot(kBlue0, Vec2(4, 0), 0));
  EXPECT_FALSE(world.add_robot({TeamColor::kBlue, kMaxRobotsPerTeam}, Vec2(4, 0), 0));
  EXPECT_TRUE(world.add_robot({TeamColor::kBlue, kMaxRobotsPerTeam - 1}, Vec2(4, 0), 0));
  WorldSnapshot snapshot = world.snapshot();
  ASSERT_EQ(snapshot.robots.size(), 4u);
  EXPECT_TRUE(std::is_sorted(snapshot.robots.begin(), snapshot.robots.end(),
                             [](const RobotState& a, const RobotState& b) { return a.key < b.key; }));
  EXPECT_EQ(robot_in(snapshot, kBlue0).position, Vec2(3, 0));
  EXPECT_TRUE(world.remove_robot(kBlue1));
  EXPECT_FALSE(world.remove_robot(kBlue1));
  EXPECT_FALSE(world.has_robot(kBlue1));
  EXPECT_FALSE(world.set_command(kBlue1, local_velocity(1, 0, 0)));
  EXPECT_EQ(world.snapshot().robots.size(), 3u);
}

TEST(SimPhysicsWorld, StepCarriesTheRemainderOfASubStep) {
  PhysicsParams params;
  params.step = 0.002;
  PhysicsWorld world(FieldGeometry::division_a(), params);
  world.step(5ms);
  EXPECT_EQ(world.time(), time::Timestamp::from_milliseconds(4));
  world.step(1ms);
  EXPECT_EQ(world.time(), time::Timestamp::from_milliseconds(6));
  for (int i = 0; i < 75; ++i) world.step(time::Duration(13'333'333));
  EXPECT_LE(world.time().nanoseconds(), 6'000'000 + 75 * 13'333'333);
  EXPECT_GT(world.time().nanoseconds(), 6'000'000 + 75 * 13'333'333 - 2'000'000);
  world.step(-5ms);
  world.step(0ms);
  EXPECT_EQ(world.snapshot().time, world.time());
}

// 11 v 11 with pseudo-random velocity commands, kicks and dribbling, and a moving ball.
void drive_match(PhysicsWorld& world, int frames) {
  std::mt19937 rng(42);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  for (TeamColor team : {TeamColor::kBlue, TeamColor::kYellow}) {
    const double side = team == TeamColor::kBlue ? -1.0 : 1.0;
    for (std::uint32_t id = 0; id < 11; ++id) {
      world.add_robot({team, id}, Vec2(side * (0.5 + 0.4 * id), -4 + 0.8 * id),
                      side > 0 ? std::numbers::pi : 0);
    }
  }
  world.teleport_ball(Vec3(0, 0, 0.0215), Vec3(2.0, 1.0, 0));
  for (int frame = 0; frame < frames; ++frame) {
    if (frame % 10 == 0) {
      for (const RobotState& robot : world.snapshot().robots) {
        RobotCommand command = global_velocity(2 * unit(rng), 2 * unit(rng), 4 * unit(rng));
        command.kick_speed = unit(rng) > 0.5 ? 5.0 : 0.0;
        command.kick_angle = unit(rng) > 0.5 ? 0.5 : 0.0;
        command.dribbler_rpm = unit(rng) > 0 ? 3000 : 0;
        world.set_command(robot.key, command);
      }
    }
    world.step(time::Duration(13'333'333));
  }
}

void expect_identical(const WorldSnapshot& a, const WorldSnapshot& b) {
  EXPECT_EQ(a.time, b.time);
  EXPECT_EQ(a.ball.position, b.ball.position);
  EXPECT_EQ(a.ball.velocity, b.ball.velocity);
  ASSERT_EQ(a.robots.size(), b.robots.size());
  for (std::size_t i = 0; i < a.robots.size(); ++i) {
    EXPECT_EQ(a.robots[i].key, b.robots[i].key);
    EXPECT_EQ(a.robots[i].position, b.robots[i].position) << i;
    EXPECT_EQ(a.robots[i].orientation, b.robots[i].orientation) << i;
    EXPECT_EQ(a.robots[i].velocity, b.robots[i].velocity) << i;
    EXPECT_EQ(a.robots[i].angular_velocity, b.robots[i].angular_velocity) << i;
    EXPECT_EQ(a.robots[i].ball_contact, b.robots[i].ball_contact) << i;
  }
}

TEST(SimPhysicsWorld, SameCallsGiveBitIdenticalSnapshots) {
  PhysicsWorld first(FieldGeometry::division_a(), PhysicsParams{});
  PhysicsWorld second(FieldGeometry::division_a(), PhysicsParams{});
  drive_match(first, 600);
  drive_match(second, 600);
  expect_identical(first.snapshot(), second.snapshot());
  // The match really moved things (a frozen world would be trivially deterministic).
  const WorldSnapshot s = first.snapshot();
  double moved = 0;
  for (const RobotState& robot : s.robots) moved += robot.velocity.norm();
  EXPECT_GT(moved, 1.0);
  for (const RobotState& robot : s.robots) {
    EXPECT_TRUE(robot.position.allFinite());
    EXPECT_LT(std::abs(robot.position.x()), 7.0);
    EXPECT_LT(std::abs(robot.position.y()), 5.5);
  }

  // A moved world carries on exactly like the original.
  PhysicsWorld moved_world = std::move(second);
  moved_world.step(100ms);
  first.step(100ms);
  expect_identical(first.snapshot(), moved_world.snapshot());
}

TEST(SimPhysicsWorld, NonFiniteInputIsRejectedAndChangesNothing) {
  PhysicsWorld world(FieldGeometry::division_a(), PhysicsParams{});
  ASSERT_TRUE(world.add_robot(kBlue0, Vec2(0, 0), 0));
  const RobotCommand good = local_velocity(1.0, 0, 0);
  ASSERT_TRUE(world.set_command(kBlue0, good));
  ASSERT_TRUE(world.teleport_ball(Vec3(1, 1, 0.0215), Vec3(0.5, 0, 0)));
  const WorldSnapshot before = world.snapshot();

  RobotCommand bad = good;
  bad.velocity.y() = kNaN;
  EXPECT_FALSE(world.set_command(kBlue0, bad));
  bad = good;
  bad.wheel_velocity[2] = kInf;
  EXPECT_FALSE(world.set_command(kBlue0, bad));
  bad = good;
  bad.kick_speed = kNaN;
  EXPECT_FALSE(world.set_command(kBlue0, bad));
  bad = good;
  bad.kick_speed = -1;
  EXPECT_FALSE(world.set_command(kBlue0, bad));
  bad = good;
  bad.kick_angle = 2.0;
  EXPECT_FALSE(world.set_command(kBlue0, bad));
  bad = good;
  bad.dribbler_rpm = -kInf;
  EXPECT_FALSE(world.set_command(kBlue0, bad));
  EXPECT_EQ(world.command(kBlue0)->velocity, good.velocity);

  EXPECT_FALSE(world.teleport_ball(Vec3(kNaN, 0, 0), Vec3::Zero()));
  EXPECT_FALSE(world.teleport_ball(Vec3::Zero(), Vec3(0, kInf, 0)));
  EXPECT_FALSE(world.teleport_robot(kBlue0, Vec2(kNaN, 0), 0, Vec2::Zero(), 0));
  EXPECT_FALSE(world.teleport_robot(kBlue0, Vec2(0, 0), kInf, Vec2::Zero(), 0));
  EXPECT_FALSE(world.teleport_robot(kBlue0, Vec2(0, 0), 0, Vec2(0, kNaN), 0));
  EXPECT_FALSE(world.teleport_robot(kBlue0, Vec2(0, 0), 0, Vec2::Zero(), kNaN));
  EXPECT_FALSE(world.add_robot(kBlue1, Vec2(kInf, 0), 0));
  EXPECT_FALSE(world.add_robot(kBlue1, Vec2(0, 0), kNaN));
  RobotSpec spec;
  spec.mass = kNaN;
  EXPECT_FALSE(world.set_team_spec(TeamColor::kBlue, spec));
  spec = RobotSpec{};
  spec.limits.acc_brake_absolute_max = kInf;
  EXPECT_FALSE(world.set_team_spec(TeamColor::kBlue, spec));
  spec = RobotSpec{};
  spec.center_to_dribbler = 0.2;
  EXPECT_FALSE(world.set_team_spec(TeamColor::kBlue, spec));
  EXPECT_EQ(world.team_spec(TeamColor::kBlue).mass, RobotSpec{}.mass);

  expect_identical(world.snapshot(), before);
  run(world, 1.0);
  const WorldSnapshot after = world.snapshot();
  EXPECT_TRUE(after.ball.position.allFinite());
  EXPECT_TRUE(robot_in(after, kBlue0).position.allFinite());
  EXPECT_NEAR(robot_in(after, kBlue0).velocity.x(), 1.0, 1e-9);
}

TEST(SimPhysicsWorld, InvalidConstructionThrows) {
  PhysicsParams params;
  params.step = -1;
  EXPECT_THROW(PhysicsWorld(FieldGeometry::division_a(), params), std::invalid_argument);
  params = PhysicsParams{};
  params.ball_restitution_wall = kNaN;
  EXPECT_THROW(PhysicsWorld(FieldGeometry::division_a(), params), std::invalid_argument);
  FieldGeometry field;
  field.boundary_width_goal_line = 0.1;  // the goal would stick through the wall
  EXPECT_THROW(PhysicsWorld(field, PhysicsParams{}), std::invalid_argument);
  EXPECT_FALSE(validate(PhysicsParams{}).has_value());
}

}  // namespace
}  // namespace ssl::sim
