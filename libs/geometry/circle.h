// Circle: centre and radius in metres. As a region (contains, intersects, distance) it is the closed disc;
// closest_point() and intersection() work on its boundary.
//
// Contract: radius >= 0. A zero radius is a valid degenerate circle, the single point `center`; negative
// radii are not supported.
//
//   Circle robot{position, 0.09};
#pragma once

#include <numbers>

#include "libs/geometry/vec2.h"

namespace ssl::geom {

struct Circle {
  Vec2 center;
  double radius = 0.0;

  // Area of the disc in square metres.
  double area() const { return std::numbers::pi * radius * radius; }

  friend bool operator==(const Circle& a, const Circle& b) = default;
};

}  // namespace ssl::geom
