#include "services/simulator/core/physics/robot_kinematics.h"

#include <gtest/gtest.h>

#include <cmath>

namespace ssl::sim {
namespace {

constexpr double kWheelDistance = 0.081;

TEST(SimPhysicsKinematics, PureRotationTurnsEveryWheelAlikeAndForwardSplitsLeftAndRight) {
  const RobotSpec spec;
  const auto spin = wheel_velocities_from_local(spec, kWheelDistance, Vec3(0, 0, 2.0));
  for (double w : spin) EXPECT_NEAR(w, 2.0 * kWheelDistance, 1e-12);

  // Forward: the right wheels push forward-left-ish (positive, CCW about the centre), the left ones
  // negative; front right at 60 degrees clockwise from forward gets cos(30 deg) of the speed.
  const auto forward = wheel_velocities_from_local(spec, kWheelDistance, Vec3(1.0, 0, 0));
  EXPECT_NEAR(forward[0], std::sin(1.0472), 1e-9);   // front right
  EXPECT_NEAR(forward[1], std::sin(2.3562), 1e-9);   // back right
  EXPECT_NEAR(forward[2], -std::sin(2.3562), 1e-9);  // back left
  EXPECT_NEAR(forward[3], -std::sin(1.0472), 1e-9);  // front left
}

TEST(SimPhysicsKinematics, WheelConversionRoundTripsForAnyRigidMotion) {
  RobotSpec spec;
  for (const Vec3& local : {Vec3(1.2, -0.4, 3.0), Vec3(0, 2.0, 0), Vec3(-0.7, 0.3, -5.0)}) {
    const Vec3 back = local_velocity_from_wheels(spec, kWheelDistance,
                                                 wheel_velocities_from_local(spec, kWheelDistance, local));
    EXPECT_NEAR((back - local).norm(), 0.0, 1e-9) << local.transpose();
  }
  spec.wheel_angles = {0.9, 2.2, -2.4, -1.1};  // another layout
  const Vec3 local(0.5, 1.5, -2.0);
  const Vec3 back = local_velocity_from_wheels(spec, kWheelDistance,
                                               wheel_velocities_from_local(spec, kWheelDistance, local));
  EXPECT_NEAR((back - local).norm(), 0.0, 1e-9);
}

TEST(SimPhysicsKinematics, InconsistentWheelSpeedsGiveTheLeastSquaresMotion) {
  const RobotSpec spec;
  // Front right alone: no rigid motion produces it; the least-squares answer reproduces it best.
  const std::array<double, 4> wheels{1.0, 0, 0, 0};
  const Vec3 local = local_velocity_from_wheels(spec, kWheelDistance, wheels);
  const auto predicted = wheel_velocities_from_local(spec, kWheelDistance, local);
  // The residual is orthogonal to every column of the wheel matrix (normal equations).
  for (const Vec3& column_probe : {Vec3(1, 0, 0), Vec3(0, 1, 0), Vec3(0, 0, 1)}) {
    const auto column = wheel_velocities_from_local(spec, kWheelDistance, column_probe);
    double dot = 0;
    for (int i = 0; i < 4; ++i) dot += (predicted[i] - wheels[i]) * column[i];
    EXPECT_NEAR(dot, 0.0, 1e-12);
  }
  EXPECT_GT(local.norm(), 0.1);
}

TEST(SimPhysicsKinematics, RampSpeedsUpAndBrakesWithTheirOwnLimits) {
  const double dt = 0.01;
  // Speeding up from rest: speed-up limit.
  EXPECT_NEAR(ramp_velocity(Vec2(0, 0), Vec2(2, 0), 3.0, 5.0, dt).x(), 0.03, 1e-12);
  // Braking along the same line: brake limit.
  EXPECT_NEAR(ramp_velocity(Vec2(2, 0), Vec2(0, 0), 3.0, 5.0, dt).x(), 1.95, 1e-12);
  // Reachable targets are reached exactly.
  EXPECT_EQ(ramp_velocity(Vec2(1, 0), Vec2(1.01, 0), 3.0, 5.0, dt), Vec2(1.01, 0));
  // Reversal: braking from 0.1 m/s to standstill takes 0.02 s > dt, so the whole step brakes.
  EXPECT_NEAR(ramp_velocity(Vec2(0.1, 0), Vec2(-1, 0), 3.0, 5.0, dt).x(), 0.05, 1e-12);
  // ... and with standstill inside the step: 0.02 m/s takes 0.004 s braking, then 0.006 s speeding up.
  EXPECT_NEAR(ramp_velocity(Vec2(0.02, 0), Vec2(-1, 0), 3.0, 5.0, dt).x(), -0.018, 1e-12);
  // Angular: the same law.
  EXPECT_NEAR(ramp_angular_velocity(0.0, 10.0, 30.0, 50.0, dt), 0.3, 1e-12);
  EXPECT_NEAR(ramp_angular_velocity(1.0, -10.0, 30.0, 50.0, dt), 0.5, 1e-12);
}

TEST(SimPhysicsKinematics, RampNeverChangesSpeedFasterThanTheLimits) {
  const double dt = 0.004;
  const double speedup = 2.0;
  const double brake = 6.0;
  for (int i = 0; i < 200; ++i) {
    const double a = 0.37 * i;
    const Vec2 current = (0.01 * (i % 17)) * Vec2(std::cos(a), std::sin(a));
    const Vec2 target = (0.2 * (i % 11)) * Vec2(std::cos(1.9 * a), std::sin(1.9 * a));
    const Vec2 next = ramp_velocity(current, target, speedup, brake, dt);
    EXPECT_LE(next.norm() - current.norm(), speedup * dt + 1e-12) << i;
    EXPECT_GE(next.norm() - current.norm(), -brake * dt - 1e-12) << i;
    EXPECT_LE((next - target).norm(), (current - target).norm() + 1e-12) << i;
  }
}

TEST(SimPhysicsKinematics, ClampNormKeepsDirection) {
  EXPECT_EQ(clamp_norm(Vec2(3, 4), 10.0), Vec2(3, 4));
  EXPECT_NEAR((clamp_norm(Vec2(3, 4), 1.0) - Vec2(0.6, 0.8)).norm(), 0.0, 1e-15);
}

}  // namespace
}  // namespace ssl::sim
