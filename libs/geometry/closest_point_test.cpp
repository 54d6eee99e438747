#include "libs/geometry/closest_point.h"

#include <cmath>
#include <limits>
#include <random>

#include <gtest/gtest.h>

#include "libs/geometry/distance.h"
#include "libs/geometry/test_util.h"

namespace ssl::geom {
namespace {

using testing::is_nan;
using testing::vec_near;

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

Polygon l_shape() { return Polygon{{0.0, 0.0}, {2.0, 0.0}, {2.0, 1.0}, {1.0, 1.0}, {1.0, 2.0}, {0.0, 2.0}}; }

TEST(GeomClosestPointTest, SegmentReturnsFootOrEndpoint) {
  const Segment s{{0.0, 0.0}, {4.0, 0.0}};
  EXPECT_EQ(closest_point(s, Vec2(1.0, 3.0)), Vec2(1.0, 0.0));
  EXPECT_EQ(closest_point(s, Vec2(6.0, 3.0)), Vec2(4.0, 0.0));
  EXPECT_EQ(closest_point(s, Vec2(-1.0, -1.0)), Vec2(0.0, 0.0));
  EXPECT_EQ(closest_point(s, Vec2(2.0, 0.0)), Vec2(2.0, 0.0));
  EXPECT_EQ(closest_point(Segment{{1.0, 1.0}, {1.0, 1.0}}, Vec2(3.0, 3.0)), Vec2(1.0, 1.0));
}

TEST(GeomClosestPointTest, LineReturnsPerpendicularFoot) {
  const Line line = Line::through({0.0, 0.0}, {1.0, 1.0});
  EXPECT_TRUE(vec_near(closest_point(line, Vec2(2.0, 0.0)), Vec2(1.0, 1.0)));
  EXPECT_TRUE(vec_near(closest_point(line, Vec2(-3.0, -1.0)), Vec2(-2.0, -2.0)));
}

TEST(GeomClosestPointTest, RayReturnsOriginBehindIt) {
  const Ray ray{{1.0, 0.0}, {1.0, 0.0}};
  EXPECT_EQ(closest_point(ray, Vec2(5.0, 2.0)), Vec2(5.0, 0.0));
  EXPECT_EQ(closest_point(ray, Vec2(-5.0, 2.0)), Vec2(1.0, 0.0));
}

TEST(GeomClosestPointTest, CircleReturnsBoundaryPointFromOutsideAndInside) {
  const Circle c{{0.0, 0.0}, 1.0};
  EXPECT_TRUE(vec_near(closest_point(c, Vec2(3.0, 4.0)), Vec2(0.6, 0.8)));
  EXPECT_TRUE(vec_near(closest_point(c, Vec2(0.3, 0.4)), Vec2(0.6, 0.8)));
  EXPECT_TRUE(vec_near(closest_point(Circle{{1.0, 1.0}, 2.0}, Vec2(1.0, -5.0)), Vec2(1.0, -1.0)));
}

TEST(GeomClosestPointTest, CircleCentreAndZeroRadiusAreDefined) {
  EXPECT_EQ(closest_point(Circle{{1.0, 2.0}, 0.5}, Vec2(1.0, 2.0)), Vec2(1.5, 2.0));
  EXPECT_EQ(closest_point(Circle{{1.0, 2.0}, 0.0}, Vec2(7.0, 7.0)), Vec2(1.0, 2.0));
}

TEST(GeomClosestPointTest, RectangleOutsideClampsToTheBoundary) {
  const Rectangle r({0.0, 0.0}, {2.0, 1.0});
  EXPECT_EQ(closest_point(r, Vec2(3.0, 3.0)), Vec2(2.0, 1.0));
  EXPECT_EQ(closest_point(r, Vec2(1.0, -1.0)), Vec2(1.0, 0.0));
  EXPECT_EQ(closest_point(r, Vec2(-5.0, 0.5)), Vec2(0.0, 0.5));
}

TEST(GeomClosestPointTest, RectangleInsideGoesToTheNearestEdge) {
  const Rectangle r({0.0, 0.0}, {2.0, 1.0});
  EXPECT_EQ(closest_point(r, Vec2(1.8, 0.5)), Vec2(2.0, 0.5));
  EXPECT_EQ(closest_point(r, Vec2(1.0, 0.1)), Vec2(1.0, 0.0));
  EXPECT_EQ(closest_point(r, Vec2(1.0, 0.75)), Vec2(1.0, 1.0));
  EXPECT_EQ(closest_point(r, Vec2(0.2, 0.5)), Vec2(0.0, 0.5));
  EXPECT_EQ(closest_point(r, Vec2(2.0, 0.5)), Vec2(2.0, 0.5));  // on the boundary: itself
}

TEST(GeomClosestPointTest, PolygonReturnsNearestBoundaryPoint) {
  const Polygon l = l_shape();
  EXPECT_TRUE(vec_near(closest_point(l, Vec2(1.6, 1.5)), Vec2(1.6, 1.0)));  // in the notch, outside
  EXPECT_TRUE(vec_near(closest_point(l, Vec2(0.5, 1.8)), Vec2(0.5, 2.0)));  // inside
  EXPECT_TRUE(vec_near(closest_point(l, Vec2(3.0, 2.5)), Vec2(2.0, 1.0)));  // nearer (2, 1) than (1, 2)
  EXPECT_TRUE(vec_near(closest_point(l, Vec2(-1.0, -2.0)), Vec2(0.0, 0.0)));
}

TEST(GeomClosestPointTest, PolygonOfEmptyOrNaNIsNaN) {
  EXPECT_TRUE(is_nan(closest_point(Polygon(), Vec2(1.0, 1.0))));
  EXPECT_TRUE(is_nan(closest_point(l_shape(), Vec2(kNaN, 1.0))));
  EXPECT_TRUE(is_nan(closest_point(Polygon{{0.0, 0.0}, {1.0, 0.0}, {kNaN, 1.0}}, Vec2(5.0, 5.0))));
}

TEST(GeomClosestPointTest, StadiumReturnsBoundaryPoint) {
  const Stadium keep_out{{{0.0, 0.0}, {2.0, 0.0}}, 0.5};
  EXPECT_TRUE(vec_near(closest_point(keep_out, Vec2(1.0, 3.0)), Vec2(1.0, 0.5)));
  EXPECT_TRUE(vec_near(closest_point(keep_out, Vec2(1.0, -0.2)), Vec2(1.0, -0.5)));
  EXPECT_TRUE(vec_near(closest_point(keep_out, Vec2(5.0, 4.0)), Vec2(2.3, 0.4)));
  EXPECT_TRUE(vec_near(closest_point(keep_out, Vec2(-0.1, 0.0)), Vec2(-0.5, 0.0)));
  // On the spine: the left side (counter-clockwise of start -> end).
  EXPECT_TRUE(vec_near(closest_point(keep_out, Vec2(1.0, 0.0)), Vec2(1.0, 0.5)));
  EXPECT_TRUE(
      vec_near(closest_point(Stadium{{{1.0, 1.0}, {1.0, 1.0}}, 2.0}, Vec2(1.0, 1.0)), Vec2(3.0, 1.0)));
}

TEST(GeomClosestPointTest, NaNGivesNaN) {
  EXPECT_TRUE(is_nan(closest_point(Circle{{0.0, 0.0}, 1.0}, Vec2(kNaN, 0.0))));
  EXPECT_TRUE(is_nan(closest_point(Rectangle({0.0, 0.0}, {1.0, 1.0}), Vec2(kNaN, kNaN))));
  EXPECT_TRUE(std::isnan(closest_point(Rectangle({0.0, 0.0}, {1.0, 1.0}), Vec2(kNaN, 5.0)).x()));
  EXPECT_TRUE(is_nan(closest_point(Stadium{{{0.0, 0.0}, {1.0, 0.0}}, 1.0}, Vec2(kNaN, 0.0))));
}

TEST(GeomClosestPointTest, PropertyDistanceToClosestPointIsTheDistance) {
  std::mt19937 rng(1234);
  std::uniform_real_distribution<double> coordinate(-5.0, 5.0);
  std::uniform_real_distribution<double> radius(0.0, 2.0);
  const Polygon l = l_shape();
  for (int i = 0; i < 2000; ++i) {
    const Vec2 p(coordinate(rng), coordinate(rng));
    const Segment s{{coordinate(rng), coordinate(rng)}, {coordinate(rng), coordinate(rng)}};
    ASSERT_NEAR(distance(p, s), distance(p, closest_point(s, p)), 1e-12);
    const Circle c{{coordinate(rng), coordinate(rng)}, radius(rng)};
    ASSERT_NEAR(distance(closest_point(c, p), c.center), c.radius, 1e-12);
    ASSERT_NEAR(std::abs(signed_distance(p, c)), distance(p, closest_point(c, p)), 1e-12);
    const Rectangle r({coordinate(rng), coordinate(rng)}, {coordinate(rng), coordinate(rng)});
    ASSERT_NEAR(std::abs(signed_distance(p, r)), distance(p, closest_point(r, p)), 1e-12);
    ASSERT_NEAR(std::abs(signed_distance(p, l)), distance(p, closest_point(l, p)), 1e-12);
    const Stadium st{s, radius(rng)};
    ASSERT_NEAR(std::abs(signed_distance(p, st)), distance(p, closest_point(st, p)), 1e-12);
  }
}

}  // namespace
}  // namespace ssl::geom
