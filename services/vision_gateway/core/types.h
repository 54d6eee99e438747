// Domain types of the vision gateway core: one SSL-Vision wrapper packet (a camera's detection frame and/or
// the field geometry) in SI units, as the adapter hands it over after decoding and converting the wire
// format once.
//
// Units: metres, radians (CCW from +x), pixels for image coordinates, m/s^2 for ball models.
// Frame: the SSL-Vision global frame (origin at the field centre, x along the field length towards the
// right goal, y along the width, "Left" = -x, "Top" = +y). No flipping happens in the gateway.
// Clocks (ssl::time::Timestamp does not carry its clock, so every name says it):
//   * `capture_vision`, `sent_vision`: the VISION HOST's wall clock (SSL-Vision t_capture / t_sent, Unix);
//   * `capture_camera`: the camera's own clock (t_capture_camera, not necessarily Unix);
//   * `ReceiveTime::wall`: this host's wall clock (Unix) when the datagram arrived; stamped on outputs;
//   * `ReceiveTime::monotonic`: this host's monotonic clock at the same moment; used for every timeout.
// Optional league fields stay std::optional here so that "not sent" is never confused with 0; the core
// resolves them (rulebook defaults for geometry) before anything is published.
//
//   VisionPacket packet;
//   packet.source = VisionSource::kSslVision;
//   packet.detection = DetectionFrame{.camera_id = 2, .frame_number = 17, ...};
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "libs/domain/division.h"
#include "libs/geometry/vec2.h"
#include "libs/time/time.h"

namespace ssl::vision_gateway {

using geom::Vec2;

/// Who produced a packet: the league's SSL_Source (same order and values).
enum class VisionSource : std::uint8_t {
  kUnknown = 0,
  kOther = 1,
  kSslVision = 2,
  kVisionProcessor = 3,
  kGrsim = 4,
  kErforceSim = 5,
};

/// One ball candidate of one camera (SSL_DetectionBall).
struct BallDetection {
  Vec2 position = Vec2::Zero();       // m
  std::optional<double> z;            // m above the carpet; ssl-vision never sends it, simulators may
  float confidence = 0;               // 0..1
  std::optional<std::uint32_t> area;  // blob area, pixels
  float pixel_x = 0;                  // image pixels
  float pixel_y = 0;

  friend bool operator==(const BallDetection&, const BallDetection&) = default;
};

/// One robot seen by one camera (SSL_DetectionRobot).
struct RobotDetection {
  std::optional<std::uint32_t> robot_id;  // pattern id 0..15 (always sent by ssl-vision)
  Vec2 position = Vec2::Zero();           // m
  std::optional<double> orientation;      // rad, CCW from +x
  std::optional<double> height;           // m, the team height configured in ssl-vision
  float confidence = 0;                   // 0..1
  float pixel_x = 0;
  float pixel_y = 0;

  friend bool operator==(const RobotDetection&, const RobotDetection&) = default;
};

/// One camera frame (SSL_DetectionFrame).
struct DetectionFrame {
  std::uint32_t camera_id = 0;
  std::uint32_t frame_number = 0;                 // increases per camera; resets when the camera restarts
  time::Timestamp capture_vision;                 // t_capture, vision host wall clock (Unix)
  time::Timestamp sent_vision;                    // t_sent, vision host wall clock (Unix)
  std::optional<time::Timestamp> capture_camera;  // t_capture_camera, the camera's own clock
  std::vector<BallDetection> balls;
  std::vector<RobotDetection> robots_yellow;
  std::vector<RobotDetection> robots_blue;

  friend bool operator==(const DetectionFrame&, const DetectionFrame&) = default;
};

/// SSL_FieldShapeType: same enumerators, order and values as the league enum.
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

/// The shape type ssl-vision's marking names stand for ("TopTouchLine" -> kTopTouchLine), kUndefined for
/// any other name. Older ssl-vision versions send names without the optional `type` field.
FieldShapeType shape_type_from_name(std::string_view name);

/// A straight field marking (SSL_FieldLineSegment): points on the line's centre.
struct FieldLine {
  std::string name;
  Vec2 p1 = Vec2::Zero();  // m
  Vec2 p2 = Vec2::Zero();  // m
  double thickness = 0;    // m, half on each side
  FieldShapeType type = FieldShapeType::kUndefined;

  friend bool operator==(const FieldLine&, const FieldLine&) = default;
};

/// A circular field marking (SSL_FieldCircularArc), from a1 to a2 counter-clockwise.
struct FieldArc {
  std::string name;
  Vec2 center = Vec2::Zero();  // m
  double radius = 0;           // m
  double a1 = 0;               // rad
  double a2 = 0;               // rad
  double thickness = 0;        // m
  FieldShapeType type = FieldShapeType::kUndefined;

