#include "services/simulator/core/physics/ball_model.h"

#include <gtest/gtest.h>

namespace ssl::sim {
namespace {

TEST(SimPhysicsBallModel, SlidingBallDeceleratesAtTheSlidingRateAndSpinsUp) {
  PhysicsParams params;
  const double dt = 0.001;
  BallGroundMotion motion{Vec2(4.0, 0), Vec2::Zero()};
  apply_carpet_friction(motion, params.gravity * dt, params);
  EXPECT_NEAR(motion.velocity.x(), 4.0 - params.ball_sliding_deceleration * dt, 1e-12);
  EXPECT_NEAR(motion.spin_velocity.x(), params.ball_sliding_deceleration * dt / params.ball_inertia_factor,
              1e-12);
  EXPECT_EQ(motion.velocity.y(), 0.0);
}

TEST(SimPhysicsBallModel, SlidingEndsAtTheRollingSpeedThenRollingDecelerates) {
  PhysicsParams params;
  const double dt = 0.0005;
  const double k = params.ball_inertia_factor;
  BallGroundMotion motion{Vec2(0, -3.0), Vec2::Zero()};
  int steps = 0;
  while ((motion.velocity - motion.spin_velocity).norm() > 0 && steps < 100000) {
    apply_carpet_friction(motion, params.gravity * dt, params);
    ++steps;
  }
  // v + k s is conserved while sliding: rolling starts at v0 / (1 + k) (5/7 for a solid sphere).
  EXPECT_NEAR(motion.velocity.y(), -3.0 / (1 + k), 1e-9);
  EXPECT_NEAR(steps * dt, 3.0 * k / ((1 + k) * params.ball_sliding_deceleration), 2 * dt);
  const double rolling_speed = motion.velocity.norm();
  apply_carpet_friction(motion, params.gravity * dt, params);
  EXPECT_NEAR(rolling_speed - motion.velocity.norm(), params.ball_rolling_deceleration * dt, 1e-12);
  EXPECT_EQ(motion.spin_velocity, motion.velocity);
}

TEST(SimPhysicsBallModel, RollingBallStopsAndNoNormalImpulseMeansNoFriction) {
  PhysicsParams params;
  BallGroundMotion motion{Vec2(0.0001, 0), Vec2(0.0001, 0)};
  apply_carpet_friction(motion, params.gravity * 0.001, params);
  EXPECT_EQ(motion.velocity, Vec2::Zero());
  EXPECT_EQ(motion.spin_velocity, Vec2::Zero());

  BallGroundMotion flying{Vec2(2.0, 1.0), Vec2::Zero()};
  apply_carpet_friction(flying, 0.0, params);
  EXPECT_EQ(flying.velocity, Vec2(2.0, 1.0));
}

TEST(SimPhysicsBallModel, HardTouchdownRemovesAtMostTheSlipThatEndsInRolling) {
  PhysicsParams params;
  const double k = params.ball_inertia_factor;
  // A chip landing at 2.83 m/s down with restitution 0.5: normal impulse 1.5 * 2.83 m/s, enough friction
  // to stop the slip, so the ball leaves the first hop rolling at 5/7 of its horizontal speed.
  BallGroundMotion motion{Vec2(2.83, 0), Vec2::Zero()};
  apply_carpet_friction(motion, 1.5 * 2.83, params);
  EXPECT_NEAR(motion.velocity.x(), 2.83 / (1 + k), 1e-12);
  EXPECT_EQ(motion.spin_velocity, motion.velocity);
  // A gentle touchdown only removes mu * impulse.
  BallGroundMotion gentle{Vec2(2.0, 0), Vec2::Zero()};
  apply_carpet_friction(gentle, 0.1, params);
  EXPECT_NEAR(gentle.velocity.x(), 2.0 - 0.1 * params.ball_sliding_deceleration / params.gravity, 1e-12);
}

}  // namespace
}  // namespace ssl::sim
