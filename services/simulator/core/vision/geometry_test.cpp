#include "services/simulator/core/vision/geometry.h"

#include <cstddef>
#include <numbers>
#include <stdexcept>
#include <string>
#include <vector>

#include <gtest/gtest.h>

namespace ssl::sim {
namespace {

using T = FieldShapeType;

struct ExpectedLine {
  T type;
  Vec2 p1;
  Vec2 p2;
};

// ssl-vision's updateFieldLinesAndArcs for a field of half length hl, half width hw, penalty stretch at |x| =
// px and penalty side lines at |y| = py, in its order.
std::vector<ExpectedLine> ssl_vision_lines(double hl, double hw, double px, double py) {
  return {
      {T::kTopTouchLine, {-hl, hw}, {hl, hw}},
      {T::kBottomTouchLine, {-hl, -hw}, {hl, -hw}},
      {T::kLeftGoalLine, {-hl, -hw}, {-hl, hw}},
      {T::kRightGoalLine, {hl, -hw}, {hl, hw}},
      {T::kHalfwayLine, {0, -hw}, {0, hw}},
      {T::kCenterLine, {-hl, 0}, {hl, 0}},
      {T::kLeftPenaltyStretch, {-px, -py}, {-px, py}},
      {T::kRightPenaltyStretch, {px, -py}, {px, py}},
      {T::kLeftFieldLeftPenaltyStretch, {-hl, -py}, {-px, -py}},
      {T::kLeftFieldRightPenaltyStretch, {-hl, py}, {-px, py}},
      {T::kRightFieldRightPenaltyStretch, {hl, -py}, {px, -py}},
      {T::kRightFieldLeftPenaltyStretch, {hl, py}, {px, py}},
  };
}

void expect_lines(const std::vector<FieldLine>& lines, const std::vector<ExpectedLine>& expected,
                  double thickness) {
  ASSERT_EQ(lines.size(), expected.size());
  for (std::size_t i = 0; i < lines.size(); ++i) {
    SCOPED_TRACE("line " + std::to_string(i) + " " + lines[i].name);
    EXPECT_EQ(lines[i].type, expected[i].type);
    EXPECT_EQ(lines[i].name, to_string(expected[i].type));
    EXPECT_NEAR(lines[i].p1.x(), expected[i].p1.x(), 1e-12);
    EXPECT_NEAR(lines[i].p1.y(), expected[i].p1.y(), 1e-12);
    EXPECT_NEAR(lines[i].p2.x(), expected[i].p2.x(), 1e-12);
    EXPECT_NEAR(lines[i].p2.y(), expected[i].p2.y(), 1e-12);
    EXPECT_DOUBLE_EQ(lines[i].thickness, thickness);
  }
}

TEST(SimVisionGeometryTest, ShapeTypesHaveTheProtobufValuesAndNames) {
  EXPECT_EQ(static_cast<int>(T::kUndefined), 0);
  EXPECT_EQ(static_cast<int>(T::kCenterCircle), 1);
  EXPECT_EQ(static_cast<int>(T::kTopTouchLine), 2);
  EXPECT_EQ(static_cast<int>(T::kBottomTouchLine), 3);
  EXPECT_EQ(static_cast<int>(T::kLeftGoalLine), 4);
  EXPECT_EQ(static_cast<int>(T::kRightGoalLine), 5);
  EXPECT_EQ(static_cast<int>(T::kHalfwayLine), 6);
  EXPECT_EQ(static_cast<int>(T::kCenterLine), 7);
  EXPECT_EQ(static_cast<int>(T::kLeftPenaltyStretch), 8);
  EXPECT_EQ(static_cast<int>(T::kRightPenaltyStretch), 9);
  EXPECT_EQ(static_cast<int>(T::kLeftFieldLeftPenaltyStretch), 10);
  EXPECT_EQ(static_cast<int>(T::kLeftFieldRightPenaltyStretch), 11);
  EXPECT_EQ(static_cast<int>(T::kRightFieldLeftPenaltyStretch), 12);
  EXPECT_EQ(static_cast<int>(T::kRightFieldRightPenaltyStretch), 13);
  EXPECT_EQ(to_string(T::kUndefined), "Undefined");
  EXPECT_EQ(to_string(T::kCenterCircle), "CenterCircle");
  EXPECT_EQ(to_string(T::kLeftFieldRightPenaltyStretch), "LeftFieldRightPenaltyStretch");
  EXPECT_EQ(to_string(T::kRightFieldRightPenaltyStretch), "RightFieldRightPenaltyStretch");
}

TEST(SimVisionGeometryTest, DivisionALinesAreSslVisionsLines) {
  const FieldGeometry field = FieldGeometry::division_a();
  const std::vector<FieldLine> lines = make_field_lines(field);
  // 12 x 9 m, defense area 1.8 m deep and 3.6 m wide: stretches at |x| = 4.2, side lines at |y| = 1.8.
  expect_lines(lines, ssl_vision_lines(6.0, 4.5, 4.2, 1.8), 0.01);
  EXPECT_DOUBLE_EQ(lines[0].p1.y(), 4.5);   // TopTouchLine at +width / 2
  EXPECT_DOUBLE_EQ(lines[1].p1.y(), -4.5);  // BottomTouchLine at -width / 2
}

TEST(SimVisionGeometryTest, DivisionBLinesAreSslVisionsLines) {
  const FieldGeometry field = FieldGeometry::division_b();
  // 9 x 6 m, defense area 1 m deep and 2 m wide: stretches at |x| = 3.5, side lines at |y| = 1.
  expect_lines(make_field_lines(field), ssl_vision_lines(4.5, 3.0, 3.5, 1.0), 0.01);
}

TEST(SimVisionGeometryTest, LinesFollowAChangedField) {
  FieldGeometry field = FieldGeometry::division_b();
  field.field_length = 10.0;
  field.field_width = 7.0;
  field.penalty_area_depth = 1.2;
  field.penalty_area_width = 2.4;
  field.line_thickness = 0.02;
  expect_lines(make_field_lines(field), ssl_vision_lines(5.0, 3.5, 3.8, 1.2), 0.02);
}

TEST(SimVisionGeometryTest, CenterCircleIsTheOnlyArc) {
  for (const FieldGeometry& field : {FieldGeometry::division_a(), FieldGeometry::division_b()}) {
    const std::vector<FieldArc> arcs = make_field_arcs(field);
    ASSERT_EQ(arcs.size(), 1u);
    EXPECT_EQ(arcs[0].name, "CenterCircle");
    EXPECT_EQ(arcs[0].type, T::kCenterCircle);
    EXPECT_EQ(arcs[0].center, Vec2(0.0, 0.0));
    EXPECT_DOUBLE_EQ(arcs[0].radius, 0.5);
    EXPECT_DOUBLE_EQ(arcs[0].a1, 0.0);
    EXPECT_DOUBLE_EQ(arcs[0].a2, 2.0 * std::numbers::pi);
    EXPECT_DOUBLE_EQ(arcs[0].thickness, 0.01);
  }
}

TEST(SimVisionGeometryTest, GeometryCarriesFieldSizesModelsAndOneCalibrationPerCamera) {
  VisionConfig config;
  config.camera_count = 8;
  config.ball_models.acc_slide = -2.5;
  const GeometryData geometry = make_geometry(FieldGeometry::division_a(), config);
  EXPECT_DOUBLE_EQ(geometry.field.field_length, 12.0);
  EXPECT_DOUBLE_EQ(geometry.field.boundary_width_goal_line, 0.6);
  EXPECT_DOUBLE_EQ(geometry.ball_radius, 0.0215);
  EXPECT_DOUBLE_EQ(geometry.max_robot_radius, 0.09);
  EXPECT_EQ(geometry.lines.size(), 12u);
  EXPECT_EQ(geometry.arcs.size(), 1u);
  ASSERT_EQ(geometry.calibrations.size(), 8u);
  for (std::size_t i = 0; i < geometry.calibrations.size(); ++i) {
    EXPECT_EQ(geometry.calibrations[i].camera_id, i);
  }
  EXPECT_DOUBLE_EQ(geometry.ball_models.acc_slide, -2.5);
  EXPECT_DOUBLE_EQ(geometry.ball_models.acc_roll, -0.4);
}

TEST(SimVisionGeometryTest, InvalidConfigsAreRejected) {
  const FieldGeometry field = FieldGeometry::division_a();
  VisionConfig config;
  config.camera_count = 3;
  EXPECT_THROW(make_geometry(field, config), std::invalid_argument);
  config = VisionConfig{};
  config.frame_rate = 0.0;
  EXPECT_THROW(make_geometry(field, config), std::invalid_argument);
  config = VisionConfig{};
  config.realism.ball_missing_probability = 1.5;
  EXPECT_THROW(make_geometry(field, config), std::invalid_argument);
  config = VisionConfig{};
  config.realism.robot_position_stddev = -0.001;
  EXPECT_THROW(make_geometry(field, config), std::invalid_argument);
  EXPECT_NO_THROW(RealismConfig::none().validate());
  EXPECT_NO_THROW(RealismConfig::realistic().validate());
  EXPECT_NO_THROW(RealismConfig::competition().validate());
}

}  // namespace
}  // namespace ssl::sim
