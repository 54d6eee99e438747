// The rule layer: the last step before a command leaves the planner. Whatever the tree and the skill
// layer decided, it enforces the hard limits of the current referee command (rules 13.3 / 13.4):
// HALT -> every robot stopped, nothing kicked or dribbled; STOP and ball placement -> speed below the
// STOP limit; no kick unless the ball may be played (normal play, or our restart after it was released);
// when robots must keep 0.5 m from the ball, a robot inside that circle never moves towards the ball and
// always has some velocity away from it.
#pragma once

#include <cstdint>
#include <optional>

#include "services/planner/core/planner.h"
#include "libs/domain/game_state.h"
#include "libs/domain/world.h"

namespace ssl::planner {

struct RuleLimits {
  bool halt = false;
  double max_speed = 3.0;  // m/s
  bool kicks_allowed = false;
  double keep_away_from_ball = 0;       // m, robot centre; 0: no keep-away
  std::optional<std::uint32_t> exempt;  // the robot allowed at the ball (our placer)
  double min_escape_speed = 0.3;        // m/s, away from the ball while inside the keep-away circle
};

RuleLimits rule_limits(const wm::GameState& game, const PlannerConfig& config, bool we_place_ball,
                       std::optional<std::uint32_t> placer);

/// Whether `limits` make `robot` (team frame) escape the ball's circle (team frame): inside the keep-away
/// distance of a restart or STOP, and not the robot exempt from it.
bool escapes_ball(const RuleLimits& limits, const wm::RobotState& robot, const std::optional<Vec2>& ball);

/// `command` (local frame) made to obey `limits` for `robot` (team frame), given the ball (team frame).
RobotCommand enforce(const RuleLimits& limits, const wm::RobotState& robot, RobotCommand command,
                     const std::optional<Vec2>& ball);

}  // namespace ssl::planner
