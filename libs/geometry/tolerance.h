// Tolerance: the one rounding allowance the geometry predicates use, and why it is relative.
//
// Coordinates are metres on a field about 10 m across, so rounding error in a double is around 1e-15 m.
// Predicates that decide "touching" (a point on a segment, parallel lines, a tangent, an endpoint on an
// edge) accept errors up to kRelativeEpsilon times the size of the quantities involved: a direction
// within 1e-12 rad of another is parallel, and a segment parameter within 1e-12 of [0, 1] is on the
// segment. This is far above double rounding (about 1e-16) and far below anything physical, and being
// relative it does not depend on units or on where the shapes are.
#pragma once

namespace ssl::geom {

// Relative tolerance (dimensionless) for sine of angles and for segment parameters.
inline constexpr double kRelativeEpsilon = 1e-12;

}  // namespace ssl::geom
