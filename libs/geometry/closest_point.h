// closest_point(shape, p): the point of a shape nearest to p, in metres.
//
// Segments, lines and rays are their own boundary. For the regions (circle, rectangle, polygon, stadium)
// the answer is always on the BOUNDARY, also when p is inside: it is where a robot inside a zone would
// leave it the quickest way. So |p - closest_point(shape, p)| == |signed_distance(p, shape)| wherever
// signed_distance() exists (see distance.h). When several boundary points are equally near (p at a circle's
// centre, on a stadium's spine, at a rectangle's centre) one of them is returned, as documented per function.
// NaN input, or an empty polygon, gives NaN components.
//
//   Vec2 exit_point = closest_point(keep_out_stadium, robot);
#pragma once

#include <algorithm>

#include "libs/geometry/circle.h"
#include "libs/geometry/line.h"
#include "libs/geometry/polygon.h"
#include "libs/geometry/project.h"
#include "libs/geometry/ray.h"
#include "libs/geometry/rectangle.h"
#include "libs/geometry/segment.h"
#include "libs/geometry/stadium.h"
#include "libs/geometry/vec2.h"

namespace ssl::geom {

// Point of the segment nearest p (an endpoint or the foot of the perpendicular).
inline Vec2 closest_point(const Segment& segment, const Vec2& p) { return project(p, segment).point; }

// Foot of the perpendicular from p onto the line (line.point if the line is degenerate).
inline Vec2 closest_point(const Line& line, const Vec2& p) { return project(p, line).point; }

// Point of the ray nearest p (the origin or the foot of the perpendicular).
inline Vec2 closest_point(const Ray& ray, const Vec2& p) { return project(p, ray).point; }

// Point on the circle's boundary nearest p; for p at the centre, center + (radius, 0).
inline Vec2 closest_point(const Circle& circle, const Vec2& p) {
  const Vec2 offset = p - circle.center;
  const double norm = offset.norm();
  if (norm == 0.0) return circle.center + Vec2(circle.radius, 0.0);
  return circle.center + offset * (circle.radius / norm);
}

// Point on the rectangle's boundary nearest p. Inside, ties between edges go to the first of
// left (min x), right, bottom (min y), top.
inline Vec2 closest_point(const Rectangle& rectangle, const Vec2& p) {
  const Vec2& lo = rectangle.min();
  const Vec2& hi = rectangle.max();
  if (!rectangle.contains(p)) {
    // Clamp each coordinate; written with comparisons so a NaN coordinate stays NaN.
    return {p.x() < lo.x() ? lo.x() : (p.x() > hi.x() ? hi.x() : p.x()),
            p.y() < lo.y() ? lo.y() : (p.y() > hi.y() ? hi.y() : p.y())};
  }
  const double to_left = p.x() - lo.x();
  const double to_right = hi.x() - p.x();
  const double to_bottom = p.y() - lo.y();
  const double to_top = hi.y() - p.y();
  const double nearest = std::min(std::min(to_left, to_right), std::min(to_bottom, to_top));
  if (to_left == nearest) return {lo.x(), p.y()};
  if (to_right == nearest) return {hi.x(), p.y()};
  if (to_bottom == nearest) return {p.x(), lo.y()};
  return {p.x(), hi.y()};
}

// Point on the polygon's boundary (its edges) nearest p. O(number of vertices).
Vec2 closest_point(const Polygon& polygon, const Vec2& p);

// Point on the stadium's boundary nearest p; for p on the spine, the point to the spine's left
// (counter-clockwise of start -> end), or +x for a zero-length spine.
inline Vec2 closest_point(const Stadium& stadium, const Vec2& p) {
  const Vec2 on_spine = closest_point(stadium.spine, p);
  Vec2 outward = normalized_or_zero(p - on_spine);
  if (outward.isZero(0.0)) {
    outward = perpendicular(normalized_or_zero(stadium.spine.direction()));
    if (outward.isZero(0.0)) outward = Vec2::UnitX();
  }
  return on_spine + stadium.radius * outward;
}

}  // namespace ssl::geom
