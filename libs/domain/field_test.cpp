#include "libs/domain/field.h"

#include <gtest/gtest.h>

#include <cmath>

namespace ssl {
namespace {

TEST(FieldGeometry, TheDivisionsHaveTheRulesNumbers) {
  const FieldGeometry a = FieldGeometry::of(Division::kA);
  EXPECT_EQ(a.field_length, 12.0);
  EXPECT_EQ(a.field_width, 9.0);
  EXPECT_EQ(a.goal_width, 1.8);
  EXPECT_EQ(a.penalty_area_depth, 1.8);
  EXPECT_EQ(a.penalty_area_width, 3.6);
  EXPECT_EQ(a.goal_center_to_penalty_mark, 8.0);
  EXPECT_EQ(a.boundary_width_goal_line, 0.6);
  const FieldGeometry b = FieldGeometry::of(Division::kB);
  EXPECT_EQ(b.field_length, 9.0);
  EXPECT_EQ(b.field_width, 6.0);
  EXPECT_EQ(b.goal_width, 1.0);
  EXPECT_EQ(b.penalty_area_depth, 1.0);
  EXPECT_EQ(b.penalty_area_width, 2.0);
  EXPECT_EQ(b.goal_center_to_penalty_mark, 6.0);
  EXPECT_EQ(b.boundary_width_goal_line, 0.3);
  EXPECT_EQ(FieldGeometry(), a) << "a default field is division A's";
}

TEST(FieldGeometry, TheDefenseAreasLieAgainstTheirGoalLines) {
  const FieldGeometry b = FieldGeometry::division_b();
  const geom::Rectangle plus = defense_area(b, +1);
  EXPECT_EQ(plus.min(), geom::Vec2(3.5, -1.0));
  EXPECT_EQ(plus.max(), geom::Vec2(4.5, 1.0));
  const geom::Rectangle minus = defense_area(b, -1);
  EXPECT_EQ(minus.min(), geom::Vec2(-4.5, -1.0));
  EXPECT_EQ(minus.max(), geom::Vec2(-3.5, 1.0));
}

TEST(FieldGeometry, ARobotCountsTowardsTheLimitUntilItIsWhollyBeyondTheLines) {
  const FieldGeometry b = FieldGeometry::division_b();  // touch lines at y = +-3, radius 0.09
  EXPECT_TRUE(counts_towards_robot_limit(b, {0.0, 3.09}));
  EXPECT_FALSE(counts_towards_robot_limit(b, {0.0, 3.0901}));
  EXPECT_TRUE(counts_towards_robot_limit(b, {-4.59, 0.0}));
  EXPECT_FALSE(counts_towards_robot_limit(b, {-4.5901, 0.0}));
}

TEST(FieldGeometry, SubstitutionSpotsLieBesideTheHalfwayLineOffTheFieldAndClearOfTheWall) {
  for (const FieldGeometry& field : {FieldGeometry::division_a(), FieldGeometry::division_b()}) {
    for (int slot = 0; slot < 5; ++slot) {
      const geom::Vec2 spot = substitution_spot(field, -1, +1, slot);
      EXPECT_FALSE(counts_towards_robot_limit(field, spot)) << slot;
      EXPECT_LE(spot.y() + field.max_robot_radius, field.half_width() + field.boundary_width - 0.05) << "wall";
      EXPECT_LT(spot.x(), 0.0) << "in the asked half";
      EXPECT_GE(spot.x(), -1.0) << "within 1 m of the halfway line";
    }
    EXPECT_NEAR((substitution_spot(field, -1, +1, 1) - substitution_spot(field, -1, +1, 0)).norm(), 0.25, 1e-12);
    EXPECT_EQ(substitution_spot(field, +1, -1, 0), geom::Vec2(0.3, -field.half_width() - 0.15));
  }
}

TEST(FieldGeometry, ImpossibleFieldsAreRejectedWithTheirKey) {
  EXPECT_TRUE(check_field_geometry(FieldGeometry::division_a()));
  EXPECT_TRUE(check_field_geometry(FieldGeometry::division_b()));
  FieldGeometry broken = FieldGeometry::division_b();
  broken.goal_width = std::nan("");
  const Status status = check_field_geometry(broken);
  ASSERT_FALSE(status);
  EXPECT_NE(status.error().message.find("goal_width"), std::string::npos);
  broken = FieldGeometry::division_b();
  broken.penalty_area_depth = 5;
  EXPECT_FALSE(check_field_geometry(broken));
}

}  // namespace
}  // namespace ssl
