// FieldGeometry: the playing field's dimensions, as the rules give them per division (venues may differ by
// up to 10 %, so services fill it from vision.geometry once it arrives). ONE type for the simulator, the
// built-in referee, world_model and the planner. Metres; lengths along x (goal to goal), widths along y;
// "penalty area" is the league's geometry name of the defense area.
//
//   FieldGeometry field = FieldGeometry::of(Division::kB);   // 9 x 6 m
//   geom::Rectangle area = defense_area(field, +1);           // the defense area at +x
#pragma once

#include "libs/common/result.h"
#include "libs/domain/division.h"
#include "libs/geometry/rectangle.h"

namespace ssl {

struct FieldGeometry {
  double field_length = 12.0;             // between goal lines
  double field_width = 9.0;               // between touch lines
  double goal_width = 1.8;                // inner, between the side walls
  double goal_depth = 0.18;
  double goal_height = 0.16;
  double goal_wall_thickness = 0.02;
  double boundary_width = 0.3;            // touch line to wall
  double boundary_width_goal_line = 0.6;  // goal line to wall
  double penalty_area_depth = 1.8;        // the defense area, along x from the goal line
  double penalty_area_width = 3.6;        // the defense area, along y, centred on the goal
  double center_circle_radius = 0.5;
  double line_thickness = 0.01;
  double goal_center_to_penalty_mark = 8.0;  // from the centre of the goal the penalty is shot at
  double goal_substitution_area_width = 0.3;
  double ball_radius = 0.0215;
  double max_robot_radius = 0.09;

  static FieldGeometry division_a() { return {}; }
  static FieldGeometry division_b() {
    FieldGeometry field;
    field.field_length = 9.0;
    field.field_width = 6.0;
    field.goal_width = 1.0;
    field.boundary_width_goal_line = 0.3;
    field.penalty_area_depth = 1.0;
    field.penalty_area_width = 2.0;
    field.goal_center_to_penalty_mark = 6.0;
    return field;
  }
  static FieldGeometry of(Division division) { return division == Division::kA ? division_a() : division_b(); }

  double half_length() const { return 0.5 * field_length; }
  double half_width() const { return 0.5 * field_width; }
  /// m from the centre line to the walls behind the goal lines, and from the halfway line to the walls
  /// beyond the touch lines.
  double wall_half_length() const { return half_length() + boundary_width_goal_line; }
  double wall_half_width() const { return half_width() + boundary_width; }

  friend bool operator==(const FieldGeometry&, const FieldGeometry&) = default;
};

/// The defense area in front of the goal at x = goal_x_sign * field_length / 2 (goal_x_sign +1 or -1).
geom::Rectangle defense_area(const FieldGeometry& field, double goal_x_sign);

/// Rules (number of robots): a robot counts towards its team's limit while any part of it is on the field
/// (the lines belong to it); one standing wholly beyond the field lines, being taken off, does not.
bool counts_towards_robot_limit(const FieldGeometry& field, const geom::Vec2& robot_centre);

/// Where a robot taken off the field waits: in the centre substitution area (the boundary beside the
/// halfway line), wholly beyond the touch line at y sign `touch_line_sign` and clear of the wall, in the
/// half at x sign `half_sign`. `slot` 0, 1, 2 ... lie 0.25 m apart, away from the halfway line, all
/// within rules::kSubstitutionAreaHalfLength of it. Same frame as the signs.
geom::Vec2 substitution_spot(const FieldGeometry& field, double half_sign, double touch_line_sign, int slot);

/// Ok when every length is finite and positive and the goal and defense areas fit in the field.
Status check_field_geometry(const FieldGeometry& field);

}  // namespace ssl
