// PhysicsWorld: the simulator's rigid-body world (Bullet 3, double precision, hidden behind a pImpl):
// carpet, boundary walls, two goals, one ball and up to 16 robots per team. SI units in the SSL-Vision
// global frame (types.h); z is up, the carpet is z = 0. Simulated time starts at 0 and advances only in
// step(). Pure: no threads, sockets, logging, globals or wall clock. Deterministic: the same calls in the
// same order give bit-identical snapshots. Not thread-safe (one owner calls everything).
//
//   PhysicsWorld world(FieldGeometry::division_a(), PhysicsParams{});
//   world.add_robot({TeamColor::kBlue, 3}, {-1.0, 0.0}, 0.0);
//   world.teleport_ball({-0.9, 0.0, 0.0215}, Vec3::Zero());          // touching its front
//   world.set_command({TeamColor::kBlue, 3}, {.kick_speed = 5.0});   // flat kick: fires on contact
//   world.step(std::chrono::microseconds(13'333));                   // any dt; sub-steps of params.step
//   WorldSnapshot now = world.snapshot();
//
// Field. Walls stand at the touch lines + boundary_width and the goal lines + boundary_width_goal_line
// (height PhysicsParams::boundary_wall_height, so no legal chip leaves the walled area). Each goal is open
// towards the field: a back wall and two side walls of goal_wall_thickness and goal_height around the
// goal_width x goal_depth inside, behind the goal line.
//
// Robots are dynamic Bullet bodies (so that the solver makes them collide with each other, the walls
// and the ball), locked to the carpet: they translate in x and y and turn about z only. Their hull is the
// RobotSpec cylinder cut flat at center_to_dribbler in front. Every sub-step each robot's velocity is
// ramped towards its command under its RobotLimits (robot_kinematics.h), starting from the velocity it
// really has, so after a collision it accelerates again within its limits. Command semantics:
//   * kLocalVelocity {forward, left, angular} is held in the robot frame (the global target turns with
//     the robot); kGlobalVelocity {x, y, angular} in the field frame; kWheelVelocity is converted to a
//     local velocity by the least-squares inverse of the wheel matrix; kNone brakes to a standstill.
//   * Speeds are clamped to vel_absolute_max / vel_angular_max before the ramp.
//   * Dribbler: while dribbler_rpm > 0 and the ball touches the flat front within dribbler_width, the
//     ball is held: driven to the point where it touches the front centre, moving with the robot (also
//     while it turns). A ball arriving at a spinning dribbler is caught at once (its speed is absorbed).
//     When the dribbler stops the ball keeps the velocity it had and rolls free.
//   * Kick: kick_speed > 0 fires as soon as the ball touches the front (ball_contact). The ball then
//     leaves at exactly the clamped speed (the robot's own velocity is NOT added; this is the absolute 3D
//     speed of the simulation protocol), along the robot's heading tilted up by kick_angle: 0 is a flat
//     kick clamped to RobotSpec::max_linear_kick_speed, > 0 a chip clamped to max_chip_kick_speed. The
//     ball starts without spin, so it slides. After firing, that robot cannot kick (nor hold the ball)
//     again until the ball has left its front: keeping a kick command armed does not fire twice.
//   Several robots touching the ball in one sub-step: the smallest RobotKey kicks or holds it.
//
// Invalid input never changes the world: the bool-returning calls return false for NaN/inf values,
// ids >= kMaxRobotsPerTeam, unknown robots, negative kick speeds or kick angles outside [0, pi/2);
// step() ignores durations <= 0. The constructor throws std::invalid_argument for an unusable field or
// PhysicsParams (validate()). A moved-from PhysicsWorld may only be destroyed or assigned to.
#pragma once

#include <memory>
#include <optional>

#include "services/simulator/core/physics/physics_params.h"
#include "services/simulator/core/types.h"

namespace ssl::sim {

/// The spin a teleported ball gets.
enum class BallSpin {
  kNone,     // no spin: a moving ball first slides (like a kicked ball)
  kRolling,  // spin matching the velocity: the ball rolls (TeleportBall.roll of the simulation protocol)
};

/// Whether PhysicsWorld takes `command`: every value finite, kick speed >= 0, kick angle in [0, pi/2).
bool command_valid(const RobotCommand& command);

class PhysicsWorld {
 public:
  /// Builds the carpet, walls and goals of `field`, with the ball at rest on the centre mark and no
  /// robots; both teams use RobotSpec{} until set_team_spec(). Throws std::invalid_argument.
  PhysicsWorld(const FieldGeometry& field, const PhysicsParams& params);
  ~PhysicsWorld();
  PhysicsWorld(const PhysicsWorld&) = delete;
  PhysicsWorld& operator=(const PhysicsWorld&) = delete;
  PhysicsWorld(PhysicsWorld&&) noexcept;
  PhysicsWorld& operator=(PhysicsWorld&&) noexcept;

  /// Sets the spec of `team`'s robots, present and future (hull, mass, limits, kick speeds, wheels).
  /// False (and no change) when a value is not finite or out of range (sizes and limits > 0,
  /// center_to_dribbler in (0, radius), kick speeds >= 0).
  bool set_team_spec(TeamColor team, const RobotSpec& spec);
  const RobotSpec& team_spec(TeamColor team) const;

  /// Adds a robot at rest with no command. False when present, id >= 16 or a value is not finite.
  bool add_robot(RobotKey key, Vec2 position, double orientation);
  bool remove_robot(RobotKey key);
  bool has_robot(RobotKey key) const;
  /// Scales one present robot's speed limits by `speed` and its acceleration limits by `acceleration` (both
  /// > 0; 1 = its team's spec), as real robots of one team differ. False when absent or a factor is not.
  bool set_robot_limit_scale(RobotKey key, double speed, double acceleration);
  /// Moves a present robot and sets its velocity (global frame); keeps its command.
  bool teleport_robot(RobotKey key, Vec2 position, double orientation, Vec2 velocity,
                      double angular_velocity);

  /// Moves the ball (z is clamped up to the resting height ball_radius) and sets its velocity (m/s,
  /// global frame) and spin. Releases it from any dribbler. False (no change) when a value is not finite.
  bool teleport_ball(const Vec3& position, const Vec3& velocity, BallSpin spin = BallSpin::kNone);

  /// Replaces the command of a present robot; it is held until the next one. False when the robot is
  /// absent or the command invalid (see the header comment).
  bool set_command(RobotKey key, const RobotCommand& command);
  /// The robot's current command, or nullopt when absent.
  std::optional<RobotCommand> command(RobotKey key) const;

  /// Advances the simulated time by dt in fixed sub-steps of params.step; the part of dt shorter than
  /// a sub-step is carried to the next call. time() and snapshot() refer to the last completed sub-step.
  void step(time::Duration dt);

  /// Time, ball and robots (sorted by key) after the last completed sub-step. ball_contact is true when
  /// the ball touches the robot's flat front within dribbler_width (PhysicsParams dribbler_* tolerances).
  WorldSnapshot snapshot() const;
  time::Timestamp time() const;

  const FieldGeometry& field() const;
  const PhysicsParams& params() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace ssl::sim
