// project(): the foot of the perpendicular from a point onto a line or a segment, with its parameter.
//
// For a line the parameter t is unbounded and counts in units of line.direction (point = line.at(t)); for
// a segment t is clamped to [0, 1] (point = segment.at(t)), so the point is the segment's closest point
// and t is how far along it lies. For the unclamped foot on a segment's supporting line use
// project(p, Line::containing(segment)). Degenerate lines and zero-length segments give t = 0 and their
// single point. NaN input gives NaN t and point.
//
//   Projection along_path = project(robot, path_segment);  // along_path.t = progress in [0, 1]
#pragma once

#include "libs/geometry/line.h"
#include "libs/geometry/ray.h"
#include "libs/geometry/segment.h"
#include "libs/geometry/vec2.h"

namespace ssl::geom {

// A parameter along a line-like shape and the point it names.
struct Projection {
  double t = 0.0;
  Vec2 point;
};

namespace detail {

// Parameter of the foot of the perpendicular from p onto origin + t * direction; 0 if direction is zero.
inline double foot_parameter(const Vec2& p, const Vec2& origin, const Vec2& direction) {
  const double length_squared = direction.squaredNorm();
  if (length_squared == 0.0) return 0.0;
  return (p - origin).dot(direction) / length_squared;
}

}  // namespace detail

// Foot of the perpendicular from p onto the infinite line; t unbounded, point = line.at(t).
inline Projection project(const Vec2& p, const Line& line) {
  const double t = detail::foot_parameter(p, line.point, line.direction);
  return {t, line.at(t)};
}

// Closest point of the segment to p, with its parameter t in [0, 1] (point = segment.at(t)).
inline Projection project(const Vec2& p, const Segment& segment) {
  const double t = detail::foot_parameter(p, segment.start, segment.direction());
  if (t <= 0.0) return {0.0, segment.start};  // exact endpoints; NaN falls through and propagates
  if (t >= 1.0) return {1.0, segment.end};
  return {t, segment.at(t)};
}

// Closest point of the ray to p, with its parameter t >= 0 (point = ray.at(t)).
inline Projection project(const Vec2& p, const Ray& ray) {
  const double t = detail::foot_parameter(p, ray.origin, ray.direction);
  if (t <= 0.0) return {0.0, ray.origin};
  return {t, ray.at(t)};
}

}  // namespace ssl::geom
