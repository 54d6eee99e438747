// Robot motion helpers of the physics core: omni-wheel kinematics and the acceleration-limited velocity
// ramp that PhysicsWorld applies to every robot at every sub-step. Pure functions, SI units.
//
// Frames. LOCAL velocity = {forward (towards the dribbler) m/s, left m/s, angular rad/s CCW}; the robot
// frame has x forward, y left. Wheel i sits at RobotSpec::wheel_angles[i], measured from forward CLOCKWISE
// (front right, back right, back left, front left), at `wheel_distance` from the centre. Its surface
// speed is positive when the wheel pushes the robot counter-clockwise about its centre, so four equal
// positive speeds spin the robot CCW in place:
//
//   wheel_i = -sin(theta_i) * forward + cos(theta_i) * left + wheel_distance * angular,  theta_i = -angle_i
//
// wheel_velocities_from_local() is that 4x3 matrix M; local_velocity_from_wheels() is its least-squares
// (Moore-Penrose) inverse (M^T M)^-1 M^T, so wheel speeds that no rigid motion produces (wheels
// fighting each other) give the rigid motion closest to them.
//
// Velocity ramp. The commanded velocity is first clamped to the speed limit; the robot's velocity then
// moves along the straight line towards it. The part of that line on which the speed falls (towards the
// point closest to standstill) uses the brake limit, the rest the speed-up limit, so in one step of dt the
// speed never rises by more than speedup * dt nor falls by more than brake * dt (RobotLimits semantics).
#pragma once

#include <array>

#include "libs/domain/robot_motion.h"
#include "services/simulator/core/types.h"

namespace ssl::sim {

/// Wheel surface speeds (m/s; front right, back right, back left, front left) for a local velocity.
std::array<double, 4> wheel_velocities_from_local(const RobotSpec& spec, double wheel_distance,
                                                  const Vec3& local_velocity);

/// Local velocity {forward, left, angular} that best matches the wheel surface speeds (least squares).
Vec3 local_velocity_from_wheels(const RobotSpec& spec, double wheel_distance,
                                const std::array<double, 4>& wheel_velocity);

/// `v` scaled down to length `max_norm` if longer (max_norm >= 0).
Vec2 clamp_norm(const Vec2& v, double max_norm);

/// One step of the velocity ramp (libs/domain/robot_motion.h, the law the world model replays too).
using ssl::ramp_velocity;

/// The same ramp for an angular velocity (rad/s, rad/s^2).
double ramp_angular_velocity(double current, double target, double speedup, double brake, double dt);

}  // namespace ssl::sim
