// Test helpers for ssl::geom unit tests: compare points with a tolerance and get readable failures.
//
//   EXPECT_TRUE(vec_near(hit, Vec2(1.0, 0.0)));
#pragma once

#include <cmath>
#include <sstream>

#include <gtest/gtest.h>

#include "libs/geometry/vec2.h"

namespace ssl::geom::testing {

// Success when every component of `actual` is within `tolerance` of `expected`.
inline ::testing::AssertionResult vec_near(const Vec2& actual, const Vec2& expected,
                                           double tolerance = 1e-12) {
  if (std::abs(actual.x() - expected.x()) <= tolerance && std::abs(actual.y() - expected.y()) <= tolerance) {
    return ::testing::AssertionSuccess();
  }
  std::ostringstream message;
  message.precision(17);
  message << "(" << actual.x() << ", " << actual.y() << ") is not within " << tolerance << " of ("
          << expected.x() << ", " << expected.y() << ")";
  return ::testing::AssertionFailure() << message.str();
}

// Success when both components are NaN.
inline ::testing::AssertionResult is_nan(const Vec2& actual) {
  if (std::isnan(actual.x()) && std::isnan(actual.y())) return ::testing::AssertionSuccess();
  return ::testing::AssertionFailure() << "(" << actual.x() << ", " << actual.y() << ") is not NaN";
}

}  // namespace ssl::geom::testing
