// Helpers shared by the simulator vision unit tests (not part of the library): snapshot builders and a loop
// that steps a VisionModel through simulated time collecting what it sends.
#pragma once

#include <cstdint>
#include <vector>

#include "services/simulator/core/types.h"
#include "services/simulator/core/vision/vision_model.h"

namespace ssl::sim::testing {

inline constexpr double kBallRadius = 0.0215;

inline time::Timestamp at_seconds(double seconds) { return time::Timestamp::from_seconds(seconds); }

inline RobotState robot_at(TeamColor team, std::uint32_t id, double x, double y, double orientation = 0.0) {
  RobotState robot;
  robot.key = {team, id};
  robot.position = Vec2(x, y);
  robot.orientation = orientation;
  return robot;
}

inline WorldSnapshot snapshot_at(time::Timestamp time, const Vec3& ball,
                                 std::vector<RobotState> robots = {}) {
  WorldSnapshot snapshot;
  snapshot.time = time;
  snapshot.ball.position = ball;
  snapshot.robots = std::move(robots);
  return snapshot;
}

/// A frame as sent, with the simulated time of the update() that returned it.
struct SentFrame {
  DetectionFrame frame;
  time::Timestamp returned_at;
  bool geometry_due = false;
};

/// Steps `model` from `start` for `duration` seconds in steps of `step` seconds, with the ball and robots of
/// `world` (its time is overwritten), and returns every frame sent in order.
inline std::vector<SentFrame> run(VisionModel& model, WorldSnapshot world, double start, double duration,
                                  double step) {
  std::vector<SentFrame> sent;
  const auto steps = static_cast<std::int64_t>(duration / step + 0.5);
  for (std::int64_t i = 0; i <= steps; ++i) {
    world.time =
        time::Timestamp::from_seconds(start) + time::duration_from_seconds(static_cast<double>(i) * step);
    VisionOutput out = model.update(world);
    for (DetectionFrame& frame : out.frames) sent.push_back({std::move(frame), world.time, out.geometry_due});
  }
  return sent;
}

}  // namespace ssl::sim::testing
