#include "services/planner/core/rules.h"

#include <algorithm>

#include "libs/geometry/vec2.h"
#include "services/planner/core/motion.h"

namespace ssl::planner {

RuleLimits rule_limits(const wm::GameState& game, const PlannerConfig& config, bool we_place_ball,
                       std::optional<std::uint32_t> placer) {
  RuleLimits limits;
  limits.halt = game.is_halted();
  limits.max_speed = config.limits.max_speed;
  if (game.is_stopped() || game.is_ball_placement() || game.is_timeout()) {
    limits.max_speed = std::min(limits.max_speed, config.stop_speed - config.stop_speed_margin);
  }
  const bool our_restart_ready =
      game.is_ready() && (game.is_our_kickoff() || game.is_our_penalty() || game.is_our_free_kick());
  limits.kicks_allowed = !limits.halt && (game.is_playing() || our_restart_ready);
  if (game.must_keep_distance_from_ball()) {
    limits.keep_away_from_ball = config.ball_keep_away + config.robot_radius;
    if (game.is_our_ball_placement() && we_place_ball) limits.exempt = placer;
  }
  return limits;
}

namespace {
/// Whether `robot` must keep away from the ball now (not the robot exempt from it).
bool keeps_away(const RuleLimits& limits, const wm::RobotState& robot) {
  return limits.keep_away_from_ball > 0 && !(limits.exempt && *limits.exempt == robot.id);
}
}  // namespace

bool escapes_ball(const RuleLimits& limits, const wm::RobotState& robot, const std::optional<Vec2>& ball) {
  return keeps_away(limits, robot) && ball && (robot.position - *ball).norm() < limits.keep_away_from_ball;
}

RobotCommand enforce(const RuleLimits& limits, const wm::RobotState& robot, RobotCommand command,
                     const std::optional<Vec2>& ball) {
  if (limits.halt) {
    RobotCommand zero;
    zero.id = command.id;
    return zero;
  }
  if (!limits.kicks_allowed) {
    command.kick = KickType::kNone;
    command.kick_speed = 0;
    command.chip_angle = 0;
  }
  Vec2 velocity = to_team(command, robot.orientation);
  if (keeps_away(limits, robot)) command.dribbler_rpm = 0;
  if (escapes_ball(limits, robot, ball)) {
    const Vec2 away = robot.position - *ball;
    const double distance = away.norm();
    const Vec2 out = distance > 1e-9 ? Vec2(away / distance) : Vec2(-1, 0);
    const double outward = velocity.dot(out);
    const Vec2 tangential = velocity - outward * out;
    velocity = tangential + std::max(outward, limits.min_escape_speed) * out;
  }
  const double speed = velocity.norm();
  if (speed > limits.max_speed) velocity *= limits.max_speed / speed;
  const RobotCommand local = to_local(command.id, velocity, command.angular, robot.orientation);
  command.forward = local.forward;
  command.left = local.left;
  return command;
}

}  // namespace ssl::planner
