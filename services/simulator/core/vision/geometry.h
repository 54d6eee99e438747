// The geometry packet the simulated SSL-Vision publishes (SSL_GeometryData) in SI units: field size, the
// field markings exactly as ssl-vision generates them, camera calibrations and ball models. The adapter
// converts metres to the millimetres of the wire format.
//
// Markings follow ssl-vision's RoboCupField::updateFieldLinesAndArcs (src/shared/util/field.cpp): twelve
// lines in this order, each named after its shape type, with points on the line centres:
//   TopTouchLine (y = +W/2), BottomTouchLine (y = -W/2), LeftGoalLine (x = -L/2), RightGoalLine (x = +L/2),
//   HalfwayLine (x = 0), CenterLine (y = 0), LeftPenaltyStretch / RightPenaltyStretch (x = -/+(L/2 - depth)),
//   LeftFieldLeftPenaltyStretch (y = -PW/2, x < 0), LeftFieldRightPenaltyStretch (y = +PW/2, x < 0),
//   RightFieldRightPenaltyStretch (y = -PW/2, x > 0), RightFieldLeftPenaltyStretch (y = +PW/2, x > 0),
// and one arc, CenterCircle, from 0 to 2 pi. "Left" is -x, "Top" is +y; the second "Left/Right" of the
// penalty side lines is as seen from the field looking at that goal.
//
//   GeometryData geometry = make_geometry(FieldGeometry::division_b(), VisionConfig{});
//   for (const FieldLine& line : geometry.lines) draw(line.p1, line.p2);
#pragma once

#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "services/simulator/core/types.h"
#include "services/simulator/core/vision/camera.h"
#include "services/simulator/core/vision/vision_config.h"

namespace ssl::sim {

/// SSL_FieldShapeType: same enumerators, order and values as the protobuf enum.
enum class FieldShapeType : std::uint8_t {
  kUndefined = 0,
  kCenterCircle = 1,
  kTopTouchLine = 2,
  kBottomTouchLine = 3,
  kLeftGoalLine = 4,
  kRightGoalLine = 5,
  kHalfwayLine = 6,
  kCenterLine = 7,
  kLeftPenaltyStretch = 8,
  kRightPenaltyStretch = 9,
  kLeftFieldLeftPenaltyStretch = 10,
  kLeftFieldRightPenaltyStretch = 11,
  kRightFieldLeftPenaltyStretch = 12,
  kRightFieldRightPenaltyStretch = 13,
};

/// The protobuf enumerator's name ("TopTouchLine"), which ssl-vision also uses as the shape's name.
std::string_view to_string(FieldShapeType type);

/// SSL_FieldLineSegment, metres.
struct FieldLine {
  std::string name;
  Vec2 p1 = Vec2::Zero();  // on the line's centre
  Vec2 p2 = Vec2::Zero();
  double thickness = 0;  // m, half on each side
  FieldShapeType type = FieldShapeType::kUndefined;

  friend bool operator==(const FieldLine&, const FieldLine&) = default;
};

/// SSL_FieldCircularArc, metres and radians (a1 to a2 counter-clockwise).
struct FieldArc {
  std::string name;
  Vec2 center = Vec2::Zero();
  double radius = 0;
  double a1 = 0;
  double a2 = 0;
  double thickness = 0;
  FieldShapeType type = FieldShapeType::kUndefined;

  friend bool operator==(const FieldArc&, const FieldArc&) = default;
};

/// SSL_GeometryData in SI units.
struct GeometryData {
  FieldGeometry field;
  double ball_radius = 0;       // m
  double max_robot_radius = 0;  // m
  std::vector<FieldLine> lines;
  std::vector<FieldArc> arcs;
  std::vector<CameraCalibration> calibrations;  // by camera id
  BallModels ball_models;
};

/// The twelve field lines ssl-vision generates for `field`, in its order.
std::vector<FieldLine> make_field_lines(const FieldGeometry& field);
/// The arcs ssl-vision generates: the centre circle.
std::vector<FieldArc> make_field_arcs(const FieldGeometry& field);

/// The full geometry for `field` seen by the cameras of `config`, with their nominal calibrations (the
/// VisionModel's geometry() adds its drawn calibration errors). Throws std::invalid_argument for an invalid
/// config.
GeometryData make_geometry(const FieldGeometry& field, const VisionConfig& config);

}  // namespace ssl::sim
