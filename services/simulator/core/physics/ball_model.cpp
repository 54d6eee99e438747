#include "services/simulator/core/physics/ball_model.h"

#include <algorithm>

namespace ssl::sim {

void apply_carpet_friction(BallGroundMotion& motion, double normal_delta_v, const PhysicsParams& params) {
  if (!(normal_delta_v > 0.0)) return;
  const double k = params.ball_inertia_factor;
  const Vec2 slip = motion.velocity - motion.spin_velocity;
  const double slip_speed = slip.norm();
  // A slip below 1 um/s is rounding left over from the step that ended sliding.
  constexpr double kRollingSlip = 1e-6;
  if (slip_speed > kRollingSlip) {
    const double budget = normal_delta_v * params.ball_sliding_deceleration / params.gravity;
    const double to_rolling = slip_speed * k / (1.0 + k);
    const Vec2 direction = slip / slip_speed;
    if (budget < to_rolling) {
      motion.velocity -= direction * budget;
      motion.spin_velocity += direction * (budget / k);
      return;
    }
    motion.velocity -= direction * to_rolling;
    motion.spin_velocity = motion.velocity;
    return;
  }
  const double speed = motion.velocity.norm();
  const double budget = normal_delta_v * params.ball_rolling_deceleration / params.gravity;
  if (speed <= budget) {
    motion.velocity = Vec2::Zero();
  } else {
    motion.velocity *= (speed - budget) / speed;
  }
  motion.spin_velocity = motion.velocity;
}

}  // namespace ssl::sim
