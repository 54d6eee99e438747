// Conversions between the league's wire formats and the simulator core, done once at the edge:
// the simulation protocol (SimulatorCommand, RobotControl and their responses, metres and m/s, kick
// angle in DEGREES), grSim's legacy packets (metres, robot heading in DEGREES) and SSL-Vision output
// (MILLIMETRES, Unix seconds). The core works in SI units on the simulated clock; `unix_offset` maps
// simulated time to the Unix time written into vision packets.
#pragma once

#include <vector>

#include "libs/time/time.h"
#include "proto/grsim_packet.pb.h"
#include "proto/grsim_robotstatus.pb.h"
#include "proto/ssl_simulation_control.pb.h"
#include "proto/ssl_simulation_robot_control.pb.h"
#include "proto/ssl_simulation_robot_feedback.pb.h"
#include "proto/ssl_vision_wrapper.pb.h"
#include "services/simulator/core/simulator.h"

namespace ssl::sim {

/// SimulatorCommand -> ControlRequest. Parts that cannot be converted (unknown team, unsupported custom
/// config, bad geometry) are reported in `errors` and left out.
ControlRequest control_from_proto(const SimulatorCommand& command, std::vector<SimError>& errors);

/// RobotControl (one team's datagram) -> commands.
std::vector<RobotCommandFor> commands_from_proto(const RobotControl& control, std::vector<SimError>& errors);

/// grSim's legacy packet: the team of its commands, the commands, and its replacement as a control
/// request.
struct GrsimInput {
  TeamColor team = TeamColor::kBlue;
  std::vector<RobotCommandFor> commands;
  ControlRequest control;
};
GrsimInput grsim_from_proto(const grSim_Packet& packet, std::vector<SimError>& errors);

/// grSim's robot status (infrared = ball at the kicker), sent back for grSim clients.
Robots_Status grsim_status_to_proto(const std::vector<RobotFeedback>& feedback);

RobotControlResponse response_to_proto(const std::vector<RobotFeedback>& feedback, const std::vector<SimError>& errors);
SimulatorResponse response_to_proto(const std::vector<SimError>& errors);

/// One camera frame as SSL-Vision sends it (millimetres; t_capture / t_sent = unix_offset + simulated
/// time, in Unix seconds).
SSL_DetectionFrame detection_to_proto(const DetectionFrame& frame, time::Duration unix_offset);

/// Field geometry, calibrations and ball models as SSL-Vision sends them (millimetres).
SSL_GeometryData geometry_to_proto(const GeometryData& geometry);

}  // namespace ssl::sim
