// Segment: the straight piece between two points, endpoints included. Metres.
//
// A zero-length segment (start == end) is allowed and behaves as the single point `start` in every
// algorithm (distance, intersection, containment).
//
//   Segment pass{ball, receiver};
//   Vec2 halfway = pass.at(0.5);
#pragma once

#include "libs/geometry/vec2.h"

namespace ssl::geom {

struct Segment {
  Vec2 start;
  Vec2 end;

  // end - start (not normalised).
  Vec2 direction() const { return end - start; }
  // Length in metres.
  double length() const { return (end - start).norm(); }
  // Squared length in square metres (no square root).
  double squared_length() const { return (end - start).squaredNorm(); }
  // The point halfway between start and end.
  Vec2 midpoint() const { return 0.5 * (start + end); }
  // start + t * (end - start): t = 0 is start, t = 1 is end; other t give points on the supporting line.
  Vec2 at(double t) const { return start + t * (end - start); }
  // The same points traversed from end to start.
  Segment reversed() const { return {end, start}; }

  friend bool operator==(const Segment& a, const Segment& b) = default;
};

}  // namespace ssl::geom
