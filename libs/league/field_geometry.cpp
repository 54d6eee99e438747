#include "libs/league/field_geometry.h"

namespace ssl::league {

FieldGeometry field_from_proto(const SSL_GeometryFieldSize& field) {
  auto metres = [](double millimetres) { return millimetres / 1000.0; };
  FieldGeometry geometry = field.field_length() <= 10000 ? FieldGeometry::division_b() : FieldGeometry::division_a();
  geometry.field_length = metres(field.field_length());
  geometry.field_width = metres(field.field_width());
  geometry.goal_width = metres(field.goal_width());
  geometry.goal_depth = metres(field.goal_depth());
  geometry.boundary_width = metres(field.boundary_width());
  if (field.has_boundary_width_goal_line()) geometry.boundary_width_goal_line = metres(field.boundary_width_goal_line());
  if (field.has_penalty_area_depth()) geometry.penalty_area_depth = metres(field.penalty_area_depth());
  if (field.has_penalty_area_width()) geometry.penalty_area_width = metres(field.penalty_area_width());
  if (field.has_center_circle_radius()) geometry.center_circle_radius = metres(field.center_circle_radius());
  if (field.has_line_thickness()) geometry.line_thickness = metres(field.line_thickness());
  if (field.has_goal_center_to_penalty_mark()) {
    geometry.goal_center_to_penalty_mark = metres(field.goal_center_to_penalty_mark());
  }
  if (field.has_goal_height()) geometry.goal_height = metres(field.goal_height());
  if (field.has_goal_substitution_area_width()) {
    geometry.goal_substitution_area_width = metres(field.goal_substitution_area_width());
  }
  return geometry;
}

}  // namespace ssl::league
