// Conversions between the IDL samples of the world_model's topics and the core's types, done once at the
// boundary. Inputs stay in the vision frame (the core's TeamFrame does the one flip); times go from Unix
// ns to ssl::time::Timestamp on the same clock. Bad numbers (NaN, infinite) are reported, not passed on.
#pragma once

#include <cstdint>
#include <optional>
#include <vector>

#include "idl/referee.h"
#include "idl/robot.h"
#include "idl/vision.h"
#include "idl/world.h"
#include "libs/common/result.h"
#include "libs/domain/world.h"

namespace ssl::wm {

/// nullopt when a coordinate is not finite (the frame is dropped and counted).
std::optional<DetectionFrame> from_idl(const idl::vision::DetectionFrame& in);
/// vision.geometry: the field by the shared conversion (libs/domain/idl_convert.h; an Error for a missing or
/// non-finite dimension), the cameras and the ball model.
Result<Geometry> from_idl(const idl::vision::Geometry& in);
/// referee.state by the shared conversion (the planner's too): an Error for an unknown command or a
/// non-finite designated position.
Result<RefereeInfo> from_idl(const idl::referee::RefereeState& in);
RobotFeedback from_idl(const idl::robot::RobotFeedback& in);
std::vector<RobotCommand> from_idl(const idl::robot::RobotCommands& in);

/// `sequence_number` and `publish_unix_ns` (host wall clock) are the adapter's.
idl::world::WorldState to_idl(const WorldState& in, std::uint64_t sequence_number, std::int64_t publish_unix_ns);

}  // namespace ssl::wm
