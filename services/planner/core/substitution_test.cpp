#include "services/planner/core/substitution.h"

#include <gtest/gtest.h>

#include <vector>

#include "libs/domain/field.h"

namespace ssl::planner {
namespace {

wm::RobotState robot(std::uint32_t id, const Vec2& position) {
  wm::RobotState r;
  r.id = id;
  r.position = position;
  r.visible = true;
  return r;
}

const wm::Field kField{wm::FieldSize::division_b()};  // touch lines at y = +-3

TEST(ChooseLeaving, NobodyLeavesWhileTheTeamIsWithinTheLimit) {
  const std::vector<wm::RobotState> six = {robot(0, {-4, 0}), robot(1, {-2, 1}), robot(2, {-2, -1}),
                                           robot(3, {0, 1}),  robot(4, {1, -1}), robot(5, {2, 0})};
  EXPECT_TRUE(choose_leaving(six, 6, 0u, {}, kField).empty());
  EXPECT_TRUE(choose_leaving(six, 11, 0u, {}, kField).empty());
}

TEST(ChooseLeaving, TheFieldPlayerNearestToItsSubstitutionSpotLeavesAndStaysChosen) {
  // Robot 3 stands nearest to the spot beside the halfway line on our half (-0.3, 3.15).
  std::vector<wm::RobotState> six = {robot(0, {-4, 0}), robot(1, {-2, 1}), robot(2, {-2, -1}),
                                     robot(3, {-0.5, 2.5}), robot(4, {1, -1}), robot(5, {2, 0})};
  const std::vector<std::uint32_t> first = choose_leaving(six, 5, 0u, {}, kField);
  EXPECT_EQ(first, std::vector<std::uint32_t>{3});
  // Robot 4 now stands nearer, but robot 3 is on its way: it keeps leaving.
  six[4].position = {-0.3, 3.0};
  EXPECT_EQ(choose_leaving(six, 5, 0u, first, kField), std::vector<std::uint32_t>{3});
  // A second card: one more leaves, robot 3 still among them.
  EXPECT_EQ(choose_leaving(six, 4, 0u, first, kField), (std::vector<std::uint32_t>{3, 4}));
}

TEST(ChooseLeaving, TheGoalkeeperLeavesOnlyWhenNoFieldPlayerIsLeft) {
  const std::vector<wm::RobotState> two = {robot(0, {-0.3, 3.1}), robot(1, {3, -2})};
  EXPECT_EQ(choose_leaving(two, 1, 0u, {}, kField), std::vector<std::uint32_t>{1});
  EXPECT_EQ(choose_leaving(two, 0, 0u, {}, kField), (std::vector<std::uint32_t>{0, 1}));
}

TEST(ChooseLeaving, WhenACardExpiresTheRobotNearestTheHalfwayLineComesBackFirst) {
  const std::vector<wm::RobotState> six = {robot(0, {-4, 0}),      robot(1, {-2, 1}),     robot(2, {-2, -1}),
                                           robot(3, {-0.3, 3.15}), robot(4, {-0.55, 3.15}), robot(5, {2, 0})};
  const std::vector<std::uint32_t> both = {3, 4};
  EXPECT_EQ(choose_leaving(six, 5, 0u, both, kField), std::vector<std::uint32_t>{4});
}

TEST(LeavingSpot, IsOnTheRobotsTouchLineInOurHalfOffTheField) {
  const Vec2 plus = leaving_spot(kField, robot(1, {2, 0.5}), 0);
  const Vec2 minus = leaving_spot(kField, robot(1, {2, -0.5}), 1);
  EXPECT_GT(plus.y(), 3.0);
  EXPECT_LT(minus.y(), -3.0);
  EXPECT_LT(plus.x(), 0.0);
  EXPECT_LT(minus.x(), plus.x()) << "the second slot lies further from the halfway line";
  EXPECT_FALSE(counts_towards_robot_limit(kField.size(), plus));
}

}  // namespace
}  // namespace ssl::planner
