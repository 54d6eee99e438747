#include "libs/geometry/intersect.h"

namespace ssl::geom {

bool intersects(const Segment& segment, const Polygon& polygon) {
  if (contains(polygon, segment.start)) return true;  // wholly inside, or starting on an edge
  for (std::size_t i = 0; i < polygon.size(); ++i) {
    if (intersects(segment, polygon.edge(i))) return true;
  }
  return false;
}

}  // namespace ssl::geom
