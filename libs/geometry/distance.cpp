#include "libs/geometry/distance.h"

#include <algorithm>
#include <limits>

#include "libs/geometry/intersect.h"

namespace ssl::geom {

double distance(const Vec2& p, const Polygon& polygon) {
  if (polygon.empty()) return std::numeric_limits<double>::quiet_NaN();
  if (contains(polygon, p)) return 0.0;
  return (p - closest_point(polygon, p)).norm();
}

double signed_distance(const Vec2& p, const Polygon& polygon) {
  const double to_boundary = (p - closest_point(polygon, p)).norm();  // NaN when empty
  return contains(polygon, p) ? -to_boundary : to_boundary;
}

double distance(const Segment& a, const Segment& b) {
  if (a.start.hasNaN() || a.end.hasNaN() || b.start.hasNaN() || b.end.hasNaN()) {
    return std::numeric_limits<double>::quiet_NaN();  // std::min below would drop a NaN
  }
  if (intersects(a, b)) return 0.0;
  // Disjoint segments: the nearest pair always includes an endpoint of one of them.
  const double squared = std::min(std::min(squared_distance(a.start, b), squared_distance(a.end, b)),
                                  std::min(squared_distance(b.start, a), squared_distance(b.end, a)));
  return std::sqrt(squared);
}

}  // namespace ssl::geom
