// Sight lines from a point: the tangent points of a circle, and the angle a segment subtends. Metres.
//
// These are the pieces of shot and pass evaluation: an obstacle robot (a circle) hides the directions
// between its two tangent points, and a goal mouth (a segment between the posts) is open over the angle it
// subtends from the ball.
//
//   if (auto t = tangent_points(ball, defender)) {
//     Angle hidden_from = angle_of(t->right - ball), hidden_to = angle_of(t->left - ball);  // CCW interval
//   }
//   Angle goal_opening = subtended_angle(ball, Segment{left_post, right_post});
#pragma once

#include <cmath>
#include <optional>

#include "libs/geometry/angle.h"
#include "libs/geometry/circle.h"
#include "libs/geometry/segment.h"
#include "libs/geometry/tolerance.h"
#include "libs/geometry/vec2.h"

namespace ssl::geom {

// The two points where lines from a viewpoint touch a circle. Left and right are as seen from the
// viewpoint looking at the circle's centre, so the circle hides the directions counter-clockwise from
// `right` to `left`.
struct TangentPoints {
  Vec2 left;
  Vec2 right;
};

// Tangent points of the circle seen from `from`. Both are `from` itself when it lies on the circle (one
// tangent line, also within rounding: tolerance.h); nullopt when `from` is inside the circle, or for NaN
// input. A zero-radius circle gives its centre twice.
inline std::optional<TangentPoints> tangent_points(const Vec2& from, const Circle& circle) {
  const Vec2 offset = from - circle.center;
  const double distance_squared = offset.squaredNorm();
  const double radius_squared = circle.radius * circle.radius;
  const double excess = distance_squared - radius_squared;                   // negative inside the circle
  if (!(excess >= -kRelativeEpsilon * radius_squared)) return std::nullopt;  // inside, or NaN
  // On the circle (up to rounding), or a zero radius seen from its centre: one tangent, touching at `from`.
  if (excess <= 0.0) return TangentPoints{from, from};
  // The tangent points lie on the chord perpendicular to `offset`, at radius^2 / distance from the centre.
  const Vec2 chord_middle = circle.center + (radius_squared / distance_squared) * offset;
  const Vec2 half_chord = (circle.radius * std::sqrt(excess) / distance_squared) * perpendicular(offset);
  return TangentPoints{chord_middle - half_chord, chord_middle + half_chord};
}

// The angle between the sight lines from `from` to the segment's two endpoints, in [0, pi]: how wide the
// segment looks. pi when `from` lies strictly between the endpoints; zero when `from` is an endpoint, is
// on the segment's line outside it, or the segment has zero length. NaN for NaN input.
inline Angle subtended_angle(const Vec2& from, const Segment& target) {
  const Vec2 a = target.start - from;
  const Vec2 b = target.end - from;
  return Angle::from_radians(std::atan2(std::abs(cross(a, b)), a.dot(b)));
}

}  // namespace ssl::geom
