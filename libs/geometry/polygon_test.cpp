#include "libs/geometry/polygon.h"

#include <cmath>
#include <limits>
#include <numbers>
#include <vector>

#include <gtest/gtest.h>

#include "libs/geometry/test_util.h"

namespace ssl::geom {
namespace {

using testing::is_nan;
using testing::vec_near;

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

Polygon unit_square() { return Polygon{{0.0, 0.0}, {1.0, 0.0}, {1.0, 1.0}, {0.0, 1.0}}; }

// An L: the square [0, 2]^2 without its top-right quarter [1, 2]^2. Area 3.
Polygon l_shape() { return Polygon{{0.0, 0.0}, {2.0, 0.0}, {2.0, 1.0}, {1.0, 1.0}, {1.0, 2.0}, {0.0, 2.0}}; }

// The five-pointed star {5/2}: every turn goes the same way but the boundary winds twice.
Polygon pentagram() {
  std::vector<Vec2> vertices;
  for (int k = 0; k < 5; ++k) {
    const double a = std::numbers::pi / 2.0 + k * 4.0 * std::numbers::pi / 5.0;
    vertices.emplace_back(std::cos(a), std::sin(a));
  }
  return Polygon(std::move(vertices));
}

TEST(GeomPolygonTest, VerticesAndEdgesWrapAround) {
  const Polygon square = unit_square();
  EXPECT_EQ(square.size(), 4u);
  EXPECT_FALSE(square.empty());
  EXPECT_EQ(square[2], Vec2(1.0, 1.0));
  EXPECT_EQ(square.edge(0), (Segment{{0.0, 0.0}, {1.0, 0.0}}));
  EXPECT_EQ(square.edge(3), (Segment{{0.0, 1.0}, {0.0, 0.0}}));
  EXPECT_TRUE(Polygon().empty());
}

TEST(GeomPolygonTest, FromRectangleIsCounterClockwise) {
  const Polygon p = Polygon::from_rectangle(Rectangle({1.0, 1.0}, {3.0, 2.0}));
  ASSERT_EQ(p.size(), 4u);
  EXPECT_EQ(p[0], Vec2(1.0, 1.0));
  EXPECT_EQ(p[1], Vec2(3.0, 1.0));
  EXPECT_EQ(signed_area(p), 2.0);
}

TEST(GeomPolygonTest, SignedAreaIsPositiveCounterClockwiseAndNegativeClockwise) {
  EXPECT_EQ(signed_area(unit_square()), 1.0);
  EXPECT_EQ(signed_area(Polygon{{0.0, 0.0}, {0.0, 1.0}, {1.0, 1.0}, {1.0, 0.0}}), -1.0);
  EXPECT_EQ(signed_area(Polygon{{0.0, 0.0}, {4.0, 0.0}, {0.0, 3.0}}), 6.0);
  EXPECT_EQ(signed_area(l_shape()), 3.0);
  EXPECT_EQ(area(Polygon{{0.0, 0.0}, {0.0, 3.0}, {4.0, 0.0}}), 6.0);
}

TEST(GeomPolygonTest, SignedAreaKeepsPrecisionFarFromTheOrigin) {
  const Polygon far{
      {1e6 + 0.1, 1e6 + 0.1}, {1e6 + 1.1, 1e6 + 0.1}, {1e6 + 1.1, 1e6 + 1.1}, {1e6 + 0.1, 1e6 + 1.1}};
  EXPECT_NEAR(signed_area(far), 1.0, 1e-9);
}

TEST(GeomPolygonTest, DegeneratePolygonsHaveZeroArea) {
  EXPECT_EQ(signed_area(Polygon()), 0.0);
  EXPECT_EQ(signed_area(Polygon{{1.0, 1.0}}), 0.0);
  EXPECT_EQ(signed_area(Polygon{{1.0, 1.0}, {2.0, 2.0}}), 0.0);
  EXPECT_EQ(signed_area(Polygon{{0.0, 0.0}, {1.0, 1.0}, {3.0, 3.0}}), 0.0);
}

TEST(GeomPolygonTest, SignedAreaOfNaNVertexIsNaN) {
  EXPECT_TRUE(std::isnan(signed_area(Polygon{{0.0, 0.0}, {kNaN, 0.0}, {1.0, 1.0}})));
  EXPECT_TRUE(std::isnan(signed_area(Polygon{{0.0, kNaN}})));
}

TEST(GeomPolygonTest, CentroidOfAreaWeightsTheRegion) {
  EXPECT_TRUE(vec_near(centroid(Polygon{{0.0, 0.0}, {2.0, 0.0}, {2.0, 2.0}, {0.0, 2.0}}), Vec2(1.0, 1.0)));
  EXPECT_TRUE(vec_near(centroid(Polygon{{0.0, 0.0}, {3.0, 0.0}, {0.0, 6.0}}), Vec2(1.0, 2.0)));
  // L: rectangle [0,2]x[0,1] (area 2, centroid (1, 0.5)) plus [0,1]x[1,2] (area 1, centroid (0.5, 1.5)).
  EXPECT_TRUE(vec_near(centroid(l_shape()), Vec2(2.5 / 3.0, 2.5 / 3.0)));
  // Clockwise order gives the same centroid.
  EXPECT_TRUE(vec_near(centroid(Polygon{{0.0, 0.0}, {0.0, 6.0}, {3.0, 0.0}}), Vec2(1.0, 2.0)));
}

TEST(GeomPolygonTest, CentroidIsNotTheVertexMeanForUnevenVertices) {
  // A square with an extra vertex on its bottom edge: the vertex mean moves, the area centroid does not.
  const Polygon square{{0.0, 0.0}, {0.5, 0.0}, {2.0, 0.0}, {2.0, 2.0}, {0.0, 2.0}};
  EXPECT_TRUE(vec_near(centroid(square), Vec2(1.0, 1.0)));
}

TEST(GeomPolygonTest, CentroidOfZeroAreaFallsBackToVertexMean) {
  EXPECT_TRUE(vec_near(centroid(Polygon{{0.0, 0.0}, {1.0, 1.0}, {5.0, 5.0}}), Vec2(2.0, 2.0)));
  EXPECT_TRUE(vec_near(centroid(Polygon{{1.0, 2.0}}), Vec2(1.0, 2.0)));
  EXPECT_TRUE(vec_near(centroid(Polygon{{1.0, 2.0}, {3.0, 2.0}}), Vec2(2.0, 2.0)));
}

TEST(GeomPolygonTest, CentroidOfEmptyOrNaNIsNaN) {
  EXPECT_TRUE(is_nan(centroid(Polygon())));
  EXPECT_TRUE(is_nan(centroid(Polygon{{0.0, 0.0}, {1.0, kNaN}, {1.0, 1.0}})));
}

TEST(GeomPolygonTest, ConvexPolygonsAreConvexInEitherOrientation) {
  EXPECT_TRUE(is_convex(unit_square()));
  EXPECT_TRUE(is_convex(Polygon{{0.0, 0.0}, {0.0, 1.0}, {1.0, 1.0}, {1.0, 0.0}}));
  EXPECT_TRUE(is_convex(Polygon{{0.0, 0.0}, {4.0, 0.0}, {0.0, 3.0}}));
  // A regular hexagon.
  std::vector<Vec2> hexagon;
  for (int k = 0; k < 6; ++k)
    hexagon.emplace_back(std::cos(k * std::numbers::pi / 3.0), std::sin(k * std::numbers::pi / 3.0));
  EXPECT_TRUE(is_convex(Polygon(hexagon)));
}

TEST(GeomPolygonTest, CollinearAndRepeatedVerticesDoNotBreakConvexity) {
  EXPECT_TRUE(is_convex(Polygon{{0.0, 0.0}, {0.5, 0.0}, {1.0, 0.0}, {1.0, 1.0}, {0.0, 1.0}}));
  EXPECT_TRUE(is_convex(Polygon{{0.0, 0.0}, {1.0, 0.0}, {1.0, 0.0}, {1.0, 1.0}, {0.0, 1.0}, {0.0, 0.0}}));
}

TEST(GeomPolygonTest, NonConvexPolygonsAreRejected) {
  EXPECT_FALSE(is_convex(l_shape()));
  EXPECT_FALSE(is_convex(pentagram()));
  // A zero-width spike going out and back along the same line.
  EXPECT_FALSE(is_convex(Polygon{{0.0, 0.0}, {1.0, 0.0}, {1.0, 1.0}, {1.0, 3.0}, {1.0, 1.0}, {0.0, 1.0}}));
  // A bow tie (self-intersecting quadrilateral).
  EXPECT_FALSE(is_convex(Polygon{{0.0, 0.0}, {1.0, 1.0}, {1.0, 0.0}, {0.0, 1.0}}));
}

TEST(GeomPolygonTest, DegeneratePolygonsAreNotConvex) {
  EXPECT_FALSE(is_convex(Polygon()));
  EXPECT_FALSE(is_convex(Polygon{{0.0, 0.0}, {1.0, 0.0}}));
  EXPECT_FALSE(is_convex(Polygon{{0.0, 0.0}, {1.0, 1.0}, {2.0, 2.0}}));
  EXPECT_FALSE(is_convex(Polygon{{1.0, 1.0}, {1.0, 1.0}, {1.0, 1.0}}));
  EXPECT_FALSE(is_convex(Polygon{{0.0, 0.0}, {1.0, 0.0}, {kNaN, 1.0}}));
}

}  // namespace
}  // namespace ssl::geom
