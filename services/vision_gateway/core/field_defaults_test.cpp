// Geometry resolution: optional fields the source left out are filled from the rulebook of the detected
// (or configured) division and named in defaulted_fields; sent values are never replaced.
#include "services/vision_gateway/core/field_defaults.h"

#include <gtest/gtest.h>

#include "services/vision_gateway/testing/builders.h"

namespace ssl::vision_gateway {
namespace {

/// Only the five required fields, as an old ssl-vision or a minimal simulator sends them.
GeometryInput bare_geometry(double length, double width) {
  GeometryInput g;
  g.field.field_length = length;
  g.field.field_width = width;
  g.field.goal_width = 1.0;
  g.field.goal_depth = 0.18;
  g.field.boundary_width = 0.3;
  return g;
}

const std::vector<std::string> kAllOptional = {"penalty_area_depth",
                                               "penalty_area_width",
                                               "center_circle_radius",
                                               "line_thickness",
                                               "goal_center_to_penalty_mark",
                                               "goal_height",
                                               "ball_radius",
                                               "max_robot_radius",
                                               "boundary_width_goal_line",
                                               "goal_substitution_area_width"};

TEST(VisionGatewayDefaults, DivisionIsDetectedFromTheFieldLength) {
  EXPECT_EQ(detect_division(bare_geometry(12.0, 9.0).field), Division::kA);
  EXPECT_EQ(detect_division(bare_geometry(10.5, 7.0).field), Division::kA);
  EXPECT_EQ(detect_division(bare_geometry(10.4, 7.0).field), Division::kB);
  EXPECT_EQ(detect_division(bare_geometry(9.0, 6.0).field), Division::kB);
  EXPECT_EQ(detect_division(bare_geometry(4.0, 3.0).field), Division::kB);  // a lab field
}

TEST(VisionGatewayDefaults, MissingFieldsOfADivisionAFieldGetDivisionARulebookValues) {
  const FieldGeometry g = resolve_geometry(bare_geometry(12.0, 9.0), DivisionChoice::kAuto);
  EXPECT_EQ(g.defaults_division, Division::kA);
  EXPECT_EQ(g.defaulted_fields, kAllOptional);
  EXPECT_DOUBLE_EQ(g.field.penalty_area_depth, 1.8);
  EXPECT_DOUBLE_EQ(g.field.penalty_area_width, 3.6);
  EXPECT_DOUBLE_EQ(g.field.center_circle_radius, 0.5);
  EXPECT_DOUBLE_EQ(g.field.line_thickness, 0.01);
  EXPECT_DOUBLE_EQ(g.field.goal_center_to_penalty_mark, 8.0);
  EXPECT_DOUBLE_EQ(g.field.goal_height, 0.16);
  EXPECT_DOUBLE_EQ(g.field.ball_radius, 0.0215);
  EXPECT_DOUBLE_EQ(g.field.max_robot_radius, 0.09);
  EXPECT_DOUBLE_EQ(g.field.boundary_width_goal_line, 0.6);
  EXPECT_DOUBLE_EQ(g.field.goal_substitution_area_width, 0.3);
  // The required fields pass through.
  EXPECT_DOUBLE_EQ(g.field.field_length, 12.0);
  EXPECT_DOUBLE_EQ(g.field.goal_width, 1.0);
}

TEST(VisionGatewayDefaults, MissingFieldsOfADivisionBFieldGetDivisionBRulebookValues) {
  const FieldGeometry g = resolve_geometry(bare_geometry(9.0, 6.0), DivisionChoice::kAuto);
  EXPECT_EQ(g.defaults_division, Division::kB);
  EXPECT_EQ(g.defaulted_fields, kAllOptional);
  EXPECT_DOUBLE_EQ(g.field.penalty_area_depth, 1.0);
  EXPECT_DOUBLE_EQ(g.field.penalty_area_width, 2.0);
  EXPECT_DOUBLE_EQ(g.field.goal_center_to_penalty_mark, 6.0);
  EXPECT_DOUBLE_EQ(g.field.boundary_width_goal_line, 0.3);
  EXPECT_DOUBLE_EQ(g.field.center_circle_radius, 0.5);
}

TEST(VisionGatewayDefaults, ConfiguredDivisionOverridesDetection) {
  const FieldGeometry g = resolve_geometry(bare_geometry(4.0, 3.0), DivisionChoice::kA);
  EXPECT_EQ(g.defaults_division, Division::kA);
  EXPECT_DOUBLE_EQ(g.field.penalty_area_width, 3.6);
  EXPECT_EQ(resolve_geometry(bare_geometry(12.0, 9.0), DivisionChoice::kB).field.penalty_area_width, 2.0);
}

TEST(VisionGatewayDefaults, SentValuesAreKeptAndOnlyTheMissingOnesAreListed) {
  GeometryInput input = testing::full_geometry();
  input.field.goal_substitution_area_width.reset();
  input.field.ball_radius.reset();
  const FieldGeometry g = resolve_geometry(input, DivisionChoice::kAuto);
  EXPECT_EQ(g.defaulted_fields, (std::vector<std::string>{"ball_radius", "goal_substitution_area_width"}));
  EXPECT_DOUBLE_EQ(g.field.goal_height, 0.155);  // sent (ssl-vision's value), not the rulebook's 0.16
  EXPECT_DOUBLE_EQ(g.field.ball_radius, 0.0215);
  EXPECT_EQ(g.field.lines, input.field.lines);
  EXPECT_EQ(g.field.arcs, input.field.arcs);
  EXPECT_EQ(g.calibrations, input.calibrations);
  EXPECT_EQ(g.straight_two_phase, input.straight_two_phase);
  EXPECT_EQ(g.chip_fixed_loss, input.chip_fixed_loss);
}

TEST(VisionGatewayDefaults, CompleteGeometryHasNoDefaultedFields) {
  EXPECT_TRUE(resolve_geometry(testing::full_geometry(), DivisionChoice::kAuto).defaulted_fields.empty());
}

TEST(VisionGatewayDefaults, ShapeTypesAreKnownByTheirSslVisionNames) {
  EXPECT_EQ(shape_type_from_name("TopTouchLine"), FieldShapeType::kTopTouchLine);
  EXPECT_EQ(shape_type_from_name("CenterCircle"), FieldShapeType::kCenterCircle);
  EXPECT_EQ(shape_type_from_name("RightFieldRightPenaltyStretch"),
            FieldShapeType::kRightFieldRightPenaltyStretch);
  EXPECT_EQ(shape_type_from_name("topTouchLine"), FieldShapeType::kUndefined);
  EXPECT_EQ(shape_type_from_name(""), FieldShapeType::kUndefined);
}

}  // namespace
}  // namespace ssl::vision_gateway
