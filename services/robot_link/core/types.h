// Domain types of robot_link, shared by its core, backends and adapter (no DDS, no protobuf).
//
// Frame and units: a robot command is in the ROBOT's local frame, SI units, as in idl/robot.idl:
// `forward` towards the dribbler and `left` in m/s, `angular` in rad/s counter-clockwise, kick speed in
// m/s (3D ball speed), chip angle in rad above the carpet, dribbler speed in rpm. Millimetres, degrees
// and fixed-point only appear at the wire edges (backends), converted once.
//
// Clock: every time stamp here is on the host MONOTONIC clock (ssl::time::MonotonicClock) unless its name
// says otherwise; the watchdog compares them with the `now` given to RobotLinkCore::step.
//
//   RobotCommand command{.id = 3, .forward = 1.0, .kick = KickType::kFlat, .kick_speed = 4.0};
//   TimedCommand latest{.command = command, .received_mono = clock.now()};
#pragma once

#include <cstdint>
#include <optional>
#include <string_view>

#include "libs/time/time.h"

namespace ssl::robot_link {

/// Robot ids a team may use on the league's protocols (0..15).
inline constexpr std::uint32_t kMaxRobots = 16;

enum class KickType { kNone, kFlat, kChip };

/// One robot's command for one tick, robot local frame.
struct RobotCommand {
  std::uint32_t id = 0;
  double forward = 0;  // m/s towards the dribbler
  double left = 0;     // m/s
  double angular = 0;  // rad/s, counter-clockwise
  KickType kick = KickType::kNone;
  double kick_speed = 0;    // m/s, 3D ball speed (used with kFlat / kChip)
  double chip_angle = 0;    // rad above the carpet (used with kChip)
  double dribbler_rpm = 0;  // 0 = off

  friend bool operator==(const RobotCommand&, const RobotCommand&) = default;
};

/// A stop command for robot `id`: zero velocity, kicker and dribbler off.
constexpr RobotCommand stop_command(std::uint32_t id) { return RobotCommand{.id = id}; }

/// True when the command moves nothing: zero velocities, no kick, dribbler off.
constexpr bool is_stop(const RobotCommand& command) {
  return command.forward == 0 && command.left == 0 && command.angular == 0 &&
         command.kick == KickType::kNone && command.kick_speed == 0 && command.dribbler_rpm == 0;
}

/// The newest command of one robot and when it arrived (host monotonic clock).
struct TimedCommand {
  RobotCommand command;
  time::Timestamp received_mono;
};

/// Why a robot is sent a stop instead of its planned command this tick (highest priority first in the
/// order the core checks them: e-stop, HALT, stale, startup).
enum class StopReason { kNone, kEstop, kHalt, kStale, kStartup };

constexpr std::string_view to_string(StopReason reason) {
  switch (reason) {
    case StopReason::kNone: return "none";
    case StopReason::kEstop: return "estop";
    case StopReason::kHalt: return "halt";
    case StopReason::kStale: return "stale";
    case StopReason::kStartup: return "startup";
  }
  return "?";
}

/// What the core decided to send to one robot this tick.
struct OutgoingCommand {
  RobotCommand command;  // already limited and clamped; all zero when `stop` is set
  StopReason stop = StopReason::kNone;
};

/// Feedback from one robot, from whichever backend heard it. Unset optionals: the backend does not
/// report that value (the simulator only reports dribbler contact).
struct FeedbackReport {
  std::uint32_t robot_id = 0;
  std::optional<bool> ball_in_dribbler;
  std::optional<double> battery_voltage;  // V
  std::optional<double> kicker_charge;    // 0..1 of full charge
  std::optional<double> link_quality;     // 0..1, share of command frames the robot received
};

}  // namespace ssl::robot_link
