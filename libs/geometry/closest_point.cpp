#include "libs/geometry/closest_point.h"

#include <cmath>
#include <limits>

namespace ssl::geom {

Vec2 closest_point(const Polygon& polygon, const Vec2& p) {
  Vec2 best = Vec2::Constant(std::numeric_limits<double>::quiet_NaN());
  double best_squared = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < polygon.size(); ++i) {
    const Vec2 candidate = closest_point(polygon.edge(i), p);
    const double squared = (candidate - p).squaredNorm();
    if (std::isnan(squared)) return Vec2::Constant(std::numeric_limits<double>::quiet_NaN());
    if (squared < best_squared) {
      best_squared = squared;
      best = candidate;
    }
  }
  return best;  // still NaN for an empty polygon
}

}  // namespace ssl::geom
