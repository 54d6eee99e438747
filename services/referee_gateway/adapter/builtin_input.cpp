#include "services/referee_gateway/adapter/builtin_input.h"

#include <cmath>

namespace ssl::referee {

void VisionObservation::add(const idl::vision::DetectionFrame& frame) {
  auto it = newest_.find(frame.camera_id());
  // Frames arrive best effort and may be reordered: a capture older than the kept one is late, ignored.
  if (it != newest_.end() && frame.capture_unix_ns() < it->second.capture_unix_ns()) return;
  newest_[frame.camera_id()] = frame;
}

Observation VisionObservation::observe(time::Timestamp now, time::Duration max_age) const {
  Observation out;
  std::map<std::pair<TeamColor, std::uint32_t>, std::pair<Vec2, int>> robots;  // sum of positions, count
  float best_confidence = -1;
  for (const auto& [camera, frame] : newest_) {
    if (now - time::Timestamp::from_nanoseconds(frame.receive_unix_ns()) > max_age) continue;
    for (const auto& ball : frame.balls()) {
      if (!std::isfinite(ball.x()) || !std::isfinite(ball.y())) {
        ++invalid_;
        continue;
      }
      if (ball.confidence() > best_confidence) {
        best_confidence = ball.confidence();
        out.ball_position = Vec2(ball.x(), ball.y());
      }
    }
    for (const TeamColor team : {TeamColor::kYellow, TeamColor::kBlue}) {
      for (const auto& robot : team == TeamColor::kYellow ? frame.robots_yellow() : frame.robots_blue()) {
        if (!std::isfinite(robot.x()) || !std::isfinite(robot.y())) {
          ++invalid_;
          continue;
        }
        auto& [sum, count] = robots[{team, robot.robot_id()}];
        if (count == 0) sum = Vec2::Zero();
        sum += Vec2(robot.x(), robot.y());
        ++count;
      }
    }
  }
  for (const auto& [key, value] : robots) {
    out.robots.push_back({.team = key.first, .id = key.second, .position = value.first / value.second});
  }
  return out;
}

std::optional<OperatorCommand> operator_command(const idl::referee::RefereeOperatorCommand& sample) {
  const int value = static_cast<int>(sample.command());
  if (value < 0 || value >= kCommandCount) return std::nullopt;
  OperatorCommand out{.command = static_cast<Command>(value)};
  if (sample.has_designated_position()) {
    out.designated_position = Vec2(sample.designated_position().x(), sample.designated_position().y());
  }
  return out;
}

}  // namespace ssl::referee
