// Builders of realistic vision data for the gateway's tests and benchmark, in the core's SI types (convert
// with to_proto for wire bytes):
//   * four_camera_frame(): one capture instant of a Division A match seen by ssl-vision's usual four
//     cameras (quadrants with 0.3 m overlap): 11 blue + 11 yellow robots and the ball, each detection in
//     every camera that sees it;
//   * full_geometry(): a Division A geometry with every optional field, the twelve ssl-vision lines, the
//     centre circle, four camera calibrations and both ball models (values chosen so that mm <-> m
//     round trips are exact in float).
#pragma once

#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

#include "services/vision_gateway/core/types.h"

namespace ssl::vision_gateway::testing {

/// A plausible Unix capture time (2026), seconds.
inline constexpr double kCaptureSeconds = 1'780'000'000.25;

/// A frame with one ball and `robots` blue robots on a line; positions in metres.
inline DetectionFrame simple_frame(std::uint32_t camera_id, std::uint32_t frame_number, int robots = 2,
                                   double capture_seconds = kCaptureSeconds) {
  DetectionFrame frame;
  frame.camera_id = camera_id;
  frame.frame_number = frame_number;
  frame.capture_vision = time::Timestamp::from_seconds(capture_seconds);
  frame.sent_vision = time::Timestamp::from_seconds(capture_seconds + 0.004);
  frame.balls.push_back(
      {.position = {0.5, -0.25}, .confidence = 0.9f, .area = 120, .pixel_x = 100, .pixel_y = 200});
  for (int i = 0; i < robots; ++i) {
    frame.robots_blue.push_back({.robot_id = static_cast<std::uint32_t>(i),
                                 .position = {-1.0 + 0.5 * i, 1.25},
                                 .orientation = 0.5,
                                 .height = 0.15,
                                 .confidence = 0.95f,
                                 .pixel_x = 10.0f * static_cast<float>(i),
                                 .pixel_y = 20});
  }
  return frame;
}

/// The four camera frames of one capture instant (see the header comment).
inline std::vector<DetectionFrame> four_camera_frame(std::uint32_t frame_number,
                                                     double capture_seconds = kCaptureSeconds) {
  constexpr double kOverlap = 0.3;
  std::vector<DetectionFrame> frames(4);
  for (std::uint32_t camera = 0; camera < 4; ++camera) {
    DetectionFrame& frame = frames[camera];
    frame.camera_id = camera;
    frame.frame_number = frame_number;
    frame.capture_vision = time::Timestamp::from_seconds(capture_seconds + 0.0005 * camera);
    frame.sent_vision = time::Timestamp::from_seconds(capture_seconds + 0.003 + 0.0005 * camera);
  }
  // Camera c covers x sign (c % 2 ? + : -) and y sign (c / 2 ? + : -), plus the overlap.
  auto cameras_seeing = [&](const Vec2& p) {
    std::vector<std::uint32_t> seen;
    for (std::uint32_t camera = 0; camera < 4; ++camera) {
      const bool x_ok = camera % 2 == 1 ? p.x() >= -kOverlap : p.x() <= kOverlap;
      const bool y_ok = camera / 2 == 1 ? p.y() >= -kOverlap : p.y() <= kOverlap;
      if (x_ok && y_ok) seen.push_back(camera);
    }
    return seen;
  };
  const Vec2 ball(0.2, -0.1);
  for (std::uint32_t camera : cameras_seeing(ball)) {
    frames[camera].balls.push_back(
        {.position = ball, .confidence = 0.93f, .area = 150, .pixel_x = 1200.5f, .pixel_y = 800.25f});
  }
  for (int team = 0; team < 2; ++team) {
    for (std::uint32_t id = 0; id < 11; ++id) {
      const double side = team == 0 ? -1.0 : 1.0;
      const Vec2 p(side * (0.4 + 0.5 * (id % 5) + 0.05 * id), -4.0 + 0.75 * id);
      const RobotDetection robot{.robot_id = id,
                                 .position = p,
                                 .orientation = team == 0 ? 0.1 * id : M_PI - 0.1 * id,
                                 .height = 0.15,
                                 .confidence = 0.98f,
                                 .pixel_x = 100.0f + 50.0f * static_cast<float>(id),
                                 .pixel_y = 900.0f - 30.0f * static_cast<float>(id)};
      for (std::uint32_t camera : cameras_seeing(p)) {
        (team == 0 ? frames[camera].robots_blue : frames[camera].robots_yellow).push_back(robot);
      }
    }
  }
  return frames;
}

/// A complete Division A geometry (see the header comment). Lengths are whole millimetres.
inline GeometryInput full_geometry() {
  GeometryInput g;
  FieldSizeInput& f = g.field;
  f.field_length = 12.0;
  f.field_width = 9.0;
  f.goal_width = 1.8;
  f.goal_depth = 0.18;
  f.boundary_width = 0.3;
  f.boundary_width_goal_line = 0.6;
  f.penalty_area_depth = 1.8;
  f.penalty_area_width = 3.6;
  f.center_circle_radius = 0.5;
  f.line_thickness = 0.01;
  f.goal_center_to_penalty_mark = 8.0;
  f.goal_height = 0.155;
  f.ball_radius = 0.0215;
  f.max_robot_radius = 0.09;
  f.goal_substitution_area_width = 0.3;
  auto line = [&](std::string name, FieldShapeType type, Vec2 p1, Vec2 p2) {
    f.lines.push_back({.name = std::move(name), .p1 = p1, .p2 = p2, .thickness = 0.01, .type = type});
  };
  line("TopTouchLine", FieldShapeType::kTopTouchLine, {-6.0, 4.5}, {6.0, 4.5});
  line("BottomTouchLine", FieldShapeType::kBottomTouchLine, {-6.0, -4.5}, {6.0, -4.5});
  line("LeftGoalLine", FieldShapeType::kLeftGoalLine, {-6.0, -4.5}, {-6.0, 4.5});
  line("RightGoalLine", FieldShapeType::kRightGoalLine, {6.0, -4.5}, {6.0, 4.5});
  line("HalfwayLine", FieldShapeType::kHalfwayLine, {0.0, -4.5}, {0.0, 4.5});
  line("CenterLine", FieldShapeType::kCenterLine, {-6.0, 0.0}, {6.0, 0.0});
  line("LeftPenaltyStretch", FieldShapeType::kLeftPenaltyStretch, {-4.2, -1.8}, {-4.2, 1.8});
  line("RightPenaltyStretch", FieldShapeType::kRightPenaltyStretch, {4.2, -1.8}, {4.2, 1.8});
  line("LeftFieldLeftPenaltyStretch", FieldShapeType::kLeftFieldLeftPenaltyStretch, {-6.0, -1.8},
       {-4.2, -1.8});
  line("LeftFieldRightPenaltyStretch", FieldShapeType::kLeftFieldRightPenaltyStretch, {-6.0, 1.8},
       {-4.2, 1.8});
  line("RightFieldRightPenaltyStretch", FieldShapeType::kRightFieldRightPenaltyStretch, {6.0, -1.8},
       {4.2, -1.8});
  line("RightFieldLeftPenaltyStretch", FieldShapeType::kRightFieldLeftPenaltyStretch, {6.0, 1.8}, {4.2, 1.8});
  f.arcs.push_back({.name = "CenterCircle",
                    .center = {0.0, 0.0},
                    .radius = 0.5,
                    .a1 = 0.0,
                    .a2 = static_cast<double>(static_cast<float>(2 * M_PI)),
                    .thickness = 0.01,
                    .type = FieldShapeType::kCenterCircle});
  for (std::uint32_t camera = 0; camera < 4; ++camera) {
    const double sx = camera % 2 == 1 ? 1.0 : -1.0;
    const double sy = camera / 2 == 1 ? 1.0 : -1.0;
    g.calibrations.push_back({.camera_id = camera,
                              .focal_length = 1292.5,
                              .principal_point_x = 1224.0,
                              .principal_point_y = 1024.0,
                              .distortion = 0.125,
                              .q0 = 1.0,
                              .q1 = 0.0,
                              .q2 = 0.0,
                              .q3 = 0.0,
                              .tx = -3.0 * sx,
                              .ty = 2.25 * sy,
                              .tz = 4.0,
                              .derived_world = Vec3{3.0 * sx, 2.25 * sy, 4.0},
                              .pixel_image_width = 2448,
                              .pixel_image_height = 2048});
  }
  g.straight_two_phase = BallModelStraightTwoPhase{-3.0, -0.4, 0.69};
  g.chip_fixed_loss = BallModelChipFixedLoss{0.75, 0.95, 0.5};
  return g;
}

}  // namespace ssl::vision_gateway::testing
