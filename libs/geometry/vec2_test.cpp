#include "libs/geometry/vec2.h"

#include <cmath>
#include <limits>
#include <numbers>
#include <random>

#include <gtest/gtest.h>

#include "libs/geometry/test_util.h"

namespace ssl::geom {
namespace {

using testing::is_nan;
using testing::vec_near;

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

TEST(GeomVec2Test, PerpendicularTurnsAQuarterCounterClockwise) {
  EXPECT_EQ(perpendicular(Vec2(3.0, 4.0)), Vec2(-4.0, 3.0));
  EXPECT_EQ(perpendicular(Vec2(1.0, 0.0)), Vec2(0.0, 1.0));
  EXPECT_EQ(perpendicular(Vec2(3.0, 4.0)).dot(Vec2(3.0, 4.0)), 0.0);
  // Accepts Eigen expressions.
  EXPECT_EQ(perpendicular(Vec2(1.0, 1.0) + Vec2(0.0, 1.0)), Vec2(-2.0, 1.0));
}

TEST(GeomVec2Test, CrossIsPositiveWhenSecondIsCounterClockwiseOfFirst) {
  EXPECT_EQ(cross(Vec2(1.0, 0.0), Vec2(0.0, 1.0)), 1.0);
  EXPECT_EQ(cross(Vec2(0.0, 1.0), Vec2(1.0, 0.0)), -1.0);
  EXPECT_EQ(cross(Vec2(2.0, 3.0), Vec2(4.0, 5.0)), -2.0);
  EXPECT_EQ(cross(Vec2(2.0, 3.0), Vec2(4.0, 6.0)), 0.0);
}

TEST(GeomVec2Test, RotateTurnsCounterClockwiseAboutTheOrigin) {
  EXPECT_TRUE(vec_near(rotate(Vec2(1.0, 0.0), Angle::quarter_turn()), Vec2(0.0, 1.0), 1e-16));
  EXPECT_TRUE(vec_near(rotate(Vec2(1.0, 2.0), Angle::half_turn()), Vec2(-1.0, -2.0), 1e-15));
  EXPECT_TRUE(
      vec_near(rotate(Vec2(2.0, 0.0), Angle::from_degrees(-60.0)), Vec2(1.0, -std::sqrt(3.0)), 1e-15));
  EXPECT_EQ(rotate(Vec2(1.5, -2.5), Angle::zero()), Vec2(1.5, -2.5));
}

TEST(GeomVec2Test, NormalizedOrZeroGivesUnitVectorOrZero) {
  EXPECT_TRUE(vec_near(normalized_or_zero(Vec2(3.0, 4.0)), Vec2(0.6, 0.8), 1e-16));
  EXPECT_EQ(normalized_or_zero(Vec2(0.0, 0.0)), Vec2(0.0, 0.0));
  EXPECT_EQ(normalized_or_zero(Vec2(0.0, -1e-9)), Vec2(0.0, -1.0));
  // Squared norm underflows to zero: documented to give zero rather than a division by zero.
  EXPECT_EQ(normalized_or_zero(Vec2(1e-200, 0.0)), Vec2(0.0, 0.0));
}

TEST(GeomVec2Test, AngleOfMeasuresFromPlusX) {
  EXPECT_EQ(angle_of(Vec2(0.0, -2.0)).radians(), -std::numbers::pi / 2.0);
  EXPECT_EQ(angle_of(Vec2(-3.0, 0.0)).radians(), std::numbers::pi);
  EXPECT_EQ(angle_of(Vec2(0.0, 0.0)).radians(), 0.0);
}

TEST(GeomVec2Test, NaNPropagates) {
  const Vec2 nan(kNaN, 1.0);
  EXPECT_TRUE(std::isnan(perpendicular(nan).y()));
  EXPECT_TRUE(std::isnan(cross(nan, Vec2(1.0, 1.0))));
  EXPECT_TRUE(is_nan(rotate(nan, Angle::quarter_turn())));
  EXPECT_TRUE(is_nan(rotate(Vec2(1.0, 0.0), Angle::from_radians(kNaN))));
  EXPECT_TRUE(is_nan(normalized_or_zero(nan)));
  EXPECT_TRUE(std::isnan(angle_of(nan).radians()));
}

TEST(GeomVec2Test, PropertyRotatePreservesLengthAndTurnsByTheAngle) {
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> coordinate(-10.0, 10.0);
  std::uniform_real_distribution<double> radians(-4.0, 4.0);
  for (int i = 0; i < 1000; ++i) {
    const Vec2 v(coordinate(rng), coordinate(rng));
    const Angle turn = Angle::from_radians(radians(rng));
    const Vec2 rotated = rotate(v, turn);
    ASSERT_NEAR(rotated.norm(), v.norm(), 1e-13);
    ASSERT_TRUE(near(angle_diff(angle_of(rotated), angle_of(v)), turn, Angle::from_radians(1e-12)));
    ASSERT_NEAR(cross(v, rotated), v.squaredNorm() * std::sin(turn.radians()), 1e-12);
  }
}

}  // namespace
}  // namespace ssl::geom
