// Polygon: a closed polygon given by its vertices (metres), convex or not, plus area, centroid and
// convexity.
//
// Contract: vertices are listed counter-clockwise (signed_area() > 0) and the last vertex joins the first;
// do not repeat the first vertex at the end. Clockwise input is accepted and every algorithm in this
// library (contains, distance, closest_point, intersects) gives the same answer for either orientation;
// only signed_area() reports it. Degenerate polygons are allowed: no vertices is the empty set, one vertex
// is a point, two are a segment. Self-intersecting polygons are allowed; contains() then uses the nonzero
// winding rule.
//
// Building a polygon allocates (it owns a std::vector); the algorithms that take one do not.
//
//   Polygon defense_area{{-6, -1}, {-4.8, -1}, {-4.8, 1}, {-6, 1}};
//   double a = area(defense_area);  // 2.4 square metres
#pragma once

#include <cmath>
#include <cstddef>
#include <initializer_list>
#include <utility>
#include <vector>

#include "libs/geometry/rectangle.h"
#include "libs/geometry/segment.h"
#include "libs/geometry/vec2.h"

namespace ssl::geom {

class Polygon {
 public:
  // The empty polygon (no vertices).
  Polygon() = default;
  // The polygon with these vertices, in order (counter-clockwise by contract; see the header comment).
  explicit Polygon(std::vector<Vec2> vertices) : vertices_(std::move(vertices)) {}
  Polygon(std::initializer_list<Vec2> vertices) : vertices_(vertices) {}
  // The rectangle as a counter-clockwise quadrilateral starting at its min corner.
  static Polygon from_rectangle(const Rectangle& r) {
    const auto c = r.corners();
    return Polygon{c[0], c[1], c[2], c[3]};
  }

  // The vertices, in the order given.
  const std::vector<Vec2>& vertices() const { return vertices_; }
  // Number of vertices (also the number of edges).
  std::size_t size() const { return vertices_.size(); }
  // True when there are no vertices.
  bool empty() const { return vertices_.empty(); }
  // Vertex i. Precondition: i < size().
  const Vec2& operator[](std::size_t i) const { return vertices_[i]; }
  // Edge i, from vertex i to vertex i + 1 (the last edge closes the polygon). Precondition: i < size().
  Segment edge(std::size_t i) const {
    return {vertices_[i], vertices_[i + 1 == vertices_.size() ? 0 : i + 1]};
  }

  friend bool operator==(const Polygon& a, const Polygon& b) = default;

 private:
  std::vector<Vec2> vertices_;
};

// Signed area in square metres (shoelace formula): positive for counter-clockwise vertices, negative for
// clockwise, zero for fewer than three vertices or collinear ones. NaN if a vertex is NaN.
double signed_area(const Polygon& polygon);

// Area in square metres, |signed_area()|.
inline double area(const Polygon& polygon) { return std::abs(signed_area(polygon)); }

// Centroid (centre of mass of the enclosed area). For zero area (collinear or fewer than three vertices) it
// falls back to the mean of the vertices; NaN for an empty polygon or a NaN vertex.
Vec2 centroid(const Polygon& polygon);

// True for a convex polygon in either orientation: every turn goes the same way and the boundary winds
// once. Collinear and repeated vertices are allowed. False for fewer than three vertices, zero area,
// self-intersecting polygons and NaN vertices.
bool is_convex(const Polygon& polygon);

}  // namespace ssl::geom
