// PhysicsParams: every tunable of the simulator's physics core (ssl::sim::PhysicsWorld), in SI units, with
// defaults that give SSL-like behaviour on carpet. Plain data: build it, change fields, pass it to the
// PhysicsWorld constructor, which rejects invalid values (validate() says why).
//
// Ball model (see ball_model.h for the equations). The ball touches the carpet at one point; Coulomb
// friction there acts on the SLIP, the velocity of the contact point = centre velocity minus the rolling
// speed its spin would give. A kicked (or teleported) ball has no spin: it SLIDES, friction decelerates it
// at ball_sliding_deceleration and spins it up at ball_sliding_deceleration / ball_inertia_factor until the
// slip is zero, which happens at 1 / (1 + ball_inertia_factor) of the initial speed (5/7 for a solid
// sphere). From then on it ROLLS and decelerates at ball_rolling_deceleration until it stops. A flat kick
// at v0 therefore stops after, with k = ball_inertia_factor, a_s = sliding, a_r = rolling deceleration:
//
//   t_slide = v0 k / ((1 + k) a_s),  d_slide = v0 t_slide - a_s t_slide^2 / 2,
//   v_roll = v0 / (1 + k),          d_roll = v_roll^2 / (2 a_r),      distance = d_slide + d_roll.
//
// The friction budget of a step is proportional to the normal impulse the carpet gave the ball in that
// step (mu = deceleration / gravity), so the same law damps the horizontal speed at each touchdown of a
// chip (a first hop loses up to k / (1 + k) of its slip, later hops little: compare
// SSL_BallModelChipFixedLoss). Contacts with walls, goals and robots are frictionless; their restitution is
// set per kind below. Bullet combines restitution as a product, so robot-robot contacts bounce with
// ball_restitution_robot^2 and robot-wall contacts with ball_restitution_robot * ball_restitution_wall.
#pragma once

#include <optional>
#include <string>

namespace ssl::sim {

struct PhysicsParams {
  // --- integration ---
  // s, fixed internal sub-step, <= 0.05. At 2 ms a 6.5 m/s ball moves 13 mm per sub-step (less than its
  // radius, so no tunnelling and at most that much overlap at an impact) and an 11 v 11 match runs at
  // ~175x real time on one core (physics_world_benchmark.cpp); 1 ms gives ~80x, 4 ms ~330x.
  double step = 0.002;
  int solver_iterations = 6;  // Bullet sequential-impulse iterations per sub-step
  double gravity = 9.81;      // m/s^2, downwards (-z)

  // --- ball ---
  double ball_radius = 0.0215;              // m
  double ball_mass = 0.046;                 // kg
  double ball_sliding_deceleration = 3.0;   // m/s^2 while the ball slides (ssl-vision acc_slide -3.0)
  double ball_rolling_deceleration = 0.35;  // m/s^2 while it rolls (ssl-vision acc_roll -0.4)
  // I / (m r^2): 0.4 for a solid sphere. Rolling starts at 1 / (1 + k) of the sliding start speed.
  double ball_inertia_factor = 0.4;
  double ball_restitution_ground = 0.5;  // vertical bounce of a chipped ball on the carpet
  double ball_restitution_wall = 0.6;    // boundary walls
  double ball_restitution_goal = 0.2;    // goal walls (damped, so a ball that enters stays inside)
  double ball_restitution_robot = 0.5;   // robot hulls
  // Fraction of the ball's spin kept when a wall, goal or robot contact changes its velocity. 1 =
  // frictionless contact at the ball's equator (physical: the spin axis is horizontal, the contact
  // cannot change it), so a rolling ball that bounces back slides against its own spin and soon stops.
  double ball_collision_spin_retention = 1.0;

  // --- robots ---
  double robot_friction = 0.5;  // Bullet friction coefficient of robot hulls (robot-robot, robot-wall)
  // Distance from the robot centre to the wheels' contact points, as a fraction of RobotSpec::radius
  // (used to convert wheel-velocity commands).
  double wheel_distance_fraction = 0.9;

  // --- dribbler ---
  // The ball counts as touching the dribbler while its centre is within this distance of the point
  // where it would touch the flat front (centre_to_dribbler + ball_radius ahead of the robot centre),
  // measured along the robot's forward axis, and laterally within dribbler_width / 2 of the axis.
  double dribbler_contact_tolerance = 0.01;  // m
  double dribbler_max_ball_height = 0.03;    // m, above the ball resting height; higher balls are not held
  // A held ball is driven towards its target at the robot's front with this gain: velocity = velocity
  // of the target point + gain * (target - ball). gain * step must stay below 1.
  double dribbler_hold_gain = 60.0;            // 1/s
  double dribbler_max_correction_speed = 1.0;  // m/s, cap on the gain term

  // --- field ---
  double boundary_wall_height = 2.5;     // m: no chip at <= 6.5 m/s clears it (apex v^2 / 2g = 2.15 m)
  double boundary_wall_thickness = 0.5;  // m, thick so that nothing tunnels through
  double wall_friction = 0.5;            // Bullet friction coefficient of walls and goals (robots only)
};

/// nullopt when `params` is usable, otherwise a one-line reason (all values finite, sizes, masses,
/// decelerations and gains > 0, restitutions and spin retention in [0, 1], dribbler_hold_gain * step < 1).
std::optional<std::string> validate(const PhysicsParams& params);

}  // namespace ssl::sim
