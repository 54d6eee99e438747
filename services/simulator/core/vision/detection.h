// What one simulated SSL-Vision camera sends per frame (SSL_DetectionFrame), in SI units: positions in
// metres in the SSL-Vision global frame, angles in radians, pixels in the camera's image. Times are on the
// SIMULATED clock (the WorldSnapshot's); the adapter converts them to the wire's double seconds and the
// positions to millimetres.
#pragma once

#include <cstdint>
#include <vector>

#include "libs/time/time.h"

namespace ssl::sim {

/// SSL_DetectionBall. Like real ssl-vision, an airborne ball is reported where the camera's ray through it
/// meets the plane z = ball radius, with has_z = false and z = 0 (VisionConfig::report_ball_height changes
/// this to the true x, y, z).
struct BallDetection {
  double x = 0;  // m
  double y = 0;  // m
  double z = 0;  // m, height of the ball's centre; meaningful only if has_z
  bool has_z = false;
  float confidence = 1;    // 0..1
  std::uint32_t area = 0;  // px, blob area
  float pixel_x = 0;       // px
  float pixel_y = 0;       // px

  friend bool operator==(const BallDetection&, const BallDetection&) = default;
};

/// SSL_DetectionRobot: the pattern's centre, heading and the team's configured height.
struct RobotDetection {
  std::uint32_t robot_id = 0;
  double x = 0;            // m
  double y = 0;            // m
  double orientation = 0;  // rad, (-pi, pi], CCW from +x
  float confidence = 1;    // 0..1
  double height = 0;       // m, the team's height used for projection
  float pixel_x = 0;       // px
  float pixel_y = 0;       // px

  friend bool operator==(const RobotDetection&, const RobotDetection&) = default;
};

/// SSL_DetectionFrame of one camera.
struct DetectionFrame {
  std::uint32_t camera_id = 0;
  std::uint32_t frame_number = 0;             // per camera, +1 per captured frame
  time::Timestamp capture_time;               // simulated clock: the snapshot the frame was taken from
  time::Timestamp sent_time;                  // simulated clock: capture_time + delay + jitter
  std::vector<BallDetection> balls;           // most confident first
  std::vector<RobotDetection> robots_yellow;  // by id
  std::vector<RobotDetection> robots_blue;    // by id

  friend bool operator==(const DetectionFrame&, const DetectionFrame&) = default;
};

}  // namespace ssl::sim
