// ssl::geom: the stack's one geometry library. Value types plus overloaded free functions, built on Eigen.
//
// Units are SI: metres and radians. Nothing here logs, allocates in an algorithm, or keeps global state.
// Include the header you need, or this one for everything:
//
//   types       vec2.h (Vec2 + helpers), angle.h, segment.h, line.h, ray.h, circle.h, rectangle.h,
//               polygon.h (+ area, centroid, convexity), stadium.h
//   algorithms  project.h, closest_point.h, contains.h, distance.h, intersect.h (intersection, intersects),
//               sight.h (tangent points, subtended angle)
//   tolerance   tolerance.h: the relative rounding allowance used for "touching"
//
// Conventions shared by every function: regions (circle, rectangle, polygon, stadium) are closed, so
// touching counts; closest_point() returns boundary points; intersection() orders results along its first
// argument; degenerate shapes (zero length, zero radius) act as the points they are; NaN input gives NaN,
// nullopt, an empty result or false, never a crash.
#pragma once

#include "libs/geometry/angle.h"
#include "libs/geometry/circle.h"
#include "libs/geometry/closest_point.h"
#include "libs/geometry/contains.h"
#include "libs/geometry/distance.h"
#include "libs/geometry/intersect.h"
#include "libs/geometry/line.h"
#include "libs/geometry/polygon.h"
#include "libs/geometry/project.h"
#include "libs/geometry/ray.h"
#include "libs/geometry/rectangle.h"
#include "libs/geometry/segment.h"
#include "libs/geometry/sight.h"
#include "libs/geometry/stadium.h"
#include "libs/geometry/tolerance.h"
#include "libs/geometry/vec2.h"
