#include "services/planner/core/assignment.h"

#include <gtest/gtest.h>

#include <vector>

namespace ssl::planner {
namespace {

using wm::Vec2;

TEST(PlannerAssignmentTest, HungarianFindsTheCheapestAssignment) {
  CostMatrix cost{};
  // Greedy (row 0 takes column 0) would cost 1 + 10; optimal is 2 + 2.
  cost[0][0] = 1;
  cost[0][1] = 2;
  cost[1][0] = 2;
  cost[1][1] = 10;
  const auto result = optimal_assignment(cost, 2, 2);
  EXPECT_EQ(result[0], 1);
  EXPECT_EQ(result[1], 0);
}

TEST(PlannerAssignmentTest, MoreSlotsThanRobotsLeavesSlotsEmpty) {
  CostMatrix cost{};
  for (std::size_t s = 0; s < 3; ++s) cost[0][s] = static_cast<double>(3 - s);
  EXPECT_EQ(optimal_assignment(cost, 1, 3)[0], 2);
}

TEST(PlannerAssignmentTest, StableAssignerKeepsItsChoiceUnlessMuchBetter) {
  StableAssigner assigner(0.3);
  const std::vector<std::uint32_t> ids = {3, 7};
  const std::vector<Vec2> slots = {{0, 0}, {1, 0}};
  std::vector<Vec2> robots = {{0.1, 0}, {0.9, 0}};
  auto first = assigner.assign(1, ids, robots, slots);
  EXPECT_EQ(first[0], 0);
  EXPECT_EQ(first[1], 1);
  // Robots drift so that swapping is slightly better: keep.
  robots = {{0.55, 0}, {0.45, 0}};
  auto second = assigner.assign(1, ids, robots, slots);
  EXPECT_EQ(second[0], 0);
  EXPECT_EQ(second[1], 1);
  // Much better: switch.
  robots = {{1.0, 0}, {0.0, 0}};
  auto third = assigner.assign(1, ids, robots, slots);
  EXPECT_EQ(third[0], 1);
  EXPECT_EQ(third[1], 0);
  // Another formation key: fresh optimal assignment at once.
  robots = {{0.55, 0}, {0.45, 0}};
  auto fourth = assigner.assign(2, ids, robots, slots);
  EXPECT_EQ(fourth[0], 1);
  EXPECT_EQ(fourth[1], 0);
}

TEST(PlannerAssignmentTest, MoreRobotsThanSlotsGetMinusOne) {
  StableAssigner assigner;
  const std::vector<std::uint32_t> ids = {1, 2, 3};
  const std::vector<Vec2> robots = {{0, 0}, {5, 0}, {1, 0}};
  const std::vector<Vec2> slots = {{0.9, 0}, {0, 0.1}};
  auto result = assigner.assign(1, ids, robots, slots);
  EXPECT_EQ(result[0], 1);
  EXPECT_EQ(result[1], -1);
  EXPECT_EQ(result[2], 0);
}

TEST(PlannerAssignmentTest, StableChoiceNeedsAClearlyBetterCandidate) {
  StableChoice choice(0.3);
  const std::vector<std::uint32_t> ids = {4, 9};
  EXPECT_EQ(choice.choose(ids, std::vector<double>{1.0, 1.2}), 4u);
  EXPECT_EQ(choice.choose(ids, std::vector<double>{1.1, 0.9}), 4u);  // 9 better by 0.2 < 0.3
  EXPECT_EQ(choice.choose(ids, std::vector<double>{1.5, 0.9}), 9u);
  EXPECT_EQ(choice.choose(std::vector<std::uint32_t>{}, std::vector<double>{}), std::nullopt);
}

}  // namespace
}  // namespace ssl::planner
