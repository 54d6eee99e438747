// contains(shape, p): whether the point p lies in a shape. Every shape is closed: its boundary counts.
//
// Segments use the library's relative tolerance (tolerance.h), so a point computed to lie on a segment is
// found on it despite rounding. Circles, rectangles and stadiums compare exactly. Polygons use the nonzero
// winding rule (identical to even-odd for simple polygons), with their edges counted as inside.
// NaN input (point or shape) gives false.
//
//   if (contains(defense_area, robot)) { ... }
#pragma once

#include "libs/geometry/circle.h"
#include "libs/geometry/polygon.h"
#include "libs/geometry/project.h"
#include "libs/geometry/rectangle.h"
#include "libs/geometry/segment.h"
#include "libs/geometry/stadium.h"
#include "libs/geometry/tolerance.h"
#include "libs/geometry/vec2.h"

namespace ssl::geom {

// True when p lies on the segment, endpoints included, within the relative tolerance of tolerance.h.
// A zero-length segment contains only its (exact) point.
inline bool contains(const Segment& segment, const Vec2& p) {
  const Vec2 d = segment.direction();
  const Vec2 w = p - segment.start;
  const double length_squared = d.squaredNorm();
  if (length_squared == 0.0) return w.squaredNorm() == 0.0;
  const double c = cross(d, w);
  const double along = d.dot(w);  // t * |d|^2
  return c * c <= kRelativeEpsilon * kRelativeEpsilon * length_squared * w.squaredNorm() &&
         along >= -kRelativeEpsilon * length_squared && along <= (1.0 + kRelativeEpsilon) * length_squared;
}

// True when p is in the closed disc.
inline bool contains(const Circle& circle, const Vec2& p) {
  return (p - circle.center).squaredNorm() <= circle.radius * circle.radius;
}

// True when p is in the closed rectangle.
inline bool contains(const Rectangle& rectangle, const Vec2& p) { return rectangle.contains(p); }

// True when p is inside the polygon (nonzero winding) or on an edge. O(number of vertices).
bool contains(const Polygon& polygon, const Vec2& p);

// True when p is within stadium.radius of the spine.
inline bool contains(const Stadium& stadium, const Vec2& p) {
  const Vec2 on_spine = project(p, stadium.spine).point;
  return (p - on_spine).squaredNorm() <= stadium.radius * stadium.radius;
}

}  // namespace ssl::geom
