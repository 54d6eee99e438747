// Conversions between robot_link's DDS samples (idl/robot.idl, idl/referee.idl) and its domain types,
// done once at the adapter's edge. Units are the same on both sides (SI, robot local frame).
#pragma once

#include <cstdint>
#include <optional>
#include <vector>

#include "idl/referee.h"
#include "idl/robot.h"
#include "libs/common/team.h"
#include "services/robot_link/core/types.h"

namespace ssl::robot_link {

/// The commands of one robot.commands sample (ids and values unchecked: the core validates them).
std::vector<RobotCommand> commands_from_idl(const idl::robot::RobotCommands& sample);

/// False when the sample names the other team explicitly (TEAM_COLOR_UNKNOWN is accepted).
bool team_matches(const idl::robot::RobotCommands& sample, TeamColor team);

/// True when the referee command is HALT.
bool is_halt(const idl::referee::RefereeState& state);

/// One robot's robot.feedback sample; `receive_unix_ns` is this host's wall clock.
idl::robot::RobotFeedback feedback_to_idl(const FeedbackReport& report, TeamColor team,
                                          std::int64_t receive_unix_ns);

idl::common::TeamColor team_to_idl(TeamColor team);

}  // namespace ssl::robot_link
