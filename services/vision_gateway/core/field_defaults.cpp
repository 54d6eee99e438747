#include "services/vision_gateway/core/field_defaults.h"

#include <array>
#include <tuple>
#include <utility>

#include "libs/domain/field.h"

namespace ssl::vision_gateway {
namespace {

/// Division A is at least this long (m): halfway between 12 m (A) and 9 m (B).
constexpr double kDivisionALengthThreshold = 10.5;

}  // namespace

OptionalFieldDefaults rulebook_defaults(Division division) {
  const ssl::FieldGeometry rules = ssl::FieldGeometry::of(division);
  return {.boundary_width_goal_line = rules.boundary_width_goal_line,
          .penalty_area_depth = rules.penalty_area_depth,
          .penalty_area_width = rules.penalty_area_width,
          .center_circle_radius = rules.center_circle_radius,
          .line_thickness = rules.line_thickness,
          .goal_center_to_penalty_mark = rules.goal_center_to_penalty_mark,
          .goal_height = rules.goal_height,
          .ball_radius = rules.ball_radius,
          .max_robot_radius = rules.max_robot_radius,
          .goal_substitution_area_width = rules.goal_substitution_area_width};
}

Division detect_division(const FieldSizeInput& field) {
  return field.field_length >= kDivisionALengthThreshold ? Division::kA : Division::kB;
}

FieldGeometry resolve_geometry(const GeometryInput& input, DivisionChoice choice) {
  FieldGeometry out;
  switch (choice) {
    case DivisionChoice::kAuto:
      out.defaults_division = detect_division(input.field);
      break;
    case DivisionChoice::kA:
      out.defaults_division = Division::kA;
      break;
    case DivisionChoice::kB:
      out.defaults_division = Division::kB;
      break;
  }
  const OptionalFieldDefaults defaults = rulebook_defaults(out.defaults_division);
  const FieldSizeInput& in = input.field;
  FieldSize& field = out.field;
  field.field_length = in.field_length;
  field.field_width = in.field_width;
  field.goal_width = in.goal_width;
  field.goal_depth = in.goal_depth;
  field.boundary_width = in.boundary_width;

  // In league field-number order (8..17), so defaulted_fields reads like the proto.
  const std::array<std::tuple<std::string_view, const std::optional<double>*, double, double*>, 10>
      optional_fields{{
          {"penalty_area_depth", &in.penalty_area_depth, defaults.penalty_area_depth,
           &field.penalty_area_depth},
          {"penalty_area_width", &in.penalty_area_width, defaults.penalty_area_width,
           &field.penalty_area_width},
          {"center_circle_radius", &in.center_circle_radius, defaults.center_circle_radius,
           &field.center_circle_radius},
          {"line_thickness", &in.line_thickness, defaults.line_thickness, &field.line_thickness},
          {"goal_center_to_penalty_mark", &in.goal_center_to_penalty_mark,
           defaults.goal_center_to_penalty_mark, &field.goal_center_to_penalty_mark},
          {"goal_height", &in.goal_height, defaults.goal_height, &field.goal_height},
          {"ball_radius", &in.ball_radius, defaults.ball_radius, &field.ball_radius},
          {"max_robot_radius", &in.max_robot_radius, defaults.max_robot_radius, &field.max_robot_radius},
          {"boundary_width_goal_line", &in.boundary_width_goal_line, defaults.boundary_width_goal_line,
           &field.boundary_width_goal_line},
          {"goal_substitution_area_width", &in.goal_substitution_area_width,
           defaults.goal_substitution_area_width, &field.goal_substitution_area_width},
      }};
  for (const auto& [name, received, fallback, target] : optional_fields) {
    if (received->has_value()) {
      *target = **received;
    } else {
      *target = fallback;
      out.defaulted_fields.emplace_back(name);
    }
  }
  field.lines = in.lines;
  field.arcs = in.arcs;
  out.calibrations = input.calibrations;
  out.straight_two_phase = input.straight_two_phase;
  out.chip_fixed_loss = input.chip_fixed_loss;
  return out;
}

FieldShapeType shape_type_from_name(std::string_view name) {
  static constexpr std::array<std::pair<std::string_view, FieldShapeType>, 13> kNames{{
      {"CenterCircle", FieldShapeType::kCenterCircle},
      {"TopTouchLine", FieldShapeType::kTopTouchLine},
      {"BottomTouchLine", FieldShapeType::kBottomTouchLine},
      {"LeftGoalLine", FieldShapeType::kLeftGoalLine},
      {"RightGoalLine", FieldShapeType::kRightGoalLine},
      {"HalfwayLine", FieldShapeType::kHalfwayLine},
      {"CenterLine", FieldShapeType::kCenterLine},
      {"LeftPenaltyStretch", FieldShapeType::kLeftPenaltyStretch},
      {"RightPenaltyStretch", FieldShapeType::kRightPenaltyStretch},
      {"LeftFieldLeftPenaltyStretch", FieldShapeType::kLeftFieldLeftPenaltyStretch},
      {"LeftFieldRightPenaltyStretch", FieldShapeType::kLeftFieldRightPenaltyStretch},
      {"RightFieldLeftPenaltyStretch", FieldShapeType::kRightFieldLeftPenaltyStretch},
      {"RightFieldRightPenaltyStretch", FieldShapeType::kRightFieldRightPenaltyStretch},
  }};
  for (const auto& [known, type] : kNames) {
    if (known == name) return type;
  }
  return FieldShapeType::kUndefined;
}

}  // namespace ssl::vision_gateway
