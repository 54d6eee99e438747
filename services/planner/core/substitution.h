// Cards take robots off the field (rules: number of robots, substitution). When the referee allows fewer
// of our robots on the field than we see, the surplus drives off to the centre substitution area beside
// the halfway line on our side, where it no longer counts (libs/domain/field.h), and waits there until the
// card expires. It happens before any play: the plays see only the robots that stay, so every strategy
// obeys the cards in the same way.
//
//   memory.leaving = choose_leaving(robots, game.our_max_allowed_bots(), keeper_id, memory.leaving);
//   intents.robots[id] = leave_field_intent(s, robot, leaving_slot);
#pragma once

#include <cstdint>
#include <optional>
#include <span>
#include <vector>

#include "libs/domain/world.h"
#include "services/planner/core/motion.h"
#include "services/planner/core/plays.h"

namespace ssl::planner {

/// The robots (ids, ascending) that leave so that at most `allowed` of `robots` (ours, visible, TEAM frame)
/// stay. Sticky: the robots of `leaving_before` that are still seen leave first; more are taken by how near
/// they stand to their touch line's substitution spot, the goalkeeper last; fewer are needed when a card
/// expired or a robot vanished, and the ones nearest to the halfway line come back first.
std::vector<std::uint32_t> choose_leaving(std::span<const wm::RobotState> robots, std::uint32_t allowed,
                                          std::optional<std::uint32_t> keeper,
                                          std::span<const std::uint32_t> leaving_before, const wm::Field& field);

/// Where robot `robot` waits off the field (TEAM frame, our half): the substitution spot of the touch line
/// on its side, `slot` the how-many-th leaving robot on that side.
Vec2 leaving_spot(const wm::Field& field, const wm::RobotState& robot, int slot);

/// The intent of a leaving robot: drive to `spot` within the current command's limits (halted in HALT,
/// the STOP speed and ball distance when they apply, around a placement), facing the field.
MotionIntent leave_field_intent(const Situation& s, const Vec2& spot);

}  // namespace ssl::planner
