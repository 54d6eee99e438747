#include "libs/geometry/project.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>

#include <gtest/gtest.h>

#include "libs/geometry/test_util.h"

namespace ssl::geom {
namespace {

using testing::is_nan;
using testing::vec_near;

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

TEST(GeomProjectTest, OntoLineGivesUnboundedParameter) {
  const Line x_axis = Line::through({0.0, 0.0}, {2.0, 0.0});
  Projection p = project(Vec2(1.0, 5.0), x_axis);
  EXPECT_EQ(p.t, 0.5);
  EXPECT_EQ(p.point, Vec2(1.0, 0.0));
  p = project(Vec2(3.0, -1.0), x_axis);
  EXPECT_EQ(p.t, 1.5);
  EXPECT_EQ(p.point, Vec2(3.0, 0.0));
  p = project(Vec2(-4.0, 2.0), x_axis);
  EXPECT_EQ(p.t, -2.0);
  EXPECT_EQ(p.point, Vec2(-4.0, 0.0));
}

TEST(GeomProjectTest, OntoDiagonalLine) {
  // Line through (1, 1) along (1, 1); (2, 0) projects back onto (1, 1), (3, 1) onto (2, 2).
  const Line diagonal = Line::from_point_and_direction({1.0, 1.0}, {1.0, 1.0});
  EXPECT_EQ(project(Vec2(2.0, 0.0), diagonal).t, 0.0);
  EXPECT_TRUE(vec_near(project(Vec2(3.0, 1.0), diagonal).point, Vec2(2.0, 2.0)));
  EXPECT_EQ(project(Vec2(3.0, 1.0), diagonal).t, 1.0);
}

TEST(GeomProjectTest, OntoSegmentClampsToTheEndpoints) {
  const Segment s{{1.0, 1.0}, {3.0, 1.0}};
  Projection p = project(Vec2(2.5, 4.0), s);
  EXPECT_EQ(p.t, 0.75);
  EXPECT_EQ(p.point, Vec2(2.5, 1.0));
  p = project(Vec2(10.0, 0.0), s);
  EXPECT_EQ(p.t, 1.0);
  EXPECT_EQ(p.point, s.end);
  p = project(Vec2(-10.0, 2.0), s);
  EXPECT_EQ(p.t, 0.0);
  EXPECT_EQ(p.point, s.start);
}

TEST(GeomProjectTest, ClampedEndpointIsExact) {
  const Segment s{{0.1, 0.2}, {0.7, 1.3}};
  EXPECT_EQ(project(Vec2(5.0, 5.0), s).point, s.end);  // no start + 1 * (end - start) rounding
}

TEST(GeomProjectTest, OntoRayClampsBehindTheOrigin) {
  const Ray ray{{0.0, 0.0}, {0.0, 2.0}};
  Projection p = project(Vec2(1.0, 3.0), ray);
  EXPECT_EQ(p.t, 1.5);
  EXPECT_EQ(p.point, Vec2(0.0, 3.0));
  p = project(Vec2(1.0, -3.0), ray);
  EXPECT_EQ(p.t, 0.0);
  EXPECT_EQ(p.point, Vec2(0.0, 0.0));
}

TEST(GeomProjectTest, DegenerateShapesProjectOntoTheirPoint) {
  const Projection on_point = project(Vec2(5.0, 5.0), Segment{{1.0, 2.0}, {1.0, 2.0}});
  EXPECT_EQ(on_point.t, 0.0);
  EXPECT_EQ(on_point.point, Vec2(1.0, 2.0));
  const Projection on_line = project(Vec2(5.0, 5.0), Line{{1.0, 2.0}, {0.0, 0.0}});
  EXPECT_EQ(on_line.t, 0.0);
  EXPECT_EQ(on_line.point, Vec2(1.0, 2.0));
}

TEST(GeomProjectTest, NaNGivesNaN) {
  const Segment s{{0.0, 0.0}, {1.0, 0.0}};
  EXPECT_TRUE(std::isnan(project(Vec2(kNaN, 0.0), s).t));
  EXPECT_TRUE(is_nan(project(Vec2(kNaN, 0.0), s).point));
  EXPECT_TRUE(is_nan(project(Vec2(0.5, 0.5), Segment{{0.0, 0.0}, {kNaN, 0.0}}).point));
  EXPECT_TRUE(is_nan(project(Vec2(0.5, 0.5), Line{{0.0, 0.0}, {kNaN, 1.0}}).point));
  EXPECT_TRUE(is_nan(project(Vec2(kNaN, 0.5), Ray{{0.0, 0.0}, {1.0, 1.0}}).point));
}

TEST(GeomProjectTest, PropertyFootIsPerpendicularAndMatchesTheParameter) {
  std::mt19937 rng(42);
  std::uniform_real_distribution<double> coordinate(-5.0, 5.0);
  for (int i = 0; i < 2000; ++i) {
    const Segment s{{coordinate(rng), coordinate(rng)}, {coordinate(rng), coordinate(rng)}};
    const Vec2 p(coordinate(rng), coordinate(rng));
    const Projection on_segment = project(p, s);
    ASSERT_GE(on_segment.t, 0.0);
    ASSERT_LE(on_segment.t, 1.0);
    ASSERT_TRUE(vec_near(on_segment.point, s.at(on_segment.t), 1e-12));
    const Projection on_line = project(p, Line::containing(s));
    ASSERT_NEAR((p - on_line.point).dot(s.direction()), 0.0, 1e-10);
    ASSERT_NEAR(on_segment.t, std::clamp(on_line.t, 0.0, 1.0), 1e-12);
  }
}

}  // namespace
}  // namespace ssl::geom
