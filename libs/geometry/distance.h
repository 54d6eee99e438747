// distance(a, b) and signed_distance(p, shape): Euclidean distances in metres.
//
// distance() is never negative and is symmetric in its arguments (both orders are provided). For the
// regions (circle, rectangle, polygon, stadium) it is the distance to the closed region, so it is 0 for a
// point inside. signed_distance() is the signed distance field: negative inside a region (minus the
// distance to the boundary), positive outside, 0 on the boundary; for a line it is positive on the left of
// line.direction. For every shape with a signed_distance(), its magnitude is |p - closest_point(s, p)|.
// NaN input gives NaN; an empty polygon gives NaN.
//
//   double clearance = distance(ball, robot_circle);   // 0 if the ball is inside the robot disc
//   double depth = -signed_distance(robot, keep_out);  // > 0: how far inside the keep-out zone
#pragma once

#include <cmath>

#include "libs/geometry/circle.h"
#include "libs/geometry/closest_point.h"
#include "libs/geometry/contains.h"
#include "libs/geometry/line.h"
#include "libs/geometry/polygon.h"
#include "libs/geometry/project.h"
#include "libs/geometry/ray.h"
#include "libs/geometry/rectangle.h"
#include "libs/geometry/segment.h"
#include "libs/geometry/stadium.h"
#include "libs/geometry/vec2.h"

namespace ssl::geom {

namespace detail {

// max(value, 0) that keeps NaN (std::max would drop it depending on argument order).
inline double clamp_non_negative(double value) { return value < 0.0 ? 0.0 : value; }

}  // namespace detail

// --- Squared distances (no square root; for hot comparisons against a squared threshold) ---

// |a - b|^2 in square metres.
inline double squared_distance(const Vec2& a, const Vec2& b) { return (a - b).squaredNorm(); }

// Squared distance from p to the nearest point of the segment.
inline double squared_distance(const Vec2& p, const Segment& segment) {
  return (p - project(p, segment).point).squaredNorm();
}

// Squared distance from p to the closed rectangle (0 inside).
inline double squared_distance(const Vec2& p, const Rectangle& rectangle) {
  return rectangle.contains(p) ? 0.0 : (p - closest_point(rectangle, p)).squaredNorm();
}

// --- Unsigned distances ---

// |a - b|.
inline double distance(const Vec2& a, const Vec2& b) { return (a - b).norm(); }

// Distance from p to the nearest point of the segment (an endpoint or the perpendicular foot).
inline double distance(const Vec2& p, const Segment& segment) {
  return std::sqrt(squared_distance(p, segment));
}
inline double distance(const Segment& segment, const Vec2& p) { return distance(p, segment); }

// Perpendicular distance from p to the infinite line (distance to line.point if the line is degenerate).
inline double distance(const Vec2& p, const Line& line) { return (p - project(p, line).point).norm(); }
inline double distance(const Line& line, const Vec2& p) { return distance(p, line); }

// Distance from p to the nearest point of the ray.
inline double distance(const Vec2& p, const Ray& ray) { return (p - project(p, ray).point).norm(); }
inline double distance(const Ray& ray, const Vec2& p) { return distance(p, ray); }

// Distance from p to the closed disc: 0 inside, |p - center| - radius outside.
inline double distance(const Vec2& p, const Circle& circle) {
  return detail::clamp_non_negative((p - circle.center).norm() - circle.radius);
}
inline double distance(const Circle& circle, const Vec2& p) { return distance(p, circle); }

// Distance from p to the closed rectangle: 0 inside.
inline double distance(const Vec2& p, const Rectangle& rectangle) {
  return std::sqrt(squared_distance(p, rectangle));
}
inline double distance(const Rectangle& rectangle, const Vec2& p) { return distance(p, rectangle); }

// Distance from p to the polygon's region: 0 inside or on an edge. O(number of vertices).
double distance(const Vec2& p, const Polygon& polygon);
inline double distance(const Polygon& polygon, const Vec2& p) { return distance(p, polygon); }

// Distance from p to the stadium: 0 inside, else distance to the spine minus the radius.
inline double distance(const Vec2& p, const Stadium& stadium) {
  return detail::clamp_non_negative(distance(p, stadium.spine) - stadium.radius);
}
inline double distance(const Stadium& stadium, const Vec2& p) { return distance(p, stadium); }

// Smallest distance between any two points of the segments: 0 if they touch or cross.
double distance(const Segment& a, const Segment& b);

// --- Signed distances (negative inside) ---

// Perpendicular distance, positive when p is left of (counter-clockwise from) line.direction, negative on
// the right. A degenerate line gives the (non-negative) distance to line.point.
inline double signed_distance(const Vec2& p, const Line& line) {
  const double length = line.direction.norm();
  if (length == 0.0) return (p - line.point).norm();
  return cross(line.direction, p - line.point) / length;
}

// |p - center| - radius: negative inside the disc.
inline double signed_distance(const Vec2& p, const Circle& circle) {
  return (p - circle.center).norm() - circle.radius;
}

// Distance to the rectangle's boundary, negative inside.
inline double signed_distance(const Vec2& p, const Rectangle& rectangle) {
  const double to_boundary = (p - closest_point(rectangle, p)).norm();
  return rectangle.contains(p) ? -to_boundary : to_boundary;
}

// Distance to the polygon's boundary, negative inside (nonzero winding). O(number of vertices).
double signed_distance(const Vec2& p, const Polygon& polygon);

// Distance to the spine minus the radius: negative inside the stadium.
inline double signed_distance(const Vec2& p, const Stadium& stadium) {
  return distance(p, stadium.spine) - stadium.radius;
}

}  // namespace ssl::geom
