// Conversions between the IDL samples of the planner's topics and the planner core's types, done once at
// the boundary. world.state arrives in the TEAM frame and stays in it; referee.state positions stay in the
// VISION frame (the core turns them with world.state's team frame; the side is never re-derived here); times go from Unix ns to
// ssl::time::Timestamp on the same clock. Inputs with a NaN or infinite number, an unknown enum value or
// an impossible robot id are REJECTED (an Error naming the field) so that the node counts them and never
// passes them on. Outputs (commands) with a non-finite number are replaced by a stop and counted.
#pragma once

#include <cstdint>
#include <optional>
#include <vector>

#include "idl/planner.h"
#include "idl/referee.h"
#include "idl/robot.h"
#include "idl/vision.h"
#include "idl/world.h"
#include "libs/common/result.h"
#include "libs/common/team.h"
#include "libs/domain/idl_convert.h"
#include "services/planner/core/planner.h"

namespace ssl::planner {

// ---- inputs ---------------------------------------------------------------------------------------------

/// world.state (team frame) -> the core's WorldState. The IDL carries no prediction instant: predicted_to is
/// the sample's publish time (world_model predicts to it).
Result<wm::WorldState> from_idl(const idl::world::WorldState& in);

/// referee.state -> RefereeInfo by the shared conversion (libs/domain/idl_convert.h: the same validation
/// as world_model's), without blue_team_on_positive_half: the team frame comes with world.state.
Result<wm::RefereeInfo> from_idl(const idl::referee::RefereeState& in);

/// vision.geometry's field -> FieldGeometry (m), by the shared conversion. An error when a dimension is
/// missing, non-positive or not finite (the node keeps the previous or the configured field).
Result<wm::FieldSize> from_idl(const idl::vision::Geometry& in);

// ---- outputs --------------------------------------------------------------------------------------------

idl::common::TeamColor to_idl(TeamColor team);
idl::robot::KickType to_idl(KickType kick);

/// One command. A command with a non-finite number becomes a full stop (kick and dribbler off) and
/// `non_finite` (when given) is incremented.
idl::robot::RobotCommand to_idl(const RobotCommand& in, std::uint64_t* non_finite = nullptr);

/// robot.commands for one tick: `stamp` is the VisionStamp of the world state the commands were computed
/// from (passed through unchanged), `sequence_number` the planner's sample counter, `publish_unix_ns` the
/// planner host's wall clock at publish time.
idl::robot::RobotCommands to_idl(const std::vector<RobotCommand>& commands, TeamColor team,
                                 const idl::common::VisionStamp& stamp, std::uint64_t sequence_number,
                                 std::int64_t publish_unix_ns, std::uint64_t* non_finite = nullptr);

/// planner.debug for one tick. Each role's target becomes a PlannedPath with that destination and no
/// intermediate points; `tick_duration` is the time spent in the core's step (s).
idl::planner::PlannerDebug to_idl(const PlannerOutput& in, TeamColor team, const idl::common::VisionStamp& stamp,
                                  double tick_duration);

}  // namespace ssl::planner
