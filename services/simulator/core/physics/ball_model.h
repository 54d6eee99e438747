// The ball's carpet friction: the sliding/rolling model of PhysicsParams, as one pure update that
// PhysicsWorld applies after every sub-step in which the carpet pushed the ball up. SI units, global frame.
//
// State: the horizontal velocity v of the ball's centre and its spin, stored as the rolling velocity s
// the spin alone would give (s = omega x r projected on the carpet; s = v means rolling without slip).
// Per step the carpet's normal impulse per unit mass is n (m/s; g * dt for a resting ball, more at the
// touchdown of a chip). Friction then acts, with k = ball_inertia_factor:
//
//   sliding (slip u = v - s != 0): v -= j u/|u|,  s += (j / k) u/|u|,
//       j = min(n * a_slide / g, |u| k / (1 + k))   (the second term ends the slip exactly: rolling)
//   rolling (u = 0):               v -= min(n * a_roll / g, |v|) v/|v|,  s = v
//
// For a resting ball this is a constant deceleration a_slide while sliding and a_roll while rolling;
// v + k s is conserved while sliding, so a ball without spin starts rolling at v / (1 + k).
#pragma once

#include "services/simulator/core/physics/physics_params.h"
#include "services/simulator/core/types.h"

namespace ssl::sim {

/// Horizontal motion of the ball on the carpet.
struct BallGroundMotion {
  Vec2 velocity = Vec2::Zero();       // m/s, of the centre
  Vec2 spin_velocity = Vec2::Zero();  // m/s, rolling velocity of the spin alone
};

/// Applies one step of carpet friction for a normal impulse per unit mass `normal_delta_v` (m/s, >= 0).
void apply_carpet_friction(BallGroundMotion& motion, double normal_delta_v, const PhysicsParams& params);

}  // namespace ssl::sim
