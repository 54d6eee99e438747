// The ONE conversion of the shared topics' IDL into the domain vocabulary: referee.state -> RefereeInfo
// and vision.geometry's field -> FieldGeometry, used by world_model and the planner alike (and by the
// lockstep match, which sends the built-in referee's state through the same wire types). A sample with a
// NaN or infinite number, a missing dimension or an enum value outside the IDL is REJECTED with an Error
// naming the field, so each node counts it and never passes it on. Positions stay in the VISION frame.
//
//   Result<wm::RefereeInfo> referee = referee_info_from_idl(sample.data);
//   if (!referee) ++malformed;  // referee.error().message names the field
#pragma once

#include <optional>

#include "idl/referee.h"
#include "idl/vision.h"
#include "libs/common/result.h"
#include "libs/domain/field.h"
#include "libs/domain/world.h"

namespace ssl {

/// The league's command by NAME (the IDL order is the league's, and so is the domain's). nullopt for a
/// value outside the IDL enum (a corrupt sample).
std::optional<wm::RefereeCommand> referee_command_from_idl(idl::referee::Command command);

/// referee.state -> RefereeInfo: command, counter, sides, designated position (m, vision frame), next
/// command, and per team the goalkeeper, can_place_ball and max_allowed_bots.
Result<wm::RefereeInfo> referee_info_from_idl(const idl::referee::RefereeState& in);

/// vision.geometry's field -> FieldGeometry (m). An error when a dimension the league requires is
/// missing, non-positive or not finite, or an optional one is negative or not finite; optional ones not
/// sent (0) keep the division A rulebook value (FieldGeometry's defaults).
Result<FieldGeometry> field_from_idl(const idl::vision::Geometry& in);

}  // namespace ssl
