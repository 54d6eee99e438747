#include "services/simulator/core/vision/geometry.h"

#include <numbers>
#include <utility>

namespace ssl::sim {

std::string_view to_string(FieldShapeType type) {
  switch (type) {
    case FieldShapeType::kUndefined: return "Undefined";
    case FieldShapeType::kCenterCircle: return "CenterCircle";
    case FieldShapeType::kTopTouchLine: return "TopTouchLine";
    case FieldShapeType::kBottomTouchLine: return "BottomTouchLine";
    case FieldShapeType::kLeftGoalLine: return "LeftGoalLine";
    case FieldShapeType::kRightGoalLine: return "RightGoalLine";
    case FieldShapeType::kHalfwayLine: return "HalfwayLine";
    case FieldShapeType::kCenterLine: return "CenterLine";
    case FieldShapeType::kLeftPenaltyStretch: return "LeftPenaltyStretch";
    case FieldShapeType::kRightPenaltyStretch: return "RightPenaltyStretch";
    case FieldShapeType::kLeftFieldLeftPenaltyStretch: return "LeftFieldLeftPenaltyStretch";
    case FieldShapeType::kLeftFieldRightPenaltyStretch: return "LeftFieldRightPenaltyStretch";
    case FieldShapeType::kRightFieldLeftPenaltyStretch: return "RightFieldLeftPenaltyStretch";
    case FieldShapeType::kRightFieldRightPenaltyStretch: return "RightFieldRightPenaltyStretch";
  }
  return "Undefined";
}

std::vector<FieldLine> make_field_lines(const FieldGeometry& field) {
  const double half_length = 0.5 * field.field_length;
  const double half_width = 0.5 * field.field_width;
  const double penalty_x = half_length - field.penalty_area_depth;  // |x| of the penalty stretches
  const double penalty_y = 0.5 * field.penalty_area_width;
  const double thickness = field.line_thickness;
  const auto line = [thickness](FieldShapeType type, Vec2 p1, Vec2 p2) {
    return FieldLine{std::string(to_string(type)), std::move(p1), std::move(p2), thickness, type};
  };
  using T = FieldShapeType;
  // Same order and endpoints as ssl-vision's updateFieldLinesAndArcs.
  return {
      line(T::kTopTouchLine, {-half_length, half_width}, {half_length, half_width}),
      line(T::kBottomTouchLine, {-half_length, -half_width}, {half_length, -half_width}),
      line(T::kLeftGoalLine, {-half_length, -half_width}, {-half_length, half_width}),
      line(T::kRightGoalLine, {half_length, -half_width}, {half_length, half_width}),
      line(T::kHalfwayLine, {0.0, -half_width}, {0.0, half_width}),
      line(T::kCenterLine, {-half_length, 0.0}, {half_length, 0.0}),
      line(T::kLeftPenaltyStretch, {-penalty_x, -penalty_y}, {-penalty_x, penalty_y}),
      line(T::kRightPenaltyStretch, {penalty_x, -penalty_y}, {penalty_x, penalty_y}),
      line(T::kLeftFieldLeftPenaltyStretch, {-half_length, -penalty_y}, {-penalty_x, -penalty_y}),
      line(T::kLeftFieldRightPenaltyStretch, {-half_length, penalty_y}, {-penalty_x, penalty_y}),
      line(T::kRightFieldRightPenaltyStretch, {half_length, -penalty_y}, {penalty_x, -penalty_y}),
      line(T::kRightFieldLeftPenaltyStretch, {half_length, penalty_y}, {penalty_x, penalty_y}),
  };
}

std::vector<FieldArc> make_field_arcs(const FieldGeometry& field) {
  // ssl-vision uses its default radius (0.5 m) and thickness (10 mm); we use the configured field's values,
  // which are the same for both divisions' defaults.
  return {FieldArc{std::string(to_string(FieldShapeType::kCenterCircle)), Vec2::Zero(),
                   field.center_circle_radius, 0.0, 2.0 * std::numbers::pi, field.line_thickness,
                   FieldShapeType::kCenterCircle}};
}

GeometryData make_geometry(const FieldGeometry& field, const VisionConfig& config) {
  GeometryData geometry;
  geometry.field = field;
  geometry.ball_radius = config.ball_radius;
  geometry.max_robot_radius = config.max_robot_radius;
  geometry.lines = make_field_lines(field);
  geometry.arcs = make_field_arcs(field);
  for (const CameraView& camera : make_camera_layout(field, config)) {
    geometry.calibrations.push_back(camera.calibration);
  }
  geometry.ball_models = config.ball_models;
  return geometry;
}

}  // namespace ssl::sim
