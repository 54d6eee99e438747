#include "libs/geometry/distance.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>

#include <gtest/gtest.h>

#include "libs/geometry/intersect.h"

namespace ssl::geom {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

Polygon l_shape() { return Polygon{{0.0, 0.0}, {2.0, 0.0}, {2.0, 1.0}, {1.0, 1.0}, {1.0, 2.0}, {0.0, 2.0}}; }

TEST(GeomDistanceTest, PointToPoint) {
  EXPECT_EQ(distance(Vec2(1.0, 1.0), Vec2(4.0, 5.0)), 5.0);
  EXPECT_EQ(squared_distance(Vec2(1.0, 1.0), Vec2(4.0, 5.0)), 25.0);
  EXPECT_EQ(distance(Vec2(1.0, 1.0), Vec2(1.0, 1.0)), 0.0);
}

TEST(GeomDistanceTest, PointToSegment) {
  const Segment s{{0.0, 0.0}, {4.0, 0.0}};
  EXPECT_EQ(distance(Vec2(2.0, 3.0), s), 3.0);    // perpendicular
  EXPECT_EQ(distance(Vec2(7.0, 4.0), s), 5.0);    // beyond the end
  EXPECT_EQ(distance(Vec2(-3.0, -4.0), s), 5.0);  // before the start
  EXPECT_EQ(distance(Vec2(1.5, 0.0), s), 0.0);    // on it
  EXPECT_EQ(squared_distance(Vec2(7.0, 4.0), s), 25.0);
  EXPECT_EQ(distance(s, Vec2(2.0, 3.0)), 3.0);                                // either order
  EXPECT_EQ(distance(Vec2(4.0, 5.0), Segment{{1.0, 1.0}, {1.0, 1.0}}), 5.0);  // zero length
}

TEST(GeomDistanceTest, PointToLineUnsignedAndSigned) {
  const Line line = Line::through({0.0, 0.0}, {2.0, 0.0});
  EXPECT_EQ(distance(Vec2(10.0, 3.0), line), 3.0);
  EXPECT_EQ(distance(line, Vec2(-10.0, -3.0)), 3.0);
  EXPECT_EQ(signed_distance(Vec2(10.0, 3.0), line), 3.0);    // left of +x
  EXPECT_EQ(signed_distance(Vec2(10.0, -3.0), line), -3.0);  // right of +x
  EXPECT_EQ(signed_distance(Vec2(10.0, 3.0), Line::through({2.0, 0.0}, {0.0, 0.0})), -3.0);
  EXPECT_NEAR(distance(Vec2(0.0, 2.0), Line::through({0.0, 0.0}, {1.0, 1.0})), std::sqrt(2.0), 1e-15);
  // Degenerate line: the distance to its point, unsigned.
  EXPECT_EQ(distance(Vec2(3.0, 4.0), Line{{0.0, 0.0}, {0.0, 0.0}}), 5.0);
  EXPECT_EQ(signed_distance(Vec2(3.0, 4.0), Line{{0.0, 0.0}, {0.0, 0.0}}), 5.0);
}

TEST(GeomDistanceTest, PointToRay) {
  const Ray ray{{0.0, 0.0}, {1.0, 0.0}};
  EXPECT_EQ(distance(Vec2(5.0, 2.0), ray), 2.0);
  EXPECT_EQ(distance(ray, Vec2(-3.0, 4.0)), 5.0);
}

TEST(GeomDistanceTest, PointToCircleIsZeroInsideAndSignedIsNegative) {
  const Circle c{{1.0, 1.0}, 1.0};
  EXPECT_EQ(distance(Vec2(4.0, 5.0), c), 4.0);
  EXPECT_EQ(distance(c, Vec2(4.0, 5.0)), 4.0);
  EXPECT_EQ(distance(Vec2(1.5, 1.0), c), 0.0);
  EXPECT_EQ(signed_distance(Vec2(1.5, 1.0), c), -0.5);
  EXPECT_EQ(signed_distance(Vec2(4.0, 5.0), c), 4.0);
  EXPECT_EQ(signed_distance(Vec2(2.0, 1.0), c), 0.0);
  EXPECT_EQ(distance(Vec2(4.0, 5.0), Circle{{1.0, 1.0}, 0.0}), 5.0);
}

TEST(GeomDistanceTest, PointToRectangle) {
  const Rectangle r({0.0, 0.0}, {2.0, 1.0});
  EXPECT_EQ(distance(Vec2(5.0, 5.0), r), 5.0);   // from the corner (2, 1)
  EXPECT_EQ(distance(Vec2(1.0, -2.0), r), 2.0);  // from the bottom edge
  EXPECT_EQ(distance(Vec2(1.0, 0.5), r), 0.0);
  EXPECT_EQ(distance(r, Vec2(5.0, 5.0)), 5.0);
  EXPECT_EQ(squared_distance(Vec2(5.0, 5.0), r), 25.0);
  EXPECT_EQ(signed_distance(Vec2(1.0, 0.75), r), -0.25);
  EXPECT_EQ(signed_distance(Vec2(1.0, -2.0), r), 2.0);
  EXPECT_EQ(signed_distance(Vec2(2.0, 0.5), r), 0.0);
}

TEST(GeomDistanceTest, PointToPolygon) {
  const Polygon l = l_shape();
  EXPECT_EQ(distance(Vec2(1.5, 1.5), l), 0.5);  // in the notch
  EXPECT_EQ(distance(Vec2(0.5, 0.5), l), 0.0);
  EXPECT_EQ(distance(l, Vec2(5.0, 0.5)), 3.0);
  EXPECT_EQ(signed_distance(Vec2(0.5, 1.75), l), -0.25);
  EXPECT_EQ(signed_distance(Vec2(1.5, 1.5), l), 0.5);
  EXPECT_TRUE(std::isnan(distance(Vec2(1.0, 1.0), Polygon())));
  EXPECT_TRUE(std::isnan(signed_distance(Vec2(1.0, 1.0), Polygon())));
}

TEST(GeomDistanceTest, PointToStadium) {
  const Stadium keep_out{{{0.0, 0.0}, {2.0, 0.0}}, 0.5};
  EXPECT_EQ(distance(Vec2(1.0, 2.0), keep_out), 1.5);
  EXPECT_EQ(distance(Vec2(5.0, 4.0), keep_out), 4.5);
  EXPECT_EQ(distance(Vec2(1.0, 0.2), keep_out), 0.0);
  EXPECT_EQ(distance(keep_out, Vec2(1.0, 2.0)), 1.5);
  EXPECT_NEAR(signed_distance(Vec2(1.0, 0.2), keep_out), -0.3, 1e-15);
}

TEST(GeomDistanceTest, SegmentToSegment) {
  const Segment a{{0.0, 0.0}, {1.0, 0.0}};
  EXPECT_EQ(distance(a, Segment{{0.5, -1.0}, {0.5, 1.0}}), 0.0);                     // crossing
  EXPECT_EQ(distance(a, Segment{{1.0, 0.0}, {1.0, 1.0}}), 0.0);                      // touching endpoints
  EXPECT_EQ(distance(a, Segment{{-1.0, 2.0}, {3.0, 2.0}}), 2.0);                     // parallel
  EXPECT_EQ(distance(a, Segment{{2.0, 0.0}, {3.0, 0.0}}), 1.0);                      // collinear, apart
  EXPECT_NEAR(distance(a, Segment{{2.0, 1.0}, {3.0, 5.0}}), std::sqrt(2.0), 1e-15);  // skew
  EXPECT_EQ(distance(a, Segment{{0.5, 3.0}, {0.5, 3.0}}), 3.0);                      // one is a point
  EXPECT_EQ(distance(Segment{{0.0, 0.0}, {0.0, 0.0}}, Segment{{3.0, 4.0}, {3.0, 4.0}}), 5.0);
}

TEST(GeomDistanceTest, NaNGivesNaN) {
  const Vec2 nan(kNaN, 0.0);
  EXPECT_TRUE(std::isnan(distance(nan, Vec2(0.0, 0.0))));
  EXPECT_TRUE(std::isnan(distance(nan, Segment{{0.0, 0.0}, {1.0, 0.0}})));
  EXPECT_TRUE(std::isnan(distance(nan, Line{{0.0, 0.0}, {1.0, 0.0}})));
  EXPECT_TRUE(std::isnan(distance(nan, Circle{{0.0, 0.0}, 1.0})));
  EXPECT_TRUE(std::isnan(distance(Vec2(5.0, 0.0), Circle{{0.0, 0.0}, kNaN})));
  EXPECT_TRUE(std::isnan(distance(nan, Rectangle({0.0, 0.0}, {1.0, 1.0}))));
  EXPECT_TRUE(std::isnan(distance(nan, l_shape())));
  EXPECT_TRUE(std::isnan(distance(nan, Stadium{{{0.0, 0.0}, {1.0, 0.0}}, 0.5})));
  EXPECT_TRUE(std::isnan(signed_distance(nan, Rectangle({0.0, 0.0}, {1.0, 1.0}))));
  EXPECT_TRUE(std::isnan(distance(Segment{{0.0, 0.0}, {1.0, 0.0}}, Segment{{5.0, 5.0}, {kNaN, 6.0}})));
  EXPECT_TRUE(std::isnan(distance(Segment{{kNaN, 0.0}, {1.0, 0.0}}, Segment{{5.0, 5.0}, {5.0, 6.0}})));
  EXPECT_TRUE(std::isnan(distance(Segment{{0.0, 0.0}, {kNaN, 0.0}}, Segment{{5.0, 5.0}, {5.0, 6.0}})));
}

TEST(GeomDistanceTest, PropertyPointToSegmentMatchesClosestPointAndBruteForce) {
  std::mt19937 rng(2024);
  std::uniform_real_distribution<double> coordinate(-5.0, 5.0);
  for (int i = 0; i < 2000; ++i) {
    const Segment s{{coordinate(rng), coordinate(rng)}, {coordinate(rng), coordinate(rng)}};
    const Vec2 p(coordinate(rng), coordinate(rng));
    const double d = distance(p, s);
    ASSERT_NEAR(d, distance(p, closest_point(s, p)), 1e-12);
    // No sampled point of the segment is nearer.
    for (int k = 0; k <= 20; ++k) ASSERT_LE(d, distance(p, s.at(k / 20.0)) + 1e-12);
    ASSERT_LE(d, std::min(distance(p, s.start), distance(p, s.end)) + 1e-12);
  }
}

TEST(GeomDistanceTest, PropertySegmentToSegmentIsSymmetricAndZeroExactlyWhenTheyMeet) {
  std::mt19937 rng(77);
  std::uniform_real_distribution<double> coordinate(-3.0, 3.0);
  for (int i = 0; i < 2000; ++i) {
    const Segment a{{coordinate(rng), coordinate(rng)}, {coordinate(rng), coordinate(rng)}};
    const Segment b{{coordinate(rng), coordinate(rng)}, {coordinate(rng), coordinate(rng)}};
    const double d = distance(a, b);
    ASSERT_EQ(d, distance(b, a));
    ASSERT_EQ(d == 0.0, intersects(a, b));
    for (int k = 0; k <= 10; ++k) {
      ASSERT_LE(d, distance(a.at(k / 10.0), b) + 1e-12);
      ASSERT_LE(d, distance(b.at(k / 10.0), a) + 1e-12);
    }
  }
}

}  // namespace
}  // namespace ssl::geom
