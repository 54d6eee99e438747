// Stadium (capsule): every point within `radius` metres of the segment `spine`, boundary included.
//
// SSL ball placement keeps robots 0.5 m away from the line between the ball and the placement position;
// that keep-out zone is Stadium{{ball, placement_position}, 0.5}. A zero-length spine is a disc; a zero
// radius is the segment itself. Contract: radius >= 0.
//
//   Stadium keep_out{{ball, target}, 0.5};
//   bool must_leave = contains(keep_out, robot);
#pragma once

#include <numbers>

#include "libs/geometry/segment.h"

namespace ssl::geom {

struct Stadium {
  Segment spine;
  double radius = 0.0;

  // Area in square metres: the rectangle along the spine plus the two half-discs.
  double area() const { return 2.0 * radius * spine.length() + std::numbers::pi * radius * radius; }

  friend bool operator==(const Stadium& a, const Stadium& b) = default;
};

}  // namespace ssl::geom
