#include "libs/geometry/polygon.h"

#include <cmath>
#include <limits>
#include <numbers>
#include <optional>

#include "libs/geometry/tolerance.h"

namespace ssl::geom {
namespace {

bool has_nan_vertex(const Polygon& polygon) {
  for (const Vec2& v : polygon.vertices()) {
    if (v.hasNaN()) return true;
  }
  return false;
}

}  // namespace

double signed_area(const Polygon& polygon) {
  const std::size_t n = polygon.size();
  if (n < 3) return has_nan_vertex(polygon) ? std::numeric_limits<double>::quiet_NaN() : 0.0;
  // Shoelace as a fan from the first vertex, so far-from-origin polygons keep their precision.
  const Vec2& origin = polygon[0];
  double twice_area = 0.0;
  for (std::size_t i = 1; i + 1 < n; ++i) twice_area += cross(polygon[i] - origin, polygon[i + 1] - origin);
  return 0.5 * twice_area;
}

Vec2 centroid(const Polygon& polygon) {
  const std::size_t n = polygon.size();
  const Vec2 nan_point = Vec2::Constant(std::numeric_limits<double>::quiet_NaN());
  if (n == 0 || has_nan_vertex(polygon)) return nan_point;
  const Vec2& origin = polygon[0];
  double twice_area = 0.0;
  double scale = 0.0;  // sum of |twice the fan triangle areas|: what "zero area" is measured against
  Vec2 weighted = Vec2::Zero();
  for (std::size_t i = 1; i + 1 < n; ++i) {
    const Vec2 a = polygon[i] - origin;
    const Vec2 b = polygon[i + 1] - origin;
    const double c = cross(a, b);
    twice_area += c;
    scale += std::abs(c);
    weighted += c * (a + b);  // triangle (origin, a, b): centroid (a + b) / 3, weight c / 2
  }
  if (std::abs(twice_area) <= kRelativeEpsilon * scale) {
    Vec2 sum = Vec2::Zero();
    for (const Vec2& v : polygon.vertices()) sum += v;
    return sum / static_cast<double>(n);
  }
  return origin + weighted / (3.0 * twice_area);
}

bool is_convex(const Polygon& polygon) {
  if (polygon.size() < 3 || has_nan_vertex(polygon)) return false;
  int turn_sign = 0;
  double total_turn = 0.0;
  // Folds the turn from edge e1 to edge e2 into the totals; false if it breaks convexity.
  const auto add_turn = [&](const Vec2& e1, const Vec2& e2) {
    const double c = cross(e1, e2);
    const double d = e1.dot(e2);
    if (c * c <= kRelativeEpsilon * kRelativeEpsilon * e1.squaredNorm() * e2.squaredNorm()) {
      return d > 0.0;  // straight on is fine; a reversal is a zero-width spike
    }
    const int sign = c > 0.0 ? 1 : -1;
    if (turn_sign != 0 && sign != turn_sign) return false;
    turn_sign = sign;
    total_turn += std::atan2(c, d);
    return true;
  };
  std::optional<Vec2> first_edge;
  Vec2 previous_edge = Vec2::Zero();
  for (std::size_t i = 0; i < polygon.size(); ++i) {
    const Vec2 e = polygon.edge(i).direction();
    if (e.squaredNorm() == 0.0) continue;  // repeated vertex
    if (!first_edge) {
      first_edge = e;
    } else if (!add_turn(previous_edge, e)) {
      return false;
    }
    previous_edge = e;
  }
  if (!first_edge || !add_turn(previous_edge, *first_edge)) return false;
  // Same-direction turns that add up to one full turn: a simple convex boundary (a star winds twice).
  return turn_sign != 0 && std::abs(std::abs(total_turn) - 2.0 * std::numbers::pi) < 1e-6;
}

}  // namespace ssl::geom
