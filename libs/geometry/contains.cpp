#include "libs/geometry/contains.h"

namespace ssl::geom {

bool contains(const Polygon& polygon, const Vec2& p) {
  if (p.hasNaN()) return false;
  int winding = 0;
  for (std::size_t i = 0; i < polygon.size(); ++i) {
    const Segment edge = polygon.edge(i);
    if (edge.start.hasNaN() || edge.end.hasNaN()) return false;
    if (contains(edge, p)) return true;
    // Count signed crossings of the ray from p towards +x (Sunday's winding-number algorithm).
    const double side = cross(edge.end - edge.start, p - edge.start);  // > 0: p left of the edge
    if (edge.start.y() <= p.y()) {
      if (edge.end.y() > p.y() && side > 0.0) ++winding;  // upward crossing, p to its left
    } else if (edge.end.y() <= p.y() && side < 0.0) {
      --winding;  // downward crossing, p to its right
    }
  }
  return winding != 0;
}

}  // namespace ssl::geom
