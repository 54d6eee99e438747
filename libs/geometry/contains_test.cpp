#include "libs/geometry/contains.h"

#include <cmath>
#include <limits>
#include <numbers>
#include <random>
#include <vector>

#include <gtest/gtest.h>

namespace ssl::geom {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

Polygon l_shape() { return Polygon{{0.0, 0.0}, {2.0, 0.0}, {2.0, 1.0}, {1.0, 1.0}, {1.0, 2.0}, {0.0, 2.0}}; }

TEST(GeomContainsTest, SegmentContainsPointsOnItIncludingEndpoints) {
  const Segment s{{0.0, 0.0}, {2.0, 1.0}};
  EXPECT_TRUE(contains(s, Vec2(1.0, 0.5)));
  EXPECT_TRUE(contains(s, Vec2(0.0, 0.0)));
  EXPECT_TRUE(contains(s, Vec2(2.0, 1.0)));
  EXPECT_FALSE(contains(s, Vec2(1.0, 0.5 + 1e-6)));
  EXPECT_FALSE(contains(s, Vec2(4.0, 2.0)));    // on the supporting line, beyond the end
  EXPECT_FALSE(contains(s, Vec2(-0.2, -0.1)));  // before the start
}

TEST(GeomContainsTest, SegmentToleratesRoundingOfComputedPoints) {
  const Segment s{{0.1, 0.2}, {0.7, 1.3}};
  for (double t : {0.0, 0.1, 0.3, 0.77, 1.0}) EXPECT_TRUE(contains(s, s.at(t))) << t;
  EXPECT_TRUE(contains(s.reversed(), s.at(0.3)));
}

TEST(GeomContainsTest, ZeroLengthSegmentContainsOnlyItsPoint) {
  const Segment point{{1.0, 1.0}, {1.0, 1.0}};
  EXPECT_TRUE(contains(point, Vec2(1.0, 1.0)));
  EXPECT_FALSE(contains(point, Vec2(1.0, 1.0 + 1e-12)));
}

TEST(GeomContainsTest, CircleIsClosed) {
  const Circle c{{1.0, 1.0}, 2.0};
  EXPECT_TRUE(contains(c, Vec2(1.0, 1.0)));
  EXPECT_TRUE(contains(c, Vec2(2.0, 2.0)));
  EXPECT_TRUE(contains(c, Vec2(3.0, 1.0)));  // on the boundary
  EXPECT_FALSE(contains(c, Vec2(3.0 + 1e-9, 1.0)));
  EXPECT_TRUE(contains(Circle{{1.0, 1.0}, 0.0}, Vec2(1.0, 1.0)));
  EXPECT_FALSE(contains(Circle{{1.0, 1.0}, 0.0}, Vec2(1.0, 1.0 + 1e-12)));
}

TEST(GeomContainsTest, RectangleIsClosed) {
  const Rectangle r({-1.0, -1.0}, {1.0, 2.0});
  EXPECT_TRUE(contains(r, Vec2(0.0, 0.0)));
  EXPECT_TRUE(contains(r, Vec2(1.0, 2.0)));
  EXPECT_TRUE(contains(r, Vec2(-1.0, 0.5)));
  EXPECT_FALSE(contains(r, Vec2(1.5, 0.0)));
  EXPECT_FALSE(contains(r, Vec2(0.0, -1.5)));
  EXPECT_TRUE(contains(Rectangle({0.0, 0.0}, {0.0, 1.0}), Vec2(0.0, 0.5)));  // zero width
}

TEST(GeomContainsTest, PolygonInsideOutsideAndBoundary) {
  const Polygon l = l_shape();
  EXPECT_TRUE(contains(l, Vec2(0.5, 0.5)));
  EXPECT_TRUE(contains(l, Vec2(0.5, 1.5)));
  EXPECT_TRUE(contains(l, Vec2(1.5, 0.5)));
  EXPECT_FALSE(contains(l, Vec2(1.5, 1.5)));  // the notch
  EXPECT_FALSE(contains(l, Vec2(-0.5, 0.5)));
  EXPECT_FALSE(contains(l, Vec2(3.0, 0.5)));
  EXPECT_TRUE(contains(l, Vec2(1.5, 1.0)));  // on an edge
  EXPECT_TRUE(contains(l, Vec2(1.0, 1.0)));  // on the reflex vertex
  EXPECT_TRUE(contains(l, Vec2(2.0, 0.0)));  // on a convex vertex
}

TEST(GeomContainsTest, PolygonOrientationDoesNotMatter) {
  const Polygon clockwise{{0.0, 2.0}, {1.0, 2.0}, {1.0, 1.0}, {2.0, 1.0}, {2.0, 0.0}, {0.0, 0.0}};
  EXPECT_TRUE(contains(clockwise, Vec2(0.5, 1.5)));
  EXPECT_FALSE(contains(clockwise, Vec2(1.5, 1.5)));
}

TEST(GeomContainsTest, PolygonRayThroughVerticesCountsOnce) {
  // A diamond: the horizontal ray from p passes exactly through the vertices (0, 1) and (2, 1).
  const Polygon diamond{{1.0, 0.0}, {2.0, 1.0}, {1.0, 2.0}, {0.0, 1.0}};
  EXPECT_TRUE(contains(diamond, Vec2(0.5, 1.0)));
  EXPECT_TRUE(contains(diamond, Vec2(1.0, 1.0)));
  EXPECT_FALSE(contains(diamond, Vec2(-0.5, 1.0)));
  EXPECT_FALSE(contains(diamond, Vec2(2.5, 1.0)));
  // Level with a horizontal edge.
  const Polygon triangle{{0.0, 0.0}, {2.0, 0.0}, {1.0, 2.0}};
  EXPECT_TRUE(contains(triangle, Vec2(0.5, 0.0)));
  EXPECT_FALSE(contains(triangle, Vec2(-1.0, 0.0)));
  EXPECT_FALSE(contains(triangle, Vec2(3.0, 0.0)));
}

TEST(GeomContainsTest, PolygonUsesNonzeroWinding) {
  // The pentagram's centre is wound twice: inside under nonzero winding (outside under even-odd).
  std::vector<Vec2> star;
  for (int k = 0; k < 5; ++k) {
    const double a = std::numbers::pi / 2.0 + k * 4.0 * std::numbers::pi / 5.0;
    star.emplace_back(std::cos(a), std::sin(a));
  }
  EXPECT_TRUE(contains(Polygon(star), Vec2(0.0, 0.0)));
  EXPECT_TRUE(contains(Polygon(star), Vec2(0.0, 0.9)));    // in the top arm: wound once
  EXPECT_FALSE(contains(Polygon(star), Vec2(0.0, -0.6)));  // between the two lower arms
}

TEST(GeomContainsTest, DegeneratePolygons) {
  EXPECT_FALSE(contains(Polygon(), Vec2(0.0, 0.0)));
  EXPECT_TRUE(contains(Polygon{{1.0, 1.0}}, Vec2(1.0, 1.0)));
  EXPECT_FALSE(contains(Polygon{{1.0, 1.0}}, Vec2(1.0, 2.0)));
  EXPECT_TRUE(contains(Polygon{{0.0, 0.0}, {2.0, 0.0}}, Vec2(1.0, 0.0)));
  EXPECT_FALSE(contains(Polygon{{0.0, 0.0}, {2.0, 0.0}}, Vec2(1.0, 0.1)));
}

TEST(GeomContainsTest, StadiumIsClosed) {
  const Stadium keep_out{{{0.0, 0.0}, {2.0, 0.0}}, 0.5};
  EXPECT_TRUE(contains(keep_out, Vec2(1.0, 0.4)));
  EXPECT_TRUE(contains(keep_out, Vec2(1.0, -0.5)));
  EXPECT_TRUE(contains(keep_out, Vec2(2.3, 0.4)));  // in the end cap, on its boundary
  EXPECT_TRUE(contains(keep_out, Vec2(-0.4, 0.0)));
  EXPECT_FALSE(contains(keep_out, Vec2(2.4, 0.4)));  // outside the cap, inside its bounding box
  EXPECT_FALSE(contains(keep_out, Vec2(1.0, 0.6)));
  EXPECT_TRUE(contains(Stadium{{{1.0, 1.0}, {1.0, 1.0}}, 1.0}, Vec2(1.0, 2.0)));
}

TEST(GeomContainsTest, NaNIsNeverContained) {
  const Vec2 nan(kNaN, 0.0);
  EXPECT_FALSE(contains(Segment{{0.0, 0.0}, {1.0, 0.0}}, nan));
  EXPECT_FALSE(contains(Segment{{0.0, 0.0}, {kNaN, 0.0}}, Vec2(0.0, 0.0)));
  EXPECT_FALSE(contains(Circle{{0.0, 0.0}, 1.0}, nan));
  EXPECT_FALSE(contains(Circle{{0.0, 0.0}, kNaN}, Vec2(0.0, 0.0)));
  EXPECT_FALSE(contains(Rectangle({0.0, 0.0}, {1.0, 1.0}), nan));
  EXPECT_FALSE(contains(l_shape(), nan));
  EXPECT_FALSE(contains(Polygon{{0.0, 0.0}, {2.0, 0.0}, {kNaN, 2.0}}, Vec2(1.0, 0.5)));
  EXPECT_FALSE(contains(Stadium{{{0.0, 0.0}, {1.0, 0.0}}, 1.0}, nan));
}

TEST(GeomContainsTest, PropertyPolygonAgreesWithRectangleAndCircle) {
  std::mt19937 rng(99);
  std::uniform_real_distribution<double> coordinate(-3.0, 3.0);
  const Rectangle box({-1.0, -0.5}, {2.0, 1.5});
  const Polygon box_polygon = Polygon::from_rectangle(box);
  // A 64-gon inscribed in the unit circle: inside it implies inside the circle.
  std::vector<Vec2> ring;
  for (int k = 0; k < 64; ++k)
    ring.emplace_back(std::cos(k * std::numbers::pi / 32), std::sin(k * std::numbers::pi / 32));
  const Polygon inscribed(ring);
  for (int i = 0; i < 5000; ++i) {
    const Vec2 p(coordinate(rng), coordinate(rng));
    ASSERT_EQ(contains(box_polygon, p), contains(box, p)) << p.transpose();
    if (contains(inscribed, p)) {
      ASSERT_TRUE(contains(Circle{{0.0, 0.0}, 1.0}, p)) << p.transpose();
    }
    if (p.norm() < std::cos(std::numbers::pi / 64)) {
      ASSERT_TRUE(contains(inscribed, p)) << p.transpose();
    }
  }
}

}  // namespace
}  // namespace ssl::geom
