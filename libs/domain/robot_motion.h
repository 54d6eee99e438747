// How a robot's velocity follows what it aims for under its acceleration limits: the one law the simulator
// drives its robots by and the world model replays our commands with (RobotLimits semantics). SI units.
#pragma once

#include <algorithm>

#include "libs/geometry/vec2.h"

namespace ssl {

/// One step of dt seconds from `current` towards `target` (m/s, any frame) along the straight line between
/// them: the part of that line on which the speed falls (towards the point nearest standstill) at `brake`,
/// the rest at `speedup` (m/s^2, > 0), so the speed never rises by more than speedup * dt nor falls by more
/// than brake * dt. Returns `target` when it is reachable.
inline geom::Vec2 ramp_velocity(const geom::Vec2& current, const geom::Vec2& target, double speedup, double brake,
                                double dt) {
  const geom::Vec2 delta = target - current;
  const double length = delta.norm();
  if (length == 0.0) return target;
  const geom::Vec2 direction = delta / length;
  // Along current + s * direction the speed falls until s_min (the point nearest standstill), then rises.
  const double s_min = std::clamp(-current.dot(direction), 0.0, length);
  double time_left = dt;
  double s = 0.0;
  if (s_min > 0.0) {
    const double brake_time = s_min / brake;
    if (brake_time >= time_left) return current + direction * (brake * time_left);
    s = s_min;
    time_left -= brake_time;
  }
  const double advance = speedup * time_left;
  if (s + advance >= length) return target;
  return current + direction * (s + advance);
}

}  // namespace ssl
