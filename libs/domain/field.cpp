#include "libs/domain/field.h"

#include "libs/domain/keep_out.h"
#include "libs/domain/rules.h"

#include <algorithm>
#include <cmath>
#include <string>
#include <utility>

namespace ssl {

geom::Rectangle defense_area(const FieldGeometry& field, double goal_x_sign) {
  const double goal_x = (goal_x_sign < 0 ? -1.0 : 1.0) * field.half_length();
  const double inner_x = goal_x - (goal_x < 0 ? -1.0 : 1.0) * field.penalty_area_depth;
  const double half_width = 0.5 * field.penalty_area_width;
  return {{goal_x, -half_width}, {inner_x, half_width}};
}

geom::Rectangle defense_area_keep_out(const FieldGeometry& field, double goal_x_sign, double margin,
                                      double behind) {
  const double sign = goal_x_sign < 0 ? -1.0 : 1.0;
  const double goal_x = sign * field.half_length();
  const double half_width = 0.5 * field.penalty_area_width + margin;
  return {{goal_x + sign * behind, -half_width}, {goal_x - sign * (field.penalty_area_depth + margin), half_width}};
}

bool counts_towards_robot_limit(const FieldGeometry& field, const geom::Vec2& robot_centre) {
  return std::abs(robot_centre.x()) <= field.half_length() + field.max_robot_radius &&
         std::abs(robot_centre.y()) <= field.half_width() + field.max_robot_radius;
}

geom::Vec2 substitution_spot(const FieldGeometry& field, double half_sign, double touch_line_sign, int slot) {
  constexpr double kFirstFromHalfway = 0.3;  // m, the first spot's distance from the halfway line
  constexpr double kSpacing = 0.25;          // m, between spots: two robots and a gap
  // Wholly beyond the line by a third of the boundary, the rest of the boundary kept from the wall.
  const double beyond = field.max_robot_radius + std::min(0.06, field.boundary_width / 3);
  const double from_halfway =
      std::min(kFirstFromHalfway + kSpacing * std::max(slot, 0), rules::kSubstitutionAreaHalfLength);
  return {(half_sign < 0 ? -1.0 : 1.0) * from_halfway,
          (touch_line_sign < 0 ? -1.0 : 1.0) * (field.half_width() + beyond)};
}

Status check_field_geometry(const FieldGeometry& field) {
  const std::pair<const char*, double> lengths[] = {
      {"field_length", field.field_length},
      {"field_width", field.field_width},
      {"goal_width", field.goal_width},
      {"goal_depth", field.goal_depth},
      {"penalty_area_depth", field.penalty_area_depth},
      {"penalty_area_width", field.penalty_area_width},
      {"center_circle_radius", field.center_circle_radius},
      {"goal_center_to_penalty_mark", field.goal_center_to_penalty_mark},
      {"max_robot_radius", field.max_robot_radius},
      {"ball_radius", field.ball_radius},
  };
  for (const auto& [name, value] : lengths) {
    if (!std::isfinite(value) || value <= 0) {
      return Error{std::string("field geometry: ") + name + " must be a positive number of metres"};
    }
  }
  if (field.goal_width >= field.field_width || field.penalty_area_width >= field.field_width ||
      field.penalty_area_depth >= field.half_length()) {
    return Error{"field geometry: the goal or defense area does not fit in the field"};
  }
  return Status::success();
}

}  // namespace ssl
