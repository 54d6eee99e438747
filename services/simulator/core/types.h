// Domain types of the simulator core: field, robots, ball, commands and snapshots. SI units (m, m/s, rad,
// rad/s, kg, s) in the SSL-Vision global frame (origin at the field centre, x along the length, y along
// the width, angles CCW from +x). Wire formats (protobuf) never appear here: the adapter converts.
// Simulated time is a ssl::time::Timestamp on the SIMULATED clock (starts at 0 unless set).
#pragma once

#include <Eigen/Core>
#include <array>
#include <compare>
#include <cstdint>
#include <vector>

#include "libs/common/team.h"
#include "libs/domain/field.h"
#include "libs/geometry/vec2.h"
#include "libs/time/time.h"

namespace ssl::sim {

using geom::Vec2;
using Vec3 = Eigen::Vector3d;

/// Identifies a robot: team colour and pattern id (0..15).
struct RobotKey {
  TeamColor team = TeamColor::kBlue;
  std::uint32_t id = 0;
  friend auto operator<=>(const RobotKey&, const RobotKey&) = default;
};

inline constexpr std::uint32_t kMaxRobotsPerTeam = 16;

/// Field dimensions, metres: the shared vocabulary's (libs/domain/field.h).
using ssl::FieldGeometry;

/// Acceleration and speed limits of a robot's motion controller.
struct RobotLimits {
  double acc_speedup_absolute_max = 3.0;  // m/s^2
  double acc_speedup_angular_max = 30.0;  // rad/s^2
  double acc_brake_absolute_max = 4.0;    // m/s^2
  double acc_brake_angular_max = 30.0;    // rad/s^2
  double vel_absolute_max = 3.0;          // m/s
  double vel_angular_max = 10.0;          // rad/s
};

/// Physical description of one team's robots (the simulation protocol's RobotSpecs).
struct RobotSpec {
  double radius = 0.09;               // m
  double height = 0.15;               // m
  double mass = 2.7;                  // kg
  double center_to_dribbler = 0.078;  // m, from the centre to the flat front (dribbler)
  double dribbler_width = 0.065;      // m
  double max_linear_kick_speed = 6.5; // m/s, rules' ball speed limit
  double max_chip_kick_speed = 6.5;   // m/s
  RobotLimits limits;
  // Wheel angles, rad from the forward direction, clockwise: front right, back right, back left,
  // front left (used to convert wheel-velocity commands).
  std::array<double, 4> wheel_angles{1.0472, 2.3562, -2.3562, -1.0472};  // 60, 135, 225, 300 deg
};

/// A robot's command, held by the simulator until the next one replaces it.
struct RobotCommand {
  enum class Move { kNone, kLocalVelocity, kGlobalVelocity, kWheelVelocity };
  Move move = Move::kNone;
  // kLocalVelocity: {forward m/s, left m/s, angular rad/s}; kGlobalVelocity: {x m/s, y m/s, angular rad/s}.
  Vec3 velocity = Vec3::Zero();
  // kWheelVelocity: wheel surface speeds, m/s: front right, back right, back left, front left.
  std::array<double, 4> wheel_velocity{0, 0, 0, 0};
  double kick_speed = 0;    // m/s, 3D ball speed; 0 = no kick. Fires once the ball touches the dribbler.
  double kick_angle = 0;    // rad above the carpet; 0 = flat kick, > 0 = chip
  double dribbler_rpm = 0;  // 0 = off
};

struct BallState {
  Vec3 position{0, 0, 0.0215};  // m, z = centre height
  Vec3 velocity = Vec3::Zero(); // m/s
};

struct RobotState {
  RobotKey key;
  Vec2 position = Vec2::Zero();  // m
  double orientation = 0;        // rad
  Vec2 velocity = Vec2::Zero();  // m/s, global frame
  double angular_velocity = 0;   // rad/s
  bool ball_contact = false;     // the ball touches the dribbler
};

/// The simulated world at one instant.
struct WorldSnapshot {
  time::Timestamp time;          // simulated clock
  BallState ball;
  std::vector<RobotState> robots;  // sorted by key
};

}  // namespace ssl::sim
