// Accessors and factories of the plain shapes: Segment, Line, Ray, Circle, Rectangle, Stadium.
#include <cmath>
#include <numbers>

#include <gtest/gtest.h>

#include "libs/geometry/circle.h"
#include "libs/geometry/line.h"
#include "libs/geometry/ray.h"
#include "libs/geometry/rectangle.h"
#include "libs/geometry/segment.h"
#include "libs/geometry/stadium.h"
#include "libs/geometry/test_util.h"

namespace ssl::geom {
namespace {

using testing::vec_near;

TEST(GeomShapesTest, SegmentAccessors) {
  const Segment s{{1.0, 2.0}, {4.0, 6.0}};
  EXPECT_EQ(s.direction(), Vec2(3.0, 4.0));
  EXPECT_EQ(s.length(), 5.0);
  EXPECT_EQ(s.squared_length(), 25.0);
  EXPECT_EQ(s.midpoint(), Vec2(2.5, 4.0));
  EXPECT_EQ(s.at(0.0), s.start);
  EXPECT_EQ(s.at(1.0), s.end);
  EXPECT_EQ(s.at(2.0), Vec2(7.0, 10.0));
  EXPECT_EQ(s.reversed(), (Segment{{4.0, 6.0}, {1.0, 2.0}}));
  EXPECT_NE(s, s.reversed());
}

TEST(GeomShapesTest, ZeroLengthSegmentHasZeroLength) {
  const Segment point{{1.0, 1.0}, {1.0, 1.0}};
  EXPECT_EQ(point.length(), 0.0);
  EXPECT_EQ(point.midpoint(), Vec2(1.0, 1.0));
}

TEST(GeomShapesTest, LineFactoriesFixPointAndDirection) {
  const Line through = Line::through({1.0, 1.0}, {3.0, 2.0});
  EXPECT_EQ(through.point, Vec2(1.0, 1.0));
  EXPECT_EQ(through.direction, Vec2(2.0, 1.0));
  EXPECT_EQ(through.at(1.0), Vec2(3.0, 2.0));
  EXPECT_EQ(through.at(-1.0), Vec2(-1.0, 0.0));
  EXPECT_EQ(Line::containing(Segment{{1.0, 1.0}, {3.0, 2.0}}), through);
  const Line along = Line::from_point_and_direction({0.0, 5.0}, {0.0, -1.0});
  EXPECT_EQ(along.at(5.0), Vec2(0.0, 0.0));
}

TEST(GeomShapesTest, RayFromAngleHasUnitDirection) {
  const Ray ray = Ray::from_angle({1.0, 1.0}, Angle::quarter_turn());
  EXPECT_EQ(ray.origin, Vec2(1.0, 1.0));
  EXPECT_TRUE(vec_near(ray.direction, Vec2(0.0, 1.0), 1e-16));
  EXPECT_TRUE(vec_near(ray.at(2.0), Vec2(1.0, 3.0), 1e-15));
}

TEST(GeomShapesTest, CircleArea) {
  EXPECT_DOUBLE_EQ((Circle{{5.0, 5.0}, 2.0}).area(), 4.0 * std::numbers::pi);
  EXPECT_EQ((Circle{{5.0, 5.0}, 0.0}).area(), 0.0);
}

TEST(GeomShapesTest, RectangleSortsItsCorners) {
  const Rectangle r({3.0, -1.0}, {1.0, 2.0});
  EXPECT_EQ(r.min(), Vec2(1.0, -1.0));
  EXPECT_EQ(r.max(), Vec2(3.0, 2.0));
  EXPECT_EQ(r, Rectangle({1.0, -1.0}, {3.0, 2.0}));
}

TEST(GeomShapesTest, RectangleAccessors) {
  const Rectangle r({0.0, 0.0}, {4.0, 2.0});
  EXPECT_EQ(r.center(), Vec2(2.0, 1.0));
  EXPECT_EQ(r.width(), 4.0);
  EXPECT_EQ(r.height(), 2.0);
  EXPECT_EQ(r.area(), 8.0);
  const auto corners = r.corners();
  EXPECT_EQ(corners[0], Vec2(0.0, 0.0));
  EXPECT_EQ(corners[1], Vec2(4.0, 0.0));
  EXPECT_EQ(corners[2], Vec2(4.0, 2.0));
  EXPECT_EQ(corners[3], Vec2(0.0, 2.0));
}

TEST(GeomShapesTest, RectangleFromCenter) {
  const Rectangle field = Rectangle::from_center({0.0, 0.0}, 12.0, 9.0);
  EXPECT_EQ(field.min(), Vec2(-6.0, -4.5));
  EXPECT_EQ(field.max(), Vec2(6.0, 4.5));
  EXPECT_EQ(Rectangle::from_center({1.0, 1.0}, -2.0, 2.0), Rectangle::from_center({1.0, 1.0}, 2.0, 2.0));
}

TEST(GeomShapesTest, RectangleContainsIsClosed) {
  const Rectangle r({0.0, 0.0}, {2.0, 1.0});
  EXPECT_TRUE(r.contains({1.0, 0.5}));
  EXPECT_TRUE(r.contains({0.0, 0.0}));
  EXPECT_TRUE(r.contains({2.0, 0.3}));
  EXPECT_FALSE(r.contains({2.0 + 1e-12, 0.3}));
  EXPECT_FALSE(r.contains({1.0, -1e-12}));
}

TEST(GeomShapesTest, RectangleExpandedGrowsAndShrinksAboutItsCenter) {
  const Rectangle r({0.0, 0.0}, {4.0, 2.0});
  EXPECT_EQ(r.expanded(0.5), Rectangle({-0.5, -0.5}, {4.5, 2.5}));
  EXPECT_EQ(r.expanded(-0.5), Rectangle({0.5, 0.5}, {3.5, 1.5}));
  // Shrinking past the centre stops at the centre line.
  EXPECT_EQ(r.expanded(-1.5), Rectangle({1.5, 1.0}, {2.5, 1.0}));
}

TEST(GeomShapesTest, StadiumArea) {
  const Stadium keep_out{{{0.0, 0.0}, {2.0, 0.0}}, 0.5};
  EXPECT_DOUBLE_EQ(keep_out.area(), 2.0 * 0.5 * 2.0 + std::numbers::pi * 0.25);
  const Stadium disc{{{1.0, 1.0}, {1.0, 1.0}}, 1.0};
  EXPECT_DOUBLE_EQ(disc.area(), std::numbers::pi);
}

}  // namespace
}  // namespace ssl::geom
