// Rulebook defaults for the optional SSL_GeometryFieldSize fields, per division, and the resolution of a
// received field size into one where every value is present.
//
// Values (metres) are the shared field geometry's by division (libs/domain/field.h: the current rulebook,
// shared/reference/ssl-protocols.md section 13.1, and ssl-vision's constants where the rulebook is silent):
//
//   field                          Div A    Div B
//   boundary_width_goal_line       0.6      0.3     (ssl-vision sends 0.6 for B too; the rules say 0.3)
//   penalty_area_depth             1.8      1.0
//   penalty_area_width             3.6      2.0
//   center_circle_radius           0.5      0.5
//   line_thickness                 0.01     0.01
//   goal_center_to_penalty_mark    8.0      6.0
//   goal_height                    0.16     0.16    (goal wall height; ssl-vision's constant is 0.155)
//   ball_radius                    0.0215   0.0215  (43 mm diameter ball)
//   max_robot_radius               0.09     0.09
//   goal_substitution_area_width   0.3      0.3
//
// The division is detected from the (always sent) field length: at least 10.5 m (halfway between the
// 12 m of Division A and the 9 m of Division B) is Division A.
//
//   FieldGeometry resolved = resolve_geometry(input, DivisionChoice::kAuto);
//   resolved.defaulted_fields;   // {"goal_substitution_area_width"} when only that one was missing
#pragma once

#include <optional>
#include <string_view>

#include "services/vision_gateway/core/types.h"

namespace ssl::vision_gateway {

/// Which division's defaults fill missing fields: detected from the field length, or fixed by config.
enum class DivisionChoice : std::uint8_t { kAuto, kA, kB };

/// The rulebook value of every optional field for a division (metres).
struct OptionalFieldDefaults {
  double boundary_width_goal_line = 0;
  double penalty_area_depth = 0;
  double penalty_area_width = 0;
  double center_circle_radius = 0;
  double line_thickness = 0;
  double goal_center_to_penalty_mark = 0;
  double goal_height = 0;
  double ball_radius = 0;
  double max_robot_radius = 0;
  double goal_substitution_area_width = 0;
};

/// The defaults of one division (see the table above).
OptionalFieldDefaults rulebook_defaults(Division division);

/// Division A when the field is at least 10.5 m long, else Division B.
Division detect_division(const FieldSizeInput& field);

/// Fills every optional field the source left out from the chosen division's defaults, and lists the
/// filled ones (by their league field names, in field-number order) in `defaulted_fields`. Lines, arcs,
/// calibrations and ball models are copied as they are.
FieldGeometry resolve_geometry(const GeometryInput& input, DivisionChoice choice);

}  // namespace ssl::vision_gateway
