// IDL <-> console core, once, at the edge; and the simulator's control packet for a placement.
#pragma once

#include <string>

#include "idl/planner.h"
#include "idl/referee.h"
#include "idl/robot.h"
#include "idl/system.h"
#include "idl/vision.h"
#include "idl/world.h"
#include "services/console/core/actions.h"
#include "services/console/core/types.h"

namespace ssl::console {

CameraView from_idl(const idl::vision::DetectionFrame& frame);
TeamWorld from_idl(const idl::world::WorldState& world);
TeamDebug from_idl(const idl::planner::PlannerDebug& debug);
ServiceHealth from_idl(const idl::system::Health& health);
RobotFeedbackView from_idl(const idl::robot::RobotFeedback& feedback, TeamColor team);
EstopView from_idl(const idl::system::Estop& estop);
ParameterStateView from_idl(const idl::system::ParameterState& state);

/// A request for `action.target`: set `action.key` (when given) and/or save.
idl::system::ParameterSet to_idl(const ParamAction& action, std::uint64_t revision, const std::string& author,
                                 std::int64_t stamp_unix_ns);
idl::system::ParameterSet save_request(const ParamSaveAction& action, std::uint64_t revision,
                                       const std::string& author, std::int64_t stamp_unix_ns);

idl::referee::RefereeOperatorCommand to_idl(const RefereeAction& action, const std::string& author,
                                            std::int64_t stamp_unix_ns);
idl::system::Estop to_idl(const EstopAction& action, const std::string& source, std::int64_t stamp_unix_ns);

/// The league simulation protocol's SimulatorCommand (serialised) that teleports the ball, or a robot to
/// `heading` (rad, vision frame), at rest.
std::string simulator_command(const PlaceAction& action, double heading);

}  // namespace ssl::console
