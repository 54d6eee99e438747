#include "libs/domain/idl_convert.h"

#include <cmath>
#include <string>
#include <utility>

namespace ssl {
namespace {

bool is_finite(double value) { return std::isfinite(value); }

}  // namespace

std::optional<wm::RefereeCommand> referee_command_from_idl(idl::referee::Command command) {
  using C = wm::RefereeCommand;
  namespace r = idl::referee;
  switch (command) {
    case r::COMMAND_HALT: return C::kHalt;
    case r::COMMAND_STOP: return C::kStop;
    case r::COMMAND_NORMAL_START: return C::kNormalStart;
    case r::COMMAND_FORCE_START: return C::kForceStart;
    case r::COMMAND_PREPARE_KICKOFF_YELLOW: return C::kPrepareKickoffYellow;
    case r::COMMAND_PREPARE_KICKOFF_BLUE: return C::kPrepareKickoffBlue;
    case r::COMMAND_PREPARE_PENALTY_YELLOW: return C::kPreparePenaltyYellow;
    case r::COMMAND_PREPARE_PENALTY_BLUE: return C::kPreparePenaltyBlue;
    case r::COMMAND_DIRECT_FREE_YELLOW: return C::kDirectFreeYellow;
    case r::COMMAND_DIRECT_FREE_BLUE: return C::kDirectFreeBlue;
    case r::COMMAND_INDIRECT_FREE_YELLOW: return C::kIndirectFreeYellow;
    case r::COMMAND_INDIRECT_FREE_BLUE: return C::kIndirectFreeBlue;
    case r::COMMAND_TIMEOUT_YELLOW: return C::kTimeoutYellow;
    case r::COMMAND_TIMEOUT_BLUE: return C::kTimeoutBlue;
    case r::COMMAND_GOAL_YELLOW: return C::kGoalYellow;
    case r::COMMAND_GOAL_BLUE: return C::kGoalBlue;
    case r::COMMAND_BALL_PLACEMENT_YELLOW: return C::kBallPlacementYellow;
    case r::COMMAND_BALL_PLACEMENT_BLUE: return C::kBallPlacementBlue;
  }
  return std::nullopt;
}

Result<wm::RefereeInfo> referee_info_from_idl(const idl::referee::RefereeState& in) {
  wm::RefereeInfo out;
  const std::optional<wm::RefereeCommand> command = referee_command_from_idl(in.command());
  if (!command) return Error{"referee.state command has an unknown value " + std::to_string(in.command())};
  out.command = *command;
  out.command_counter = in.command_counter();
  if (in.has_blue_team_on_positive_half()) out.blue_team_on_positive_half = in.blue_team_on_positive_half();
  if (in.has_designated_position()) {
    const auto& p = in.designated_position();
    if (!is_finite(p.x()) || !is_finite(p.y())) {
      return Error{"referee.state designated_position is not finite"};
    }
    out.designated_position = wm::Vec2(p.x(), p.y());
  }
  if (in.has_next_command()) {
    const std::optional<wm::RefereeCommand> next = referee_command_from_idl(in.next_command());
    if (!next) {
      return Error{"referee.state next_command has an unknown value " + std::to_string(in.next_command())};
    }
    out.next_command = *next;
  }
  out.yellow_goalkeeper = in.yellow().goalkeeper();
  out.blue_goalkeeper = in.blue().goalkeeper();
  out.yellow_can_place_ball = in.yellow().can_place_ball();
  out.blue_can_place_ball = in.blue().can_place_ball();
  out.yellow_max_allowed_bots = in.yellow().max_allowed_bots();
  out.blue_max_allowed_bots = in.blue().max_allowed_bots();
  return out;
}

Result<FieldGeometry> field_from_idl(const idl::vision::Geometry& in) {
  const auto& f = in.field();
  FieldGeometry out;
  const std::pair<const char*, double> required[] = {
      {"field_length", f.field_length()},
      {"field_width", f.field_width()},
      {"goal_width", f.goal_width()},
      {"goal_depth", f.goal_depth()},
      {"penalty_area_depth", f.penalty_area_depth()},
      {"penalty_area_width", f.penalty_area_width()},
      {"center_circle_radius", f.center_circle_radius()},
      {"goal_center_to_penalty_mark", f.goal_center_to_penalty_mark()},
  };
  for (const auto& [name, value] : required) {
    if (!is_finite(value) || value <= 0) {
      return Error{std::string("vision.geometry field.") + name + " = " + std::to_string(value) +
                   " is not a positive finite length"};
    }
  }
  // Optional in the league's message: 0 when not sent, then the rulebook's value stays.
  const std::pair<const char*, double> optional[] = {
      {"boundary_width", f.boundary_width()},
      {"boundary_width_goal_line", f.boundary_width_goal_line()},
      {"goal_height", f.goal_height()},
      {"line_thickness", f.line_thickness()},
      {"goal_substitution_area_width", f.goal_substitution_area_width()},
      {"ball_radius", f.ball_radius()},
      {"max_robot_radius", f.max_robot_radius()},
  };
  for (const auto& [name, value] : optional) {
    if (!is_finite(value) || value < 0) {
      return Error{std::string("vision.geometry field.") + name + " = " + std::to_string(value) +
                   " is not a finite non-negative length"};
    }
  }
  const auto sent_or_default = [](double sent, double rulebook) { return sent > 0 ? sent : rulebook; };
  out.field_length = f.field_length();
  out.field_width = f.field_width();
  out.goal_width = f.goal_width();
  out.goal_depth = f.goal_depth();
  out.penalty_area_depth = f.penalty_area_depth();
  out.penalty_area_width = f.penalty_area_width();
  out.center_circle_radius = f.center_circle_radius();
  out.goal_center_to_penalty_mark = f.goal_center_to_penalty_mark();
  out.boundary_width = sent_or_default(f.boundary_width(), out.boundary_width);
  out.boundary_width_goal_line = sent_or_default(f.boundary_width_goal_line(), out.boundary_width_goal_line);
  out.goal_height = sent_or_default(f.goal_height(), out.goal_height);
  out.line_thickness = sent_or_default(f.line_thickness(), out.line_thickness);
  out.goal_substitution_area_width =
      sent_or_default(f.goal_substitution_area_width(), out.goal_substitution_area_width);
  out.ball_radius = sent_or_default(f.ball_radius(), out.ball_radius);
  out.max_robot_radius = sent_or_default(f.max_robot_radius(), out.max_robot_radius);
  return out;
}

}  // namespace ssl
