#include "services/robot_link/backend/wire_convert.h"

#include <cmath>
#include <numbers>

namespace ssl::robot_link {
namespace {

constexpr double kRadiansToDegrees = 180.0 / std::numbers::pi;

/// Kick angle of a command in rad: 0 for flat kicks and no kick.
double kick_angle(const RobotCommand& command) {
  return command.kick == KickType::kChip ? command.chip_angle : 0.0;
}

double kick_speed(const RobotCommand& command) {
  return command.kick == KickType::kNone ? 0.0 : command.kick_speed;
}

}  // namespace

RobotControl to_robot_control(std::span<const OutgoingCommand> commands) {
  RobotControl control;
  for (const OutgoingCommand& out : commands) {
    const RobotCommand& command = out.command;
    ::RobotCommand* wire = control.add_robot_commands();
    wire->set_id(command.id);
    MoveLocalVelocity* velocity = wire->mutable_move_command()->mutable_local_velocity();
    velocity->set_forward(static_cast<float>(command.forward));
    velocity->set_left(static_cast<float>(command.left));
    velocity->set_angular(static_cast<float>(command.angular));
    wire->set_kick_speed(static_cast<float>(kick_speed(command)));
    wire->set_kick_angle(static_cast<float>(kick_angle(command) * kRadiansToDegrees));
    wire->set_dribbler_speed(static_cast<float>(command.dribbler_rpm));
  }
  return control;
}

std::vector<FeedbackReport> feedback_from_response(const RobotControlResponse& response) {
  std::vector<FeedbackReport> reports;
  for (const ::RobotFeedback& wire : response.feedback()) {
    if (wire.id() >= kMaxRobots) continue;
    FeedbackReport report;
    report.robot_id = wire.id();
    if (wire.has_dribbler_ball_contact()) report.ball_in_dribbler = wire.dribbler_ball_contact();
    reports.push_back(report);
  }
  return reports;
}

grSim_Packet to_grsim_packet(std::span<const OutgoingCommand> commands, TeamColor team, double timestamp_s) {
  grSim_Packet packet;
  grSim_Commands* wire_commands = packet.mutable_commands();
  wire_commands->set_timestamp(timestamp_s);
  wire_commands->set_isteamyellow(team == TeamColor::kYellow);
  for (const OutgoingCommand& out : commands) {
    const RobotCommand& command = out.command;
    grSim_Robot_Command* wire = wire_commands->add_robot_commands();
    wire->set_id(command.id);
    const double speed = kick_speed(command);
    const double angle = kick_angle(command);
    wire->set_kickspeedx(static_cast<float>(speed * std::cos(angle)));
    wire->set_kickspeedz(static_cast<float>(speed * std::sin(angle)));
    wire->set_veltangent(static_cast<float>(command.forward));
    wire->set_velnormal(static_cast<float>(command.left));
    wire->set_velangular(static_cast<float>(command.angular));
    wire->set_spinner(command.dribbler_rpm > 0);
    wire->set_wheelsspeed(false);
  }
  return packet;
}

std::vector<FeedbackReport> feedback_from_grsim_status(const Robots_Status& status) {
  std::vector<FeedbackReport> reports;
  for (const Robot_Status& wire : status.robots_status()) {
    if (wire.robot_id() < 0 || static_cast<std::uint32_t>(wire.robot_id()) >= kMaxRobots) continue;
    FeedbackReport report;
    report.robot_id = static_cast<std::uint32_t>(wire.robot_id());
    report.ball_in_dribbler = wire.infrared();
    reports.push_back(report);
  }
  return reports;
}

radio::CommandFrame to_command_frame(std::span<const OutgoingCommand> commands, std::uint16_t sequence) {
  radio::CommandFrame frame;
  frame.sequence = sequence;
  for (const OutgoingCommand& out : commands) {
    if (out.command.id >= kMaxRobots || frame.robots.size() == radio::kMaxRecords) continue;
    frame.robots.push_back({.command = out.command, .stop = out.stop != StopReason::kNone});
  }
  return frame;
}

std::vector<FeedbackReport> feedback_from_status_frame(const radio::StatusFrame& frame) {
  std::vector<FeedbackReport> reports;
  for (const radio::StatusRecord& record : frame.robots) {
    FeedbackReport report;
    report.robot_id = record.robot_id;
    report.ball_in_dribbler = record.ball_in_dribbler;
    report.battery_voltage = record.battery_voltage;
    report.kicker_charge = record.kicker_charge;
    report.link_quality = record.link_quality;
    reports.push_back(report);
  }
  return reports;
}

}  // namespace ssl::robot_link
