#include "libs/domain/field.h"

#include "libs/domain/keep_out.h"

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
