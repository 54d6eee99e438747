// Rectangle: an axis-aligned rectangle in metres, the closed region between a min and a max corner.
//
// Invariant: min() <= max() in both coordinates (the constructor sorts the corners). A zero width or
// height is a valid degenerate rectangle (a segment or a point). As a region (contains, intersects,
// distance) the boundary is included; closest_point() works on the boundary.
//
//   Rectangle field = Rectangle::from_center({0, 0}, 12.0, 9.0);
//   bool in_play = field.contains(ball);
#pragma once

#include <algorithm>
#include <array>
#include <utility>

#include "libs/geometry/vec2.h"

namespace ssl::geom {

class Rectangle {
 public:
  // The rectangle spanned by two opposite corners, given in any order.
  Rectangle(const Vec2& corner_a, const Vec2& corner_b) : min_(corner_a), max_(corner_b) {
    if (max_.x() < min_.x()) std::swap(min_.x(), max_.x());
    if (max_.y() < min_.y()) std::swap(min_.y(), max_.y());
  }
  // The rectangle centred on `center` with the given width (x) and height (y); negative sizes use |size|.
  static Rectangle from_center(const Vec2& center, double width, double height) {
    const Vec2 half(0.5 * width, 0.5 * height);
    return {center - half, center + half};
  }

  // Corner with the smallest x and y.
  const Vec2& min() const { return min_; }
  // Corner with the largest x and y.
  const Vec2& max() const { return max_; }
  // Centre point.
  Vec2 center() const { return 0.5 * (min_ + max_); }
  // Extent along x, metres.
  double width() const { return max_.x() - min_.x(); }
  // Extent along y, metres.
  double height() const { return max_.y() - min_.y(); }
  // Area in square metres.
  double area() const { return width() * height(); }
  // The four corners counter-clockwise, starting at min().
  std::array<Vec2, 4> corners() const {
    return {min_, Vec2(max_.x(), min_.y()), max_, Vec2(min_.x(), max_.y())};
  }
  // True when p is inside or on the boundary; false for NaN.
  bool contains(const Vec2& p) const {
    return p.x() >= min_.x() && p.x() <= max_.x() && p.y() >= min_.y() && p.y() <= max_.y();
  }
  // Grown by `margin` metres on every side (shrunk if negative, but never past the centre).
  Rectangle expanded(double margin) const {
    const Vec2 c = center();
    const double half_width = std::max(0.0, 0.5 * width() + margin);
    const double half_height = std::max(0.0, 0.5 * height() + margin);
    return {c - Vec2(half_width, half_height), c + Vec2(half_width, half_height)};
  }

  friend bool operator==(const Rectangle& a, const Rectangle& b) = default;

 private:
  Vec2 min_;
  Vec2 max_;
};

}  // namespace ssl::geom
