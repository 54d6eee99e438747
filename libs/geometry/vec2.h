// Vec2: a point or a vector in the plane, in metres (Eigen::Vector2d), and the small helpers Eigen lacks.
//
// Points and vectors share one type, as in Eigen; the names of variables say which is meant. The helpers
// are free functions so they also accept Eigen expressions:
//
//   Vec2 left_of_heading = rotate(velocity, Angle::quarter_turn());
//   double side = cross(goal - ball, robot - ball);  // > 0: robot is left of the ball->goal line
//
// NaN components propagate: every helper returns NaN components (or a NaN angle) for a NaN input.
#pragma once

#include <cmath>

#include <Eigen/Core>

#include "libs/geometry/angle.h"

namespace ssl::geom {

using Vec2 = Eigen::Vector2d;

// The vector turned a quarter turn counter-clockwise: (x, y) -> (-y, x). Same length.
inline Vec2 perpendicular(const Vec2& v) { return {-v.y(), v.x()}; }

// 2D cross product a.x * b.y - a.y * b.x: positive when b points counter-clockwise of a, zero when parallel.
inline double cross(const Vec2& a, const Vec2& b) { return a.x() * b.y() - a.y() * b.x(); }

// The vector rotated counter-clockwise by `angle` about the origin.
inline Vec2 rotate(const Vec2& v, Angle angle) {
  const double c = std::cos(angle.radians());
  const double s = std::sin(angle.radians());
  return {c * v.x() - s * v.y(), s * v.x() + c * v.y()};
}

// Unit vector along v, or (0, 0) when v is the zero vector (or so small its squared norm underflows).
inline Vec2 normalized_or_zero(const Vec2& v) {
  const double norm = v.norm();
  if (norm == 0.0) return Vec2::Zero();
  return v / norm;
}

// Unit vector along v, or `fallback` when v is the zero vector.
inline Vec2 normalized_or(const Vec2& v, const Vec2& fallback) {
  const Vec2 u = normalized_or_zero(v);
  return u.squaredNorm() > 0 ? u : fallback;
}

// Direction of v counter-clockwise from +x, in (-pi, pi]; the zero vector gives zero.
inline Angle angle_of(const Vec2& v) { return Angle::from_vector(v); }

}  // namespace ssl::geom
