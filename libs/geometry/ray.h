// Ray: a half-line from `origin` along `direction` (any non-zero length), origin included. Metres.
//
// Intersections with a ray are reported nearest the origin first. A zero direction is a degenerate ray
// that behaves as the single point `origin`.
//
//   Ray shot = Ray::from_angle(ball, Angle::from_degrees(10));
#pragma once

#include "libs/geometry/angle.h"
#include "libs/geometry/vec2.h"

namespace ssl::geom {

struct Ray {
  Vec2 origin;
  Vec2 direction;  // need not be unit length

  // The ray from `origin` heading `heading` (unit direction).
  static Ray from_angle(const Vec2& origin, Angle heading) { return {origin, heading.to_unit_vector()}; }

  // origin + t * direction; the ray is t >= 0.
  Vec2 at(double t) const { return origin + t * direction; }

  friend bool operator==(const Ray& a, const Ray& b) = default;
};

}  // namespace ssl::geom
