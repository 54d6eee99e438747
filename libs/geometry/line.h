// Line: an infinite straight line, stored as a point on it and a direction (any non-zero length). Metres.
//
// The direction also fixes the parameterisation used by project() (point + t * direction) and the sign
// of signed_distance() (positive on the left, i.e. counter-clockwise of the direction). A zero direction
// is a degenerate line that behaves as the single point `point`; it never intersects another line.
//
//   Line goal_line = Line::through({-4.5, -0.5}, {-4.5, 0.5});
#pragma once

#include "libs/geometry/segment.h"
#include "libs/geometry/vec2.h"

namespace ssl::geom {

struct Line {
  Vec2 point;      // any point on the line
  Vec2 direction;  // need not be unit length

  // The line through a and b, directed from a to b (t = 0 at a, t = 1 at b).
  static Line through(const Vec2& a, const Vec2& b) { return {a, b - a}; }
  // The line through `p` along `direction`.
  static Line from_point_and_direction(const Vec2& p, const Vec2& direction) { return {p, direction}; }
  // The line that contains `s`, directed from s.start to s.end.
  static Line containing(const Segment& s) { return {s.start, s.end - s.start}; }

  // point + t * direction.
  Vec2 at(double t) const { return point + t * direction; }

  friend bool operator==(const Line& a, const Line& b) = default;
};

}  // namespace ssl::geom
