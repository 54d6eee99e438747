#include "libs/domain/keep_out.h"

#include <gtest/gtest.h>

#include "libs/geometry/distance.h"

namespace ssl {
namespace {

constexpr double kRobotRadius = 0.09;

void expect_near(const geom::Vec2& actual, const geom::Vec2& expected) {
  EXPECT_NEAR(actual.x(), expected.x(), 1e-12);
  EXPECT_NEAR(actual.y(), expected.y(), 1e-12);
}

TEST(KeepOut, TheBallDiscIsTheRuleDistanceFromTheRobotsNearestSide) {
  const geom::Circle zone = ball_keep_out({1, 2}, kRobotRadius);
  EXPECT_DOUBLE_EQ(zone.radius, rules::kStopBallDistance + kRobotRadius);
  EXPECT_LT(geom::signed_distance(geom::Vec2(1 + 0.58, 2), zone), 0) << "its side 0.49 m from the ball";
  EXPECT_GT(geom::signed_distance(geom::Vec2(1 + 0.60, 2), zone), 0) << "its side 0.51 m from the ball";
}

TEST(KeepOut, ThePlacementStadiumCoversTheWholeWayOfTheBall) {
  const geom::Stadium zone = placement_keep_out({0, 0}, {2, 0}, kRobotRadius);
  EXPECT_DOUBLE_EQ(zone.radius, rules::kPlacementKeepOutDistance + kRobotRadius);
  EXPECT_LT(geom::signed_distance(geom::Vec2(1, 0.58), zone), 0) << "beside the middle of the way";
  EXPECT_GT(geom::signed_distance(geom::Vec2(1, 0.60), zone), 0);
  EXPECT_LT(geom::signed_distance(geom::Vec2(2.58, 0), zone), 0) << "beyond the designated position";
}

TEST(KeepOut, TheDefenseAreaZoneGrowsTowardsTheFieldAndReachesBehindTheGoal) {
  const FieldGeometry b = FieldGeometry::division_b();  // 9 x 6 m, defense area 1 x 2 m
  const geom::Rectangle theirs = defense_area_keep_out(b, +1, 0.3, 1.0);
  expect_near(theirs.min(), geom::Vec2(4.5 - 1.0 - 0.3, -1.3));
  expect_near(theirs.max(), geom::Vec2(4.5 + 1.0, 1.3));
  const geom::Rectangle ours = defense_area_keep_out(b, -1, 0.1, 1.0);
  expect_near(ours.min(), geom::Vec2(-4.5 - 1.0, -1.1));
  expect_near(ours.max(), geom::Vec2(-4.5 + 1.0 + 0.1, 1.1));
}

}  // namespace
}  // namespace ssl
