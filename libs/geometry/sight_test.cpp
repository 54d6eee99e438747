#include "libs/geometry/sight.h"

#include <cmath>
#include <limits>
#include <numbers>
#include <random>

#include <gtest/gtest.h>

#include "libs/geometry/distance.h"
#include "libs/geometry/test_util.h"

namespace ssl::geom {
namespace {

using testing::vec_near;

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr double kPi = std::numbers::pi;

TEST(GeomSightTest, TangentPointsFromOutside) {
  // From (2, 0) to the unit circle: the tangents touch at x = 1/2, y = -+sqrt(3)/2.
  const auto t = tangent_points(Vec2(2.0, 0.0), Circle{{0.0, 0.0}, 1.0});
  ASSERT_TRUE(t);
  // Looking from (2, 0) towards the centre (along -x), left is -y.
  EXPECT_TRUE(vec_near(t->left, Vec2(0.5, -std::sqrt(3.0) / 2.0), 1e-15));
  EXPECT_TRUE(vec_near(t->right, Vec2(0.5, std::sqrt(3.0) / 2.0), 1e-15));
}

TEST(GeomSightTest, TangentPointsOfAnOffsetCircle) {
  // From the origin to the circle at (0, 5) with radius 3: a 3-4-5 triangle, touching at (-+2.4, 3.2).
  const auto t = tangent_points(Vec2(0.0, 0.0), Circle{{0.0, 5.0}, 3.0});
  ASSERT_TRUE(t);
  EXPECT_TRUE(vec_near(t->left, Vec2(-2.4, 3.2), 1e-15));
  EXPECT_TRUE(vec_near(t->right, Vec2(2.4, 3.2), 1e-15));
}

TEST(GeomSightTest, CircleHidesTheIntervalFromRightToLeft) {
  const Vec2 from(2.0, 0.0);
  const auto t = tangent_points(from, Circle{{0.0, 0.0}, 1.0});
  ASSERT_TRUE(t);
  const Angle hidden = angle_diff(angle_of(t->left - from), angle_of(t->right - from));
  EXPECT_NEAR(hidden.degrees(), 60.0, 1e-12);  // 2 * asin(r / d) = 2 * 30 degrees
}

TEST(GeomSightTest, TangentPointsOnTheBoundaryAreTheViewpoint) {
  const auto t = tangent_points(Vec2(0.0, 1.0), Circle{{0.0, 0.0}, 1.0});
  ASSERT_TRUE(t);
  EXPECT_EQ(t->left, Vec2(0.0, 1.0));
  EXPECT_EQ(t->right, Vec2(0.0, 1.0));
  // A viewpoint computed on the circle (with rounding) still counts as on it.
  const Circle c{{0.3, -0.2}, 0.7};
  const Vec2 on = c.center + c.radius * Angle::from_degrees(37.0).to_unit_vector();
  const auto rounded = tangent_points(on, c);
  ASSERT_TRUE(rounded);
  EXPECT_TRUE(vec_near(rounded->left, on, 1e-7));
  EXPECT_TRUE(vec_near(rounded->right, on, 1e-7));
}

TEST(GeomSightTest, NoTangentsFromInside) {
  EXPECT_FALSE(tangent_points(Vec2(0.5, 0.0), Circle{{0.0, 0.0}, 1.0}));
  EXPECT_FALSE(tangent_points(Vec2(0.0, 0.0), Circle{{0.0, 0.0}, 1.0}));
}

TEST(GeomSightTest, ZeroRadiusCircleIsItsCentre) {
  auto t = tangent_points(Vec2(3.0, 4.0), Circle{{1.0, 1.0}, 0.0});
  ASSERT_TRUE(t);
  EXPECT_EQ(t->left, Vec2(1.0, 1.0));
  EXPECT_EQ(t->right, Vec2(1.0, 1.0));
  t = tangent_points(Vec2(1.0, 1.0), Circle{{1.0, 1.0}, 0.0});
  ASSERT_TRUE(t);
  EXPECT_EQ(t->left, Vec2(1.0, 1.0));
}

TEST(GeomSightTest, TangentPointsOfNaNAreNullopt) {
  EXPECT_FALSE(tangent_points(Vec2(kNaN, 0.0), Circle{{0.0, 0.0}, 1.0}));
  EXPECT_FALSE(tangent_points(Vec2(5.0, 0.0), Circle{{0.0, 0.0}, kNaN}));
}

TEST(GeomSightTest, PropertyTangentPointsAreOnTheCircleAndPerpendicular) {
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> coordinate(-5.0, 5.0);
  std::uniform_real_distribution<double> radius(0.01, 1.0);
  int checked = 0;
  for (int i = 0; i < 3000; ++i) {
    const Vec2 from(coordinate(rng), coordinate(rng));
    const Circle c{{coordinate(rng), coordinate(rng)}, radius(rng)};
    const auto t = tangent_points(from, c);
    ASSERT_EQ(t.has_value(), distance(from, c.center) >= c.radius);
    if (!t) continue;
    ++checked;
    for (const Vec2& touch : {t->left, t->right}) {
      ASSERT_NEAR(distance(touch, c.center), c.radius, 1e-12);
      ASSERT_NEAR((touch - c.center).dot(touch - from), 0.0, 1e-11);  // radius is perpendicular to sight
    }
    // left is counter-clockwise of right, by 2 asin(r / d).
    const Angle hidden = angle_diff(angle_of(t->left - from), angle_of(t->right - from));
    ASSERT_NEAR(hidden.radians(), 2.0 * std::asin(c.radius / distance(from, c.center)), 1e-9);
  }
  EXPECT_GT(checked, 2000);
}

TEST(GeomSightTest, SubtendedAngleOfAGoal) {
  // A 1 m goal mouth seen from 1 m in front of its centre: 2 atan(0.5) = 53.13 degrees.
  const Segment goal{{4.5, -0.5}, {4.5, 0.5}};
  EXPECT_NEAR(subtended_angle(Vec2(3.5, 0.0), goal).radians(), 2.0 * std::atan(0.5), 1e-15);
  EXPECT_NEAR(subtended_angle(Vec2(3.5, 0.0), goal.reversed()).radians(), 2.0 * std::atan(0.5), 1e-15);
  EXPECT_NEAR(subtended_angle(Vec2(0.0, 0.0), Segment{{1.0, -1.0}, {1.0, 1.0}}).degrees(), 90.0, 1e-12);
  // From the side, beside the left post: one endpoint straight ahead, the other 1 m further along.
  EXPECT_NEAR(subtended_angle(Vec2(3.5, 0.5), goal).radians(), kPi / 4.0, 1e-15);
}

TEST(GeomSightTest, SubtendedAngleDegenerateCases) {
  const Segment goal{{4.5, -0.5}, {4.5, 0.5}};
  EXPECT_EQ(subtended_angle(Vec2(4.5, 0.0), goal).radians(), kPi);  // on the segment
  EXPECT_EQ(subtended_angle(Vec2(4.5, 0.5), goal).radians(), 0.0);  // at an endpoint
  EXPECT_EQ(subtended_angle(Vec2(4.5, 3.0), goal).radians(), 0.0);  // on its line, outside
  EXPECT_EQ(subtended_angle(Vec2(0.0, 0.0), Segment{{1.0, 1.0}, {1.0, 1.0}}).radians(), 0.0);
  EXPECT_TRUE(std::isnan(subtended_angle(Vec2(kNaN, 0.0), goal).radians()));
}

}  // namespace
}  // namespace ssl::geom
