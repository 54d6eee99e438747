#include "services/planner/core/substitution.h"

#include <algorithm>
#include <cmath>

#include "libs/domain/field.h"

namespace ssl::planner {
namespace {

bool contains(std::span<const std::uint32_t> ids, std::uint32_t id) {
  return std::find(ids.begin(), ids.end(), id) != ids.end();
}

double touch_line_sign(const wm::RobotState& robot) { return robot.position.y() < 0 ? -1.0 : 1.0; }

}  // namespace

Vec2 leaving_spot(const wm::Field& field, const wm::RobotState& robot, int slot) {
  return substitution_spot(field.size(), -1, touch_line_sign(robot), slot);
}

std::vector<std::uint32_t> choose_leaving(std::span<const wm::RobotState> robots, std::uint32_t allowed,
                                          std::optional<std::uint32_t> keeper,
                                          std::span<const std::uint32_t> leaving_before, const wm::Field& field) {
  const std::size_t surplus = robots.size() > allowed ? robots.size() - allowed : 0;
  if (surplus == 0) return {};
  // Candidates in order of preference: already leaving (nearest to the halfway line stays off longest),
  // then field players by distance to their spot, then the goalkeeper.
  struct Candidate {
    int group;
    double cost;
    std::uint32_t id;
  };
  std::vector<Candidate> candidates;
  candidates.reserve(robots.size());
  for (const wm::RobotState& robot : robots) {
    if (contains(leaving_before, robot.id)) {
      candidates.push_back({0, -std::abs(robot.position.x()), robot.id});
    } else {
      const double to_spot = (robot.position - leaving_spot(field, robot, 0)).norm();
      candidates.push_back({keeper && robot.id == *keeper ? 2 : 1, to_spot, robot.id});
    }
  }
  std::sort(candidates.begin(), candidates.end(), [](const Candidate& a, const Candidate& b) {
    if (a.group != b.group) return a.group < b.group;
    if (a.cost != b.cost) return a.cost < b.cost;
    return a.id < b.id;
  });
  std::vector<std::uint32_t> leaving;
  for (std::size_t i = 0; i < surplus && i < candidates.size(); ++i) leaving.push_back(candidates[i].id);
  std::sort(leaving.begin(), leaving.end());
  return leaving;
}

MotionIntent leave_field_intent(const Situation& s, const Vec2& spot) {
  const wm::GameState& game = *s.game;
  MotionIntent intent =
      game.must_keep_distance_from_ball() ? stop_intent(s, "leave_field") : base_intent(s, "leave_field");
  intent.target = spot;
  intent.orientation = spot.y() < 0 ? M_PI / 2 : -M_PI / 2;  // facing the field
  intent.may_enter_boundary = true;
  intent.avoid_placement_corridor = game.is_ball_placement();
  intent.role = "substitute";
  intent.skill = "move_to";
  if (game.is_halted()) {
    intent.halt = true;
    intent.max_speed = 0;
    intent.skill = "halt";
  }
  return intent;
}

}  // namespace ssl::planner
