// Conversions between robot_link's per-tick commands / feedback and the backends' wire formats, done once
// here: the simulation protocol (RobotControl with local velocities, kick angle in DEGREES; every optional
// field set explicitly, since an unset field means "unchanged"), grSim's legacy packet (kick split into
// horizontal and vertical speeds, dribbler on/off) and the radio frames (radio_frame.h). Pure functions.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "libs/common/team.h"
#include "proto/grsim_packet.pb.h"
#include "proto/grsim_robotstatus.pb.h"
#include "proto/ssl_simulation_robot_control.pb.h"
#include "proto/ssl_simulation_robot_feedback.pb.h"
#include "services/robot_link/core/types.h"
#include "services/robot_link/radio/radio_frame.h"

namespace ssl::robot_link {

/// One team's RobotControl datagram: local velocities, kick_speed, kick_angle (degrees: 0 flat, > 0 chip)
/// and dribbler_speed (rpm), all set.
RobotControl to_robot_control(std::span<const OutgoingCommand> commands);

/// The feedback of a RobotControlResponse (dribbler contact only).
std::vector<FeedbackReport> feedback_from_response(const RobotControlResponse& response);

/// One team's grSim_Packet: veltangent/velnormal/velangular, kickspeedx = v cos(angle), kickspeedz =
/// v sin(angle), spinner = dribbler on, wheelsspeed = false. `timestamp_s` is informative (grSim ignores it).
grSim_Packet to_grsim_packet(std::span<const OutgoingCommand> commands, TeamColor team, double timestamp_s);

/// grSim's robot status: infrared (ball at the kicker) as ball in dribbler; invalid ids are skipped.
std::vector<FeedbackReport> feedback_from_grsim_status(const Robots_Status& status);

/// A radio command frame with sequence number `sequence`.
radio::CommandFrame to_command_frame(std::span<const OutgoingCommand> commands, std::uint16_t sequence);

/// The feedback of a radio status frame.
std::vector<FeedbackReport> feedback_from_status_frame(const radio::StatusFrame& frame);

}  // namespace ssl::robot_link
