#include "libs/domain/team_field.h"

#include <gtest/gtest.h>

#include <cmath>

namespace ssl::wm {
namespace {

TEST(WorldModelField, NamedPointsOfDivisionAInTheTeamFrame) {
  const Field field;  // division A defaults
  EXPECT_EQ(field.our_goal_center(), Vec2(-6.0, 0));
  EXPECT_EQ(field.their_goal_center(), Vec2(6.0, 0));
  EXPECT_EQ(field.their_penalty_mark(), Vec2(-2.0, 0));  // 8 m in front of their goal
  EXPECT_EQ(field.our_penalty_mark(), Vec2(2.0, 0));
  EXPECT_EQ(field.our_goal_posts()[0], Vec2(-6.0, 0.9));
  EXPECT_EQ(field.their_goal_posts()[1], Vec2(6.0, -0.9));
  EXPECT_EQ(field.our_defense_area_front_corners()[0], Vec2(-4.2, 1.8));
  EXPECT_EQ(field.their_defense_area_front_corners()[1], Vec2(4.2, -1.8));
  EXPECT_EQ(field.our_defense_area_corners()[0], Vec2(-6.0, -1.8));
  EXPECT_EQ(field.their_defense_area_corners()[0], Vec2(6.0, 1.8));
  EXPECT_EQ(field.their_corner_pos(), Vec2(6.0, 4.5));
  EXPECT_EQ(field.our_corner_neg(), Vec2(-6.0, -4.5));
}

TEST(WorldModelField, AreasContainTheRightPoints) {
  FieldSize b;
  b.field_length = 9;
  b.field_width = 6;
  b.penalty_area_depth = 1;
  b.penalty_area_width = 2;
  const Field field(b);
  EXPECT_TRUE(field.in_our_defense_area({-4.0, 0.5}));
  EXPECT_FALSE(field.in_our_defense_area({-3.4, 0.5}));
  EXPECT_TRUE(field.in_their_defense_area({4.2, -0.9}));
  EXPECT_FALSE(field.in_their_defense_area({-4.2, -0.9}));
  EXPECT_TRUE(field.in_field({4.5, 3.0}));
  EXPECT_FALSE(field.in_field({4.6, 0}));
  EXPECT_TRUE(field.in_center_circle({0.3, 0.3}));
  EXPECT_TRUE(field.in_our_half({-0.1, 2}));
}

TEST(WorldModelField, ABallLeavesTheFieldOnlyWhollyBeyondALine) {
  const Field field;  // division A: 12 x 9, ball radius 0.0215
  EXPECT_TRUE(field.ball_in_field({-6.02, 0.5})) << "centre 2 cm behind the goal line: still on it";
  EXPECT_FALSE(field.ball_in_field({-6.022, 0.5}));
  EXPECT_TRUE(field.ball_in_field({1.0, 4.52}));
  EXPECT_FALSE(field.ball_in_field({1.0, -4.53}));
}

TEST(WorldModelField, DistanceToOurGoalWallsIsToTheNearerWallFromItsPostBack) {
  const Field field;  // division A: posts at y = +-0.9 on x = -6, goal depth 0.18
  EXPECT_NEAR(field.distance_to_our_goal_walls({-5.95, -0.81}), std::hypot(0.05, 0.09), 1e-12)
      << "in front of the post";
  EXPECT_NEAR(field.distance_to_our_goal_walls({-6.1, -0.7}), 0.2, 1e-12) << "beside the wall, inside the goal";
  EXPECT_NEAR(field.distance_to_our_goal_walls({-6.3, 0.9}), 0.12, 1e-12) << "behind the goal";
  EXPECT_NEAR(field.distance_to_our_goal_walls({-5.0, 0.3}), std::hypot(1.0, 0.6), 1e-12);
}

TEST(WorldModelField, DistanceInsideIsToTheFirstLineCrossed) {
  const Field field;  // division A: 12 x 9
  EXPECT_NEAR(field.distance_inside({0, 0}, {1, 0}), 6.0, 1e-12);
  EXPECT_NEAR(field.distance_inside({0, 0}, {0, -1}), 4.5, 1e-12);
  // Diagonal from the centre: the touch line (4.5 / sin 45) comes before the goal line (6 / cos 45).
  const double d = std::sqrt(0.5);
  EXPECT_NEAR(field.distance_inside({0, 0}, {d, d}), 4.5 / d, 1e-9);
  EXPECT_NEAR(field.distance_inside({-5.0, 4.0}, {-d, d}), 0.5 / d, 1e-9);
  // On the touch line moving out: nothing left; moving along it: the goal line.
  EXPECT_EQ(field.distance_inside({1.0, 4.5}, {0, 1}), 0.0);
  EXPECT_NEAR(field.distance_inside({1.0, 4.5}, {1, 0}), 5.0, 1e-12);
}

}  // namespace
}  // namespace ssl::wm
