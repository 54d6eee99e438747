// intersection(a, b): where shapes meet; intersects(a, b): whether they meet at all. Metres.
//
// Two conventions, chosen for collision checks and path queries:
// - intersection() of a path-like shape (segment, ray, line) with another shape reports points in the
//   order they are met along the FIRST argument. With a circle it returns the BOUNDARY crossings (0, 1 for
//   a tangent, or 2) in an Intersections value (fixed capacity, no allocation). With a segment or a
//   rectangle it returns the FIRST point met as std::optional: for collinear overlapping segments that is
//   the overlap's end nearest the path's start, and for a rectangle it is the entry point (the path's start
//   itself when that is inside).
// - intersects() treats circles, rectangles, polygons and stadiums as closed solid regions: a segment
//   wholly inside a circle intersects it, and touching counts. It is symmetric; both orders are provided.
//
// "Touching" allows the relative tolerance of tolerance.h, so endpoints and tangents computed with rounding
// still meet. Degenerate shapes act as what they are: a zero-length segment or zero direction is a point,
// a zero radius is a point. The one exception is line-line: parallel, coincident and degenerate lines
// have no single intersection point and give nullopt.
// Any NaN input gives nullopt, an empty Intersections, or false.
//
//   Intersections hits = intersection(ball_path, robot_circle);
//   if (!hits.empty()) time_to_contact = (hits[0] - ball).norm() / ball_speed;
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <optional>
#include <utility>

#include "libs/geometry/circle.h"
#include "libs/geometry/contains.h"
#include "libs/geometry/distance.h"
#include "libs/geometry/line.h"
#include "libs/geometry/polygon.h"
#include "libs/geometry/ray.h"
#include "libs/geometry/rectangle.h"
#include "libs/geometry/segment.h"
#include "libs/geometry/stadium.h"
#include "libs/geometry/tolerance.h"
#include "libs/geometry/vec2.h"

namespace ssl::geom {

// Up to two points, in order along the path they were computed for. A small value type: no allocation.
class Intersections {
 public:
  // Number of points, 0 to 2.
  int size() const { return size_; }
  // True when there are no points.
  bool empty() const { return size_ == 0; }
  // Point i. Precondition: i < size().
  const Vec2& operator[](int i) const { return points_[i]; }
  const Vec2* begin() const { return points_.data(); }
  const Vec2* end() const { return points_.data() + size_; }
  // Appends a point. Precondition: size() < 2.
  void push_back(const Vec2& p) { points_[size_++] = p; }

