#include "services/robot_link/adapter/convert.h"

namespace ssl::robot_link {

std::vector<RobotCommand> commands_from_idl(const idl::robot::RobotCommands& sample) {
  std::vector<RobotCommand> commands;
  commands.reserve(sample.commands().size());
  for (const idl::robot::RobotCommand& wire : sample.commands()) {
    RobotCommand command;
    command.id = wire.id();
    command.forward = wire.forward();
    command.left = wire.left();
    command.angular = wire.angular();
    switch (wire.kick()) {
      case idl::robot::KICK_FLAT: command.kick = KickType::kFlat; break;
      case idl::robot::KICK_CHIP: command.kick = KickType::kChip; break;
      default: command.kick = KickType::kNone; break;
    }
    command.kick_speed = wire.kick_speed();
    command.chip_angle = wire.chip_angle();
    command.dribbler_rpm = wire.dribbler_rpm();
    commands.push_back(command);
  }
  return commands;
}

idl::common::TeamColor team_to_idl(TeamColor team) {
  return team == TeamColor::kBlue ? idl::common::TEAM_COLOR_BLUE : idl::common::TEAM_COLOR_YELLOW;
}

bool team_matches(const idl::robot::RobotCommands& sample, TeamColor team) {
  return sample.team() == idl::common::TEAM_COLOR_UNKNOWN || sample.team() == team_to_idl(team);
}

bool is_halt(const idl::referee::RefereeState& state) {
  return state.command() == idl::referee::COMMAND_HALT;
}

idl::robot::RobotFeedback feedback_to_idl(const FeedbackReport& report, TeamColor team,
                                          std::int64_t receive_unix_ns) {
  idl::robot::RobotFeedback sample;
  sample.robot_id(report.robot_id);
  sample.team(team_to_idl(team));
  sample.ball_in_dribbler(report.ball_in_dribbler.value_or(false));
  sample.has_battery(report.battery_voltage.has_value());
  sample.battery_voltage(report.battery_voltage.value_or(0));
  sample.has_kicker_charge(report.kicker_charge.has_value());
  sample.kicker_charge(report.kicker_charge.value_or(0));
  sample.has_link_quality(report.link_quality.has_value());
  sample.link_quality(report.link_quality.value_or(0));
  sample.receive_unix_ns(receive_unix_ns);
  return sample;
}

}  // namespace ssl::robot_link