  friend bool operator==(const FieldArc&, const FieldArc&) = default;
};

/// SSL_GeometryFieldSize as received: the five required league fields, the optional ones as sent.
struct FieldSizeInput {
  double field_length = 0;                             // m, between goal lines
  double field_width = 0;                              // m, between touch lines
  double goal_width = 0;                               // m, between the inner post edges
  double goal_depth = 0;                               // m
  double boundary_width = 0;                           // m, touch-line centre to wall
  std::optional<double> boundary_width_goal_line;      // m, goal-line centre to wall
  std::optional<double> penalty_area_depth;            // m
  std::optional<double> penalty_area_width;            // m
  std::optional<double> center_circle_radius;          // m
  std::optional<double> line_thickness;                // m
  std::optional<double> goal_center_to_penalty_mark;   // m
  std::optional<double> goal_height;                   // m
  std::optional<double> ball_radius;                   // m
  std::optional<double> max_robot_radius;              // m
  std::optional<double> goal_substitution_area_width;  // m
  std::vector<FieldLine> lines;
  std::vector<FieldArc> arcs;

  friend bool operator==(const FieldSizeInput&, const FieldSizeInput&) = default;
};

/// The field size after resolution: every value present (m); `defaulted_fields` (in FieldGeometry) names
/// the ones filled from the rulebook.
struct FieldSize {
  double field_length = 0;
  double field_width = 0;
  double goal_width = 0;
  double goal_depth = 0;
  double boundary_width = 0;
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
  std::vector<FieldLine> lines;
  std::vector<FieldArc> arcs;

  friend bool operator==(const FieldSize&, const FieldSize&) = default;
};

/// A point in space, metres.
struct Vec3 {
  double x = 0;
  double y = 0;
  double z = 0;

  friend bool operator==(const Vec3&, const Vec3&) = default;
};

/// SSL_GeometryCameraCalibration. Image quantities stay in pixels; translations are metres.
struct CameraCalibration {
  std::uint32_t camera_id = 0;
  double focal_length = 0;       // pixels
  double principal_point_x = 0;  // pixels
  double principal_point_y = 0;  // pixels
  double distortion = 0;
  double q0 = 0;  // rotation quaternion
  double q1 = 0;
  double q2 = 0;
  double q3 = 0;
  double tx = 0;  // translation, m
  double ty = 0;
  double tz = 0;
  std::optional<Vec3> derived_world;  // camera position in the world, m (present when all three were sent)
  std::optional<std::uint32_t> pixel_image_width;
  std::optional<std::uint32_t> pixel_image_height;

  friend bool operator==(const CameraCalibration&, const CameraCalibration&) = default;
};

/// SSL_BallModelStraightTwoPhase (already SI on the wire).
struct BallModelStraightTwoPhase {
  double acc_slide = 0;  // m/s^2, negative
  double acc_roll = 0;   // m/s^2, negative
  double k_switch = 0;   // fraction of the initial speed at which rolling starts

  friend bool operator==(const BallModelStraightTwoPhase&, const BallModelStraightTwoPhase&) = default;
};

/// SSL_BallModelChipFixedLoss (dimensionless damping factors).
struct BallModelChipFixedLoss {
  double damping_xy_first_hop = 0;
  double damping_xy_other_hops = 0;
  double damping_z = 0;

  friend bool operator==(const BallModelChipFixedLoss&, const BallModelChipFixedLoss&) = default;
};

/// SSL_GeometryData as received.
struct GeometryInput {
  FieldSizeInput field;
  std::vector<CameraCalibration> calibrations;
  std::optional<BallModelStraightTwoPhase> straight_two_phase;
  std::optional<BallModelChipFixedLoss> chip_fixed_loss;

  friend bool operator==(const GeometryInput&, const GeometryInput&) = default;
};

/// Geometry as published: every field resolved.
struct FieldGeometry {
  FieldSize field;
  std::vector<std::string> defaulted_fields;  // league field names filled from the rulebook, in field order
  Division defaults_division = Division::kA;  // the division whose defaults were (or would be) used
  std::vector<CameraCalibration> calibrations;
  std::optional<BallModelStraightTwoPhase> straight_two_phase;
  std::optional<BallModelChipFixedLoss> chip_fixed_loss;

  friend bool operator==(const FieldGeometry&, const FieldGeometry&) = default;
};

/// One decoded SSL_WrapperPacket: a detection frame, a geometry, both or (rarely) neither.
struct VisionPacket {
  std::optional<DetectionFrame> detection;
  std::optional<GeometryInput> geometry;
  VisionSource source = VisionSource::kUnknown;

  friend bool operator==(const VisionPacket&, const VisionPacket&) = default;
};

/// When a datagram arrived, on the two host clocks (read together by the adapter right after receive).
struct ReceiveTime {
  time::Timestamp wall;       // host wall clock, Unix: stamped on published samples
  time::Timestamp monotonic;  // host monotonic clock: timeouts and silences
};

}  // namespace ssl::vision_gateway
