#include "libs/geometry/intersect.h"

#include <cmath>
#include <limits>
#include <numbers>
#include <optional>
#include <random>

#include <gtest/gtest.h>

#include "libs/geometry/test_util.h"

namespace ssl::geom {
namespace {

using testing::vec_near;

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

Polygon l_shape() { return Polygon{{0.0, 0.0}, {2.0, 0.0}, {2.0, 1.0}, {1.0, 1.0}, {1.0, 2.0}, {0.0, 2.0}}; }

// ---------------------------------------------------------------------------------------------------------
// Segment-segment

TEST(GeomIntersectTest, CrossingSegmentsMeetInOnePoint) {
  const auto hit = intersection(Segment{{0.0, 0.0}, {2.0, 2.0}}, Segment{{0.0, 2.0}, {2.0, 0.0}});
  ASSERT_TRUE(hit);
  EXPECT_TRUE(vec_near(*hit, Vec2(1.0, 1.0)));
  const auto skew = intersection(Segment{{0.0, 0.0}, {4.0, 2.0}}, Segment{{1.0, 3.0}, {3.0, -1.0}});
  ASSERT_TRUE(skew);  // y = x / 2 meets y = -2x + 5 at (2, 1)
  EXPECT_TRUE(vec_near(*skew, Vec2(2.0, 1.0)));
}

TEST(GeomIntersectTest, SegmentsTouchingAtAnEndpointMeet) {
  const auto t_junction = intersection(Segment{{0.0, 0.0}, {1.0, 0.0}}, Segment{{1.0, -1.0}, {1.0, 1.0}});
  ASSERT_TRUE(t_junction);
  EXPECT_TRUE(vec_near(*t_junction, Vec2(1.0, 0.0)));
  const auto corner = intersection(Segment{{0.0, 0.0}, {1.0, 0.0}}, Segment{{1.0, 0.0}, {1.0, 1.0}});
  ASSERT_TRUE(corner);
  EXPECT_TRUE(vec_near(*corner, Vec2(1.0, 0.0)));
}

TEST(GeomIntersectTest, EndpointTouchingSurvivesRounding) {
  // b starts at a point computed on a (not representable exactly); they must still meet there.
  const Segment a{{0.1, 0.2}, {0.7, 1.3}};
  for (double t : {0.0, 0.3, 0.9, 1.0}) {
    const Segment b{a.at(t), {5.0, -3.0}};
    const auto hit = intersection(a, b);
    ASSERT_TRUE(hit) << t;
    EXPECT_TRUE(vec_near(*hit, a.at(t), 1e-12)) << t;
    EXPECT_TRUE(intersects(b, a)) << t;
  }
}

TEST(GeomIntersectTest, SeparateSegmentsDoNotMeet) {
  const Segment a{{0.0, 0.0}, {1.0, 0.0}};
  EXPECT_FALSE(intersection(a, Segment{{0.0, 1.0}, {1.0, 1.0}}));   // parallel
  EXPECT_FALSE(intersection(a, Segment{{2.0, -1.0}, {2.0, 1.0}}));  // lines cross beyond a's end
  EXPECT_FALSE(intersection(a, Segment{{0.5, 0.1}, {0.5, 1.0}}));   // lines cross before b's start
  EXPECT_FALSE(intersection(a, Segment{{1.0 + 1e-9, -1.0}, {1.0 + 1e-9, 1.0}}));  // just misses
  EXPECT_FALSE(intersects(a, Segment{{2.0, 0.0}, {3.0, 0.0}}));                   // collinear, apart
}

TEST(GeomIntersectTest, CollinearOverlapReturnsTheOverlapEndNearestFirstStart) {
  const Segment a{{0.0, 0.0}, {4.0, 0.0}};
  auto hit = intersection(a, Segment{{1.0, 0.0}, {6.0, 0.0}});
  ASSERT_TRUE(hit);
  EXPECT_TRUE(vec_near(*hit, Vec2(1.0, 0.0)));
  hit = intersection(a, Segment{{6.0, 0.0}, {1.0, 0.0}});  // b's direction does not matter
  ASSERT_TRUE(hit);
  EXPECT_TRUE(vec_near(*hit, Vec2(1.0, 0.0)));
  hit = intersection(Segment{{2.0, 0.0}, {5.0, 0.0}}, Segment{{0.0, 0.0}, {3.0, 0.0}});  // a starts in b
  ASSERT_TRUE(hit);
  EXPECT_EQ(*hit, Vec2(2.0, 0.0));
  hit = intersection(Segment{{4.0, 0.0}, {0.0, 0.0}}, Segment{{1.0, 0.0}, {2.0, 0.0}});  // a's direction does
  ASSERT_TRUE(hit);
  EXPECT_TRUE(vec_near(*hit, Vec2(2.0, 0.0)));
  hit = intersection(Segment{{0.0, 0.0}, {1.0, 0.0}}, Segment{{1.0, 0.0}, {2.0, 0.0}});  // end to end
  ASSERT_TRUE(hit);
  EXPECT_TRUE(vec_near(*hit, Vec2(1.0, 0.0)));
}

TEST(GeomIntersectTest, CollinearOverlapOnADiagonal) {
  const Segment a{{0.1, 0.1}, {0.7, 0.4}};  // direction (0.6, 0.3)
  const Segment b{a.at(0.5), a.at(2.0)};
  const auto hit = intersection(a, b);
  ASSERT_TRUE(hit);
  EXPECT_TRUE(vec_near(*hit, a.at(0.5), 1e-12));
}

TEST(GeomIntersectTest, ZeroLengthSegmentsActAsPoints) {
  const Segment a{{0.0, 0.0}, {2.0, 0.0}};
  const Segment on{{1.0, 0.0}, {1.0, 0.0}};
  const Segment off{{1.0, 0.5}, {1.0, 0.5}};
  ASSERT_TRUE(intersection(a, on));
  EXPECT_EQ(*intersection(a, on), Vec2(1.0, 0.0));
  ASSERT_TRUE(intersection(on, a));
  EXPECT_EQ(*intersection(on, a), Vec2(1.0, 0.0));
  EXPECT_FALSE(intersection(a, off));
  EXPECT_FALSE(intersection(off, a));
  EXPECT_TRUE(intersects(on, on));
  EXPECT_FALSE(intersects(on, off));
}

// ---------------------------------------------------------------------------------------------------------
// Line-line and ray-segment

TEST(GeomIntersectTest, LinesCrossInOnePoint) {
  const auto hit = intersection(Line::through({0.0, 0.0}, {1.0, 1.0}), Line::through({0.0, 2.0}, {2.0, 0.0}));
  ASSERT_TRUE(hit);
  EXPECT_TRUE(vec_near(*hit, Vec2(1.0, 1.0)));
  // Far outside the defining points: lines are infinite.
  const auto far =
      intersection(Line::through({0.0, 0.0}, {1.0, 0.0}), Line::through({10.0, 1.0}, {10.0, 2.0}));
  ASSERT_TRUE(far);
  EXPECT_TRUE(vec_near(*far, Vec2(10.0, 0.0)));
}

TEST(GeomIntersectTest, ParallelCoincidentAndDegenerateLinesHaveNoPoint) {
  const Line x_axis = Line::through({0.0, 0.0}, {1.0, 0.0});
  EXPECT_FALSE(intersection(x_axis, Line::through({0.0, 1.0}, {1.0, 1.0})));
  EXPECT_FALSE(intersection(x_axis, Line::through({5.0, 0.0}, {-3.0, 0.0})));  // coincident
  EXPECT_FALSE(intersection(x_axis, Line{{0.0, 0.0}, {0.0, 0.0}}));
  EXPECT_FALSE(intersection(x_axis, Line{{0.0, 0.0}, {kNaN, 1.0}}));
}

TEST(GeomIntersectTest, RayMeetsSegmentAheadOnly) {
  const Ray ray{{0.0, 0.0}, {1.0, 0.0}};
  auto hit = intersection(ray, Segment{{2.0, -1.0}, {2.0, 1.0}});
  ASSERT_TRUE(hit);
  EXPECT_TRUE(vec_near(*hit, Vec2(2.0, 0.0)));
  EXPECT_FALSE(intersection(ray, Segment{{-2.0, -1.0}, {-2.0, 1.0}}));                 // behind
  EXPECT_FALSE(intersection(ray, Segment{{2.0, 0.5}, {2.0, 1.0}}));                    // above
  hit = intersection(Ray{{0.0, 0.0}, {1e-3, 0.0}}, Segment{{1e3, -1.0}, {1e3, 1.0}});  // scale-free
  ASSERT_TRUE(hit);
  EXPECT_TRUE(vec_near(*hit, Vec2(1e3, 0.0), 1e-9));
}

TEST(GeomIntersectTest, RayAlongASegmentMeetsItsNearestPoint) {
  const Ray ray{{0.0, 0.0}, {1.0, 0.0}};
  auto hit = intersection(ray, Segment{{5.0, 0.0}, {3.0, 0.0}});
  ASSERT_TRUE(hit);
  EXPECT_TRUE(vec_near(*hit, Vec2(3.0, 0.0)));
  hit = intersection(ray, Segment{{-1.0, 0.0}, {1.0, 0.0}});  // origin on the segment
  ASSERT_TRUE(hit);
  EXPECT_EQ(*hit, Vec2(0.0, 0.0));
  EXPECT_FALSE(intersection(ray, Segment{{-3.0, 0.0}, {-1.0, 0.0}}));
}

// ---------------------------------------------------------------------------------------------------------
// Circles

TEST(GeomIntersectTest, LineCrossesCircleTwiceInDirectionOrder) {
  const Circle unit{{0.0, 0.0}, 1.0};
  Intersections hits = intersection(Line::through({-5.0, 0.0}, {5.0, 0.0}), unit);
  ASSERT_EQ(hits.size(), 2);
  EXPECT_TRUE(vec_near(hits[0], Vec2(-1.0, 0.0)));
  EXPECT_TRUE(vec_near(hits[1], Vec2(1.0, 0.0)));
  hits = intersection(Line::through({5.0, 0.0}, {4.0, 0.0}), unit);  // reversed direction
  ASSERT_EQ(hits.size(), 2);
  EXPECT_TRUE(vec_near(hits[0], Vec2(1.0, 0.0)));
  EXPECT_TRUE(vec_near(hits[1], Vec2(-1.0, 0.0)));
  // A chord at y = 0.6: x = +-0.8.
  hits = intersection(Line::through({0.0, 0.6}, {1.0, 0.6}), unit);
  ASSERT_EQ(hits.size(), 2);
  EXPECT_TRUE(vec_near(hits[0], Vec2(-0.8, 0.6), 1e-15));
  EXPECT_TRUE(vec_near(hits[1], Vec2(0.8, 0.6), 1e-15));
}

TEST(GeomIntersectTest, TangentLineTouchesOnce) {
  const Intersections hits = intersection(Line::through({-3.0, 1.0}, {3.0, 1.0}), Circle{{0.0, 0.0}, 1.0});
  ASSERT_EQ(hits.size(), 1);
  EXPECT_TRUE(vec_near(hits[0], Vec2(0.0, 1.0)));
  EXPECT_TRUE(
      intersection(Line::through({-3.0, 1.0 + 1e-9}, {3.0, 1.0 + 1e-9}), Circle{{0.0, 0.0}, 1.0}).empty());
}

TEST(GeomIntersectTest, TangentInGeneralPositionTouchesOnceDespiteRounding) {
  const Circle c{{0.3, -0.7}, 0.45};
  for (double degrees = 0.0; degrees < 360.0; degrees += 7.0) {
    const Vec2 normal = Angle::from_degrees(degrees).to_unit_vector();
    const Vec2 touch = c.center + c.radius * normal;
    const Line tangent =
        Line::from_point_and_direction(touch - 2.0 * perpendicular(normal), perpendicular(normal));
    const Intersections hits = intersection(tangent, c);
    ASSERT_EQ(hits.size(), 1) << degrees;
    EXPECT_TRUE(vec_near(hits[0], touch, 1e-12)) << degrees;
  }
}

TEST(GeomIntersectTest, SegmentCircleBoundaryCrossings) {
  const Circle unit{{0.0, 0.0}, 1.0};
  Intersections hits = intersection(Segment{{-2.0, 0.0}, {2.0, 0.0}}, unit);
  ASSERT_EQ(hits.size(), 2);
  EXPECT_TRUE(vec_near(hits[0], Vec2(-1.0, 0.0)));
  EXPECT_TRUE(vec_near(hits[1], Vec2(1.0, 0.0)));
  hits = intersection(Segment{{0.0, 0.0}, {0.0, -3.0}}, unit);  // starts inside: one exit
  ASSERT_EQ(hits.size(), 1);
  EXPECT_TRUE(vec_near(hits[0], Vec2(0.0, -1.0)));
  hits = intersection(Segment{{-2.0, 0.0}, {0.0, 0.0}}, unit);  // ends inside: one entry
  ASSERT_EQ(hits.size(), 1);
  EXPECT_TRUE(vec_near(hits[0], Vec2(-1.0, 0.0)));
  hits = intersection(Segment{{-3.0, 0.0}, {-1.0, 0.0}}, unit);  // ends exactly on the circle
  ASSERT_EQ(hits.size(), 1);
  EXPECT_TRUE(vec_near(hits[0], Vec2(-1.0, 0.0)));
  EXPECT_TRUE(intersection(Segment{{-0.5, 0.0}, {0.5, 0.0}}, unit).empty());   // wholly inside
  EXPECT_TRUE(intersection(Segment{{2.0, 2.0}, {3.0, 0.0}}, unit).empty());    // outside
  EXPECT_TRUE(intersection(Segment{{-3.0, 0.0}, {-1.5, 0.0}}, unit).empty());  // line crosses, segment short
}

TEST(GeomIntersectTest, SegmentCircleDegenerateCases) {
  const Circle unit{{0.0, 0.0}, 1.0};
  // Tangent segment.
  Intersections hits = intersection(Segment{{-1.0, 1.0}, {1.0, 1.0}}, unit);
  ASSERT_EQ(hits.size(), 1);
  EXPECT_TRUE(vec_near(hits[0], Vec2(0.0, 1.0)));
  // Zero-length segment on / off the boundary.
  hits = intersection(Segment{{0.6, 0.8}, {0.6, 0.8}}, unit);
  ASSERT_EQ(hits.size(), 1);
  EXPECT_EQ(hits[0], Vec2(0.6, 0.8));
  EXPECT_TRUE(intersection(Segment{{0.5, 0.5}, {0.5, 0.5}}, unit).empty());
  // Zero-radius circle on / off the segment (also at a non-representable point).
  const Segment s{{0.1, 0.2}, {0.7, 1.3}};
  hits = intersection(s, Circle{s.at(0.3), 0.0});
  ASSERT_EQ(hits.size(), 1);
  EXPECT_TRUE(vec_near(hits[0], s.at(0.3), 1e-12));
  EXPECT_TRUE(intersection(s, Circle{s.at(0.3) + Vec2(1e-6, 0.0), 0.0}).empty());
}

TEST(GeomIntersectTest, RayCircle) {
  const Circle c{{5.0, 0.0}, 1.0};
  Intersections hits = intersection(Ray{{0.0, 0.0}, {2.0, 0.0}}, c);
  ASSERT_EQ(hits.size(), 2);
  EXPECT_TRUE(vec_near(hits[0], Vec2(4.0, 0.0)));
  EXPECT_TRUE(vec_near(hits[1], Vec2(6.0, 0.0)));
  EXPECT_TRUE(intersection(Ray{{0.0, 0.0}, {-1.0, 0.0}}, c).empty());  // pointing away
  hits = intersection(Ray{{5.0, 0.0}, {0.0, 1.0}}, c);                 // from the centre
  ASSERT_EQ(hits.size(), 1);
  EXPECT_TRUE(vec_near(hits[0], Vec2(5.0, 1.0)));
  int visited = 0;
  for (const Vec2& p : intersection(Ray{{0.0, 0.0}, {1.0, 0.0}}, c)) visited += p.x() > 0.0 ? 1 : 0;
  EXPECT_EQ(visited, 2);
}

// ---------------------------------------------------------------------------------------------------------
// Rectangles

TEST(GeomIntersectTest, SegmentRectangleEntryPoint) {
  const Rectangle r({0.0, 0.0}, {2.0, 1.0});
  auto hit = intersection(Segment{{-1.0, 0.5}, {1.0, 0.5}}, r);
  ASSERT_TRUE(hit);
  EXPECT_EQ(*hit, Vec2(0.0, 0.5));
  hit = intersection(Segment{{3.0, 0.5}, {1.0, 0.5}}, r);  // from the right
  ASSERT_TRUE(hit);
  EXPECT_EQ(*hit, Vec2(2.0, 0.5));
  hit = intersection(Segment{{1.0, 0.5}, {5.0, 5.0}}, r);  // starts inside
  ASSERT_TRUE(hit);
  EXPECT_EQ(*hit, Vec2(1.0, 0.5));
  hit = intersection(Segment{{-1.0, 0.0}, {1.0, 2.0}}, r);  // through the corner (0, 1) only
  ASSERT_TRUE(hit);
  EXPECT_TRUE(vec_near(*hit, Vec2(0.0, 1.0)));
  hit = intersection(Segment{{-1.0, 0.0}, {3.0, 0.0}}, r);  // along the bottom edge
  ASSERT_TRUE(hit);
  EXPECT_EQ(*hit, Vec2(0.0, 0.0));
  hit = intersection(Segment{{-1.0, 0.5}, {0.0, 0.5}}, r);  // ends on the boundary
  ASSERT_TRUE(hit);
  EXPECT_EQ(*hit, Vec2(0.0, 0.5));
}

TEST(GeomIntersectTest, SegmentRectangleMisses) {
  const Rectangle r({0.0, 0.0}, {2.0, 1.0});
  EXPECT_FALSE(intersection(Segment{{-2.0, 0.5}, {-1.0, 0.5}}, r));  // stops short
  EXPECT_FALSE(intersection(Segment{{3.0, -1.0}, {3.0, 2.0}}, r));   // vertical, beside
  EXPECT_FALSE(intersection(Segment{{-1.0, 0.5}, {0.5, 3.0}}, r));   // passes the corner outside
  EXPECT_FALSE(intersection(Segment{{-1.0, 0.5}, {-1.0, 0.5}}, r));  // a point outside
  EXPECT_TRUE(intersection(Segment{{1.0, 0.5}, {1.0, 0.5}}, r));     // a point inside
}

TEST(GeomIntersectTest, RayRectangleEntryPoint) {
  const Rectangle r({0.0, 0.0}, {2.0, 1.0});
  auto hit = intersection(Ray{{-5.0, 0.5}, {1.0, 0.0}}, r);
  ASSERT_TRUE(hit);
  EXPECT_EQ(*hit, Vec2(0.0, 0.5));
  hit = intersection(Ray{{1.0, 3.0}, {0.0, -1.0}}, r);
  ASSERT_TRUE(hit);
  EXPECT_EQ(*hit, Vec2(1.0, 1.0));
  hit = intersection(Ray{{1.0, 0.5}, {1.0, 1.0}}, r);  // origin inside
  ASSERT_TRUE(hit);
  EXPECT_EQ(*hit, Vec2(1.0, 0.5));
  EXPECT_FALSE(intersection(Ray{{-5.0, 0.5}, {-1.0, 0.0}}, r));
  EXPECT_FALSE(intersection(Ray{{-5.0, 0.5}, {1.0, 1.0}}, r));
}

// ---------------------------------------------------------------------------------------------------------
// Boolean tests

TEST(GeomIntersectTest, SegmentCircleTouchesTheSolidDisc) {
  const Circle c{{0.0, 0.0}, 1.0};
  EXPECT_TRUE(intersects(Segment{{-0.5, 0.0}, {0.5, 0.0}}, c));  // wholly inside
  EXPECT_TRUE(intersects(Segment{{-2.0, 1.0}, {2.0, 1.0}}, c));  // tangent
  EXPECT_TRUE(intersects(c, Segment{{-2.0, 0.0}, {2.0, 0.0}}));
  EXPECT_FALSE(intersects(Segment{{-2.0, 1.01}, {2.0, 1.01}}, c));
  EXPECT_FALSE(intersects(Segment{{1.5, 0.0}, {3.0, 0.0}}, c));
}

TEST(GeomIntersectTest, CircleCircle) {
  const Circle a{{0.0, 0.0}, 1.0};
  EXPECT_TRUE(intersects(a, Circle{{3.0, 0.0}, 2.0}));  // touching
  EXPECT_FALSE(intersects(a, Circle{{3.0, 0.0}, 1.9}));
  EXPECT_TRUE(intersects(a, Circle{{0.1, 0.0}, 0.2}));  // one inside the other
  EXPECT_TRUE(intersects(a, Circle{{1.0, 0.0}, 0.0}));  // a point on the boundary
}

TEST(GeomIntersectTest, CircleRectangle) {
  const Rectangle r({0.0, 0.0}, {2.0, 1.0});
  EXPECT_TRUE(intersects(Circle{{1.0, 4.0}, 3.0}, r));  // touching the top edge
  EXPECT_FALSE(intersects(Circle{{1.0, 4.0}, 2.99}, r));
  EXPECT_TRUE(intersects(Circle{{1.0, 0.5}, 0.1}, r));  // inside
  EXPECT_TRUE(intersects(r, Circle{{5.0, 5.0}, 5.0}));  // reaches the corner (2, 1)
  EXPECT_FALSE(intersects(r, Circle{{5.0, 5.0}, 4.99}));
}

TEST(GeomIntersectTest, SegmentRectangleBoolean) {
  const Rectangle r({0.0, 0.0}, {2.0, 1.0});
  EXPECT_TRUE(intersects(Segment{{-1.0, -1.0}, {3.0, 2.0}}, r));
  EXPECT_TRUE(intersects(r, Segment{{0.5, 0.5}, {1.5, 0.5}}));
  EXPECT_FALSE(intersects(Segment{{-1.0, 2.0}, {3.0, 2.0}}, r));
}

TEST(GeomIntersectTest, SegmentPolygon) {
  const Polygon l = l_shape();
  EXPECT_TRUE(intersects(Segment{{-1.0, 0.5}, {0.5, 0.5}}, l));  // enters
  EXPECT_TRUE(intersects(Segment{{0.2, 0.2}, {0.4, 0.4}}, l));   // wholly inside
  EXPECT_TRUE(intersects(Segment{{1.5, 1.5}, {3.0, 0.0}}, l));   // from the notch through the (2, 1) corner
  EXPECT_FALSE(intersects(Segment{{1.2, 1.2}, {1.8, 1.8}}, l));  // inside the notch only
  EXPECT_FALSE(intersects(l, Segment{{3.0, 0.0}, {3.0, 3.0}}));
  EXPECT_FALSE(intersects(Segment{{0.0, 0.0}, {1.0, 1.0}}, Polygon()));
}

TEST(GeomIntersectTest, CirclePolygon) {
  const Polygon l = l_shape();
  EXPECT_TRUE(intersects(Circle{{1.5, 1.5}, 0.5}, l));  // touches the notch edges
  EXPECT_FALSE(intersects(Circle{{1.5, 1.5}, 0.49}, l));
  EXPECT_TRUE(intersects(l, Circle{{0.5, 0.5}, 0.1}));
}

TEST(GeomIntersectTest, StadiumTests) {
  const Stadium keep_out{{{0.0, 0.0}, {2.0, 0.0}}, 0.5};
  EXPECT_TRUE(intersects(Segment{{1.0, 2.0}, {1.0, 0.5}}, keep_out));  // reaches the boundary
  EXPECT_FALSE(intersects(Segment{{1.0, 2.0}, {1.0, 0.51}}, keep_out));
  EXPECT_TRUE(intersects(keep_out, Segment{{-1.0, -1.0}, {3.0, 1.0}}));  // crosses the spine
  EXPECT_TRUE(intersects(Circle{{1.0, 0.59}, 0.09}, keep_out));          // a robot touching the zone
  EXPECT_FALSE(intersects(keep_out, Circle{{1.0, 0.6}, 0.09}));
}

// ---------------------------------------------------------------------------------------------------------
// NaN

TEST(GeomIntersectTest, NaNInputNeverIntersects) {
  const Segment good{{0.0, 0.0}, {1.0, 1.0}};
  const Segment bad{{kNaN, 0.0}, {1.0, 0.0}};
  const Circle circle{{0.0, 0.0}, 1.0};
  const Rectangle rect({0.0, 0.0}, {1.0, 1.0});
  EXPECT_FALSE(intersection(good, bad));
  EXPECT_FALSE(intersection(bad, good));
  EXPECT_FALSE(intersection(bad, bad));
  EXPECT_FALSE(intersection(Segment{{kNaN, 0.0}, {kNaN, 0.0}}, good));
  EXPECT_FALSE(intersection(Ray{{0.0, 0.0}, {kNaN, 1.0}}, good));
  EXPECT_TRUE(intersection(bad, circle).empty());
  EXPECT_TRUE(intersection(good, Circle{{0.0, 0.0}, kNaN}).empty());
  EXPECT_TRUE(intersection(Line{{kNaN, 0.0}, {1.0, 0.0}}, circle).empty());
  EXPECT_TRUE(intersection(Ray{{0.0, 0.0}, {kNaN, 0.0}}, circle).empty());
  EXPECT_FALSE(intersection(bad, rect));
  EXPECT_FALSE(intersection(Ray{{0.5, 0.5}, {kNaN, 0.0}}, rect));
  EXPECT_FALSE(intersection(good, Rectangle({0.0, 0.0}, {kNaN, 1.0})));
  EXPECT_FALSE(intersects(bad, circle));
  EXPECT_FALSE(intersects(circle, Circle{{kNaN, 0.0}, 1.0}));
  EXPECT_FALSE(intersects(Circle{{kNaN, 0.0}, 1.0}, rect));
  EXPECT_FALSE(intersects(bad, rect));
  EXPECT_FALSE(intersects(bad, l_shape()));
  EXPECT_FALSE(intersects(Circle{{kNaN, 0.0}, 1.0}, l_shape()));
  EXPECT_FALSE(intersects(bad, Stadium{good, 1.0}));
  EXPECT_FALSE(intersects(circle, Stadium{bad, 1.0}));
}

// ---------------------------------------------------------------------------------------------------------
// Properties

TEST(GeomIntersectTest, PropertySegmentCircleHitsLieOnBothAndAgreeWithIntersects) {
  std::mt19937 rng(31337);
  std::uniform_real_distribution<double> coordinate(-3.0, 3.0);
  std::uniform_real_distribution<double> radius(0.0, 2.0);
  int hit_count = 0;
  for (int i = 0; i < 5000; ++i) {
    const Segment s{{coordinate(rng), coordinate(rng)}, {coordinate(rng), coordinate(rng)}};
    const Circle c{{coordinate(rng), coordinate(rng)}, radius(rng)};
    const Intersections hits = intersection(s, c);
    hit_count += hits.size();
    for (const Vec2& p : hits) {
      ASSERT_NEAR(distance(p, c.center), c.radius, 1e-9);
      ASSERT_LT(distance(p, s), 1e-12);
    }
    if (hits.size() == 2) {
      ASSERT_LE(distance(s.start, hits[0]), distance(s.start, hits[1]));
    }
    if (!hits.empty()) {
      ASSERT_TRUE(intersects(s, c));
    }
    // Disc semantics: misses the boundary but intersects => wholly inside.
    if (hits.empty() && intersects(s, c)) {
      ASSERT_TRUE(contains(c, s.start) && contains(c, s.end));
    }
  }
  EXPECT_GT(hit_count, 1000);  // the sample exercises the interesting branch
}

TEST(GeomIntersectTest, PropertySegmentSegmentHitLiesOnBothAndIsSymmetric) {
  std::mt19937 rng(4242);
  std::uniform_real_distribution<double> coordinate(-3.0, 3.0);
  int hit_count = 0;
  for (int i = 0; i < 5000; ++i) {
    const Segment a{{coordinate(rng), coordinate(rng)}, {coordinate(rng), coordinate(rng)}};
    const Segment b{{coordinate(rng), coordinate(rng)}, {coordinate(rng), coordinate(rng)}};
    const auto hit = intersection(a, b);
    ASSERT_EQ(intersects(a, b), intersects(b, a));
    ASSERT_EQ(hit.has_value(), intersects(a.reversed(), b));
    if (hit) {
      ++hit_count;
      ASSERT_LT(distance(*hit, a), 1e-12);
      ASSERT_LT(distance(*hit, b), 1e-12);
      ASSERT_TRUE(vec_near(*hit, *intersection(b, a), 1e-12));
    }
  }
  EXPECT_GT(hit_count, 500);
}

TEST(GeomIntersectTest, PropertyRectangleEntryIsTheFirstContainedPoint) {
  std::mt19937 rng(8);
  std::uniform_real_distribution<double> coordinate(-3.0, 3.0);
  const Rectangle r({-1.0, -0.5}, {1.5, 1.0});
  for (int i = 0; i < 3000; ++i) {
    const Segment s{{coordinate(rng), coordinate(rng)}, {coordinate(rng), coordinate(rng)}};
    const auto entry = intersection(s, r);
    const Polygon as_polygon = Polygon::from_rectangle(r);
    ASSERT_EQ(entry.has_value(), intersects(s, as_polygon));
    if (!entry) continue;
    ASSERT_LT(distance(*entry, r), 1e-12);
    // No sampled point before the entry is inside.
    const double t_entry = project(*entry, s).t;
    for (int k = 0; k < 20; ++k) {
      const double t = t_entry * k / 20.0;
      if (t < t_entry - 1e-9) {
        ASSERT_FALSE(r.contains(s.at(t))) << t << " " << t_entry;
      }
    }
  }
}

}  // namespace
}  // namespace ssl::geom