 private:
  std::array<Vec2, 2> points_{Vec2::Zero(), Vec2::Zero()};
  int size_ = 0;
};

namespace detail {

inline constexpr double kInfinity = std::numeric_limits<double>::infinity();

// The point p + t * d (exactly p when t == 0).
inline Vec2 point_on_path(const Vec2& p, const Vec2& d, double t) { return t == 0.0 ? p : Vec2(p + t * d); }

// t limited to [t_min, t_max] (NaN stays NaN; callers have already rejected it).
inline double clamp_parameter(double t, double t_min, double t_max) {
  return t < t_min ? t_min : (t > t_max ? t_max : t);
}

// Parameters are compared with an absolute slack of kRelativeEpsilon: they are fractions of a segment
// (or multiples of a direction), so this is the relative tolerance of tolerance.h.
inline bool parameter_in_range(double t, double t_min, double t_max) {
  return t >= t_min - kRelativeEpsilon && t <= t_max + kRelativeEpsilon;
}

// First point of `target` met along the path p + t * d, t in [0, t_max]; see intersection(Segment, Segment).
inline std::optional<Vec2> first_hit(const Vec2& p, const Vec2& d, double t_max, const Segment& target) {
  constexpr double kEps = kRelativeEpsilon;
  const Vec2 e = target.direction();
  const Vec2 w = target.start - p;
  const double dd = d.squaredNorm();
  const double ee = e.squaredNorm();
  const double denominator = cross(d, e);
  if (denominator * denominator > kEps * kEps * dd * ee) {
    // The supporting lines cross at one point: p + t d = target.start + u e.
    const double t = cross(w, e) / denominator;
    const double u = cross(w, d) / denominator;
    if (!parameter_in_range(t, 0.0, t_max) || !parameter_in_range(u, 0.0, 1.0)) return std::nullopt;
    return point_on_path(p, d, clamp_parameter(t, 0.0, t_max));
  }
  // Parallel, degenerate or NaN.
  if (dd == 0.0) {
    if (contains(target, p)) return p;  // the path is a point (NaN fails contains)
    return std::nullopt;
  }
  const double c = cross(d, w);
  if (!(c * c <= kEps * kEps * dd * w.squaredNorm())) return std::nullopt;  // not collinear, or NaN
  // Collinear: overlap of the target's parameter range with [0, t_max] (a point target has t0 == t1).
  const double t0 = d.dot(w) / dd;
  const double t1 = d.dot(target.end - p) / dd;
  const double lo = std::max(std::min(t0, t1), 0.0);
  const double hi = std::min(std::max(t0, t1), t_max);
  if (lo > hi + kEps) return std::nullopt;
  return point_on_path(p, d, std::min(lo, t_max));
}

// Path parameters where p + t * d crosses the circle's boundary, ascending; a tangent counts once.
struct CircleCrossings {
  int count = 0;
  std::array<double, 2> t = {0.0, 0.0};
};

inline CircleCrossings circle_crossings(const Vec2& p, const Vec2& d, const Circle& circle) {
  constexpr double kEps = kRelativeEpsilon;
  const Vec2 w = p - circle.center;
  const double r = circle.radius;
  const double a = d.squaredNorm();
  if (a == 0.0) {  // the path is the point p: on the boundary or not
    const double w2 = w.squaredNorm();
    if (std::abs(w2 - r * r) <= kEps * (w2 + r * r)) return {1, {0.0, 0.0}};
    return {};
  }
  // |w + t d|^2 = r^2  <=>  a t^2 + 2 b t + (|w|^2 - r^2) = 0, whose discriminant b^2 - a (|w|^2 - r^2)
  // is written a r^2 - h^2 (h = cross(d, w)) to avoid cancellation. The tolerance admits rounding in a
  // tangent (scaled by r) and in a zero-radius circle lying on the path (scaled by |w|).
  const double b = d.dot(w);
  const double h = cross(d, w);
  const double discriminant = a * r * r - h * h;
  const double w_extent = std::abs(w.x()) + std::abs(w.y());
  const double tolerance = a * (kEps * r * (r + w_extent) + kEps * kEps * w.squaredNorm());
  if (!(discriminant >= -tolerance)) return {};  // misses, or NaN
  if (discriminant <= tolerance) return {1, {-b / a, 0.0}};
  const double root = std::sqrt(discriminant);
  return {2, {(-b - root) / a, (-b + root) / a}};
}

// Boundary crossings of the circle along p + t * d with t in [t_min, t_max].
inline Intersections circle_hits(const Vec2& p, const Vec2& d, double t_min, double t_max,
                                 const Circle& circle) {
  const CircleCrossings crossings = circle_crossings(p, d, circle);
  Intersections hits;
  for (int i = 0; i < crossings.count; ++i) {
    const double t = crossings.t[i];
    if (parameter_in_range(t, t_min, t_max)) {
      hits.push_back(point_on_path(p, d, clamp_parameter(t, t_min, t_max)));
    }
  }
  return hits;
}

// Entry point of the path p + t * d, t in [0, t_max], into the closed rectangle (slab clipping).
inline std::optional<Vec2> rectangle_entry(const Vec2& p, const Vec2& d, double t_max, const Rectangle& r) {
  if (p.hasNaN() || d.hasNaN() || r.min().hasNaN() || r.max().hasNaN()) return std::nullopt;
  double lo = 0.0;
  double hi = t_max;
  for (int axis = 0; axis < 2; ++axis) {
    if (d[axis] == 0.0) {
      if (p[axis] < r.min()[axis] || p[axis] > r.max()[axis]) return std::nullopt;
      continue;
    }
    double t_near = (r.min()[axis] - p[axis]) / d[axis];
    double t_far = (r.max()[axis] - p[axis]) / d[axis];
    if (t_near > t_far) std::swap(t_near, t_far);
    lo = std::max(lo, t_near);
    hi = std::min(hi, t_far);
  }
  if (lo > hi + kRelativeEpsilon) return std::nullopt;
  return point_on_path(p, d, std::min(lo, t_max));
}

}  // namespace detail

// --- Intersection points ---

// First point of b met going from a.start to a.end. Crossing or touching segments meet in one point;
// collinear overlapping segments return the overlap's end nearest a.start (a.start itself if it lies on
// b). A zero-length segment meets the other only if it lies on it. nullopt if they do not meet.
inline std::optional<Vec2> intersection(const Segment& a, const Segment& b) {
  return detail::first_hit(a.start, a.direction(), 1.0, b);
}

// The single crossing point of two lines; nullopt for parallel or coincident lines (no single point),
// and for degenerate lines.
inline std::optional<Vec2> intersection(const Line& a, const Line& b) {
  const double denominator = cross(a.direction, b.direction);
  const double scale =
      kRelativeEpsilon * kRelativeEpsilon * a.direction.squaredNorm() * b.direction.squaredNorm();
  if (!(denominator * denominator > scale)) return std::nullopt;  // parallel, degenerate or NaN
  return a.at(cross(b.point - a.point, b.direction) / denominator);
}

// First point of the segment met along the ray (collinear overlap: the one nearest the origin).
inline std::optional<Vec2> intersection(const Ray& ray, const Segment& segment) {
  return detail::first_hit(ray.origin, ray.direction, detail::kInfinity, segment);
}

// Where the line crosses the circle's boundary, in the order met along line.direction.
inline Intersections intersection(const Line& line, const Circle& circle) {
  return detail::circle_hits(line.point, line.direction, -detail::kInfinity, detail::kInfinity, circle);
}

// Where the segment crosses the circle's boundary, nearest segment.start first. A segment wholly inside
// or outside the circle has none (use intersects() for "touches the disc").
inline Intersections intersection(const Segment& segment, const Circle& circle) {
  return detail::circle_hits(segment.start, segment.direction(), 0.0, 1.0, circle);
}

// Where the ray crosses the circle's boundary, nearest the origin first (one point if the origin is
// inside the circle).
inline Intersections intersection(const Ray& ray, const Circle& circle) {
  return detail::circle_hits(ray.origin, ray.direction, 0.0, detail::kInfinity, circle);
}

// The first point of the segment inside the closed rectangle, met going from start to end: segment.start
// when it is inside, otherwise where the segment enters. nullopt if it misses the rectangle.
inline std::optional<Vec2> intersection(const Segment& segment, const Rectangle& rectangle) {
  return detail::rectangle_entry(segment.start, segment.direction(), 1.0, rectangle);
}

// The first point of the ray inside the closed rectangle (the origin when it is inside).
inline std::optional<Vec2> intersection(const Ray& ray, const Rectangle& rectangle) {
  return detail::rectangle_entry(ray.origin, ray.direction, detail::kInfinity, rectangle);
}

// --- Boolean tests (regions are solid; touching counts) ---

// True when the segments share at least one point.
inline bool intersects(const Segment& a, const Segment& b) { return intersection(a, b).has_value(); }

// True when the segment touches the closed disc (also when it lies wholly inside).
inline bool intersects(const Segment& segment, const Circle& circle) {
  return squared_distance(circle.center, segment) <= circle.radius * circle.radius;
}
inline bool intersects(const Circle& circle, const Segment& segment) { return intersects(segment, circle); }

// True when the closed discs overlap or touch.
inline bool intersects(const Circle& a, const Circle& b) {
  const double reach = a.radius + b.radius;
  return (a.center - b.center).squaredNorm() <= reach * reach;
}

// True when the closed disc and the closed rectangle overlap or touch.
inline bool intersects(const Circle& circle, const Rectangle& rectangle) {
  return squared_distance(circle.center, rectangle) <= circle.radius * circle.radius;
}
inline bool intersects(const Rectangle& rectangle, const Circle& circle) {
  return intersects(circle, rectangle);
}

// True when the segment touches the closed rectangle (also when it lies wholly inside).
inline bool intersects(const Segment& segment, const Rectangle& rectangle) {
  return intersection(segment, rectangle).has_value();
}
inline bool intersects(const Rectangle& rectangle, const Segment& segment) {
  return intersects(segment, rectangle);
}

// True when the segment touches the polygon's region (crosses an edge or lies inside). O(vertices).
bool intersects(const Segment& segment, const Polygon& polygon);
inline bool intersects(const Polygon& polygon, const Segment& segment) {
  return intersects(segment, polygon);
}

// True when the closed disc touches the polygon's region. O(vertices).
inline bool intersects(const Circle& circle, const Polygon& polygon) {
  return distance(circle.center, polygon) <= circle.radius;
}
inline bool intersects(const Polygon& polygon, const Circle& circle) { return intersects(circle, polygon); }

// True when the segment comes within stadium.radius of the spine.
inline bool intersects(const Segment& segment, const Stadium& stadium) {
  return distance(segment, stadium.spine) <= stadium.radius;
}
inline bool intersects(const Stadium& stadium, const Segment& segment) {
  return intersects(segment, stadium);
}

// True when the closed disc and the stadium overlap or touch.
inline bool intersects(const Circle& circle, const Stadium& stadium) {
  return distance(circle.center, stadium.spine) <= circle.radius + stadium.radius;
}
inline bool intersects(const Stadium& stadium, const Circle& circle) { return intersects(circle, stadium); }

}  // namespace ssl::geom
