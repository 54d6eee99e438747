#include "libs/domain/idl_convert.h"

#include <gtest/gtest.h>

#include <cstddef>
#include <limits>
#include <string>
#include <utility>

namespace ssl {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr double kInf = std::numeric_limits<double>::infinity();

TEST(DomainIdlConvert, EveryRefereeCommandMapsByName) {
  using C = wm::RefereeCommand;
  namespace r = idl::referee;
  const std::pair<r::Command, C> expected[] = {
      {r::COMMAND_HALT, C::kHalt},
      {r::COMMAND_STOP, C::kStop},
      {r::COMMAND_NORMAL_START, C::kNormalStart},
      {r::COMMAND_FORCE_START, C::kForceStart},
      {r::COMMAND_PREPARE_KICKOFF_YELLOW, C::kPrepareKickoffYellow},
      {r::COMMAND_PREPARE_KICKOFF_BLUE, C::kPrepareKickoffBlue},
      {r::COMMAND_PREPARE_PENALTY_YELLOW, C::kPreparePenaltyYellow},
      {r::COMMAND_PREPARE_PENALTY_BLUE, C::kPreparePenaltyBlue},
      {r::COMMAND_DIRECT_FREE_YELLOW, C::kDirectFreeYellow},
      {r::COMMAND_DIRECT_FREE_BLUE, C::kDirectFreeBlue},
      {r::COMMAND_INDIRECT_FREE_YELLOW, C::kIndirectFreeYellow},
      {r::COMMAND_INDIRECT_FREE_BLUE, C::kIndirectFreeBlue},
      {r::COMMAND_TIMEOUT_YELLOW, C::kTimeoutYellow},
      {r::COMMAND_TIMEOUT_BLUE, C::kTimeoutBlue},
      {r::COMMAND_GOAL_YELLOW, C::kGoalYellow},
      {r::COMMAND_GOAL_BLUE, C::kGoalBlue},
      {r::COMMAND_BALL_PLACEMENT_YELLOW, C::kBallPlacementYellow},
      {r::COMMAND_BALL_PLACEMENT_BLUE, C::kBallPlacementBlue},
  };
  for (std::size_t i = 0; i < std::size(expected); ++i) {
    const auto& [command, core] = expected[i];
    EXPECT_EQ(static_cast<std::size_t>(command), i) << "the IDL order is the league's";
    EXPECT_EQ(referee_command_from_idl(command), core) << i;
    EXPECT_EQ(static_cast<std::size_t>(core), i) << "the core's order is the league's";
  }
  EXPECT_EQ(referee_command_from_idl(static_cast<r::Command>(18)), std::nullopt);
}

idl::referee::RefereeState idl_referee() {
  idl::referee::RefereeState r;
  r.command(idl::referee::COMMAND_BALL_PLACEMENT_YELLOW);
  r.command_counter(7);
  r.has_designated_position(true);
  r.designated_position().x(1.5);
  r.designated_position().y(-0.5);
  r.has_blue_team_on_positive_half(true);
  r.blue_team_on_positive_half(true);
  r.has_next_command(true);
  r.next_command(idl::referee::COMMAND_DIRECT_FREE_YELLOW);
  r.yellow().goalkeeper(1);
  r.yellow().can_place_ball(true);
  r.yellow().max_allowed_bots(10);
  r.blue().goalkeeper(4);
  r.blue().can_place_ball(false);
  r.blue().max_allowed_bots(6);
  return r;
}

TEST(DomainIdlConvert, RefereeStateKeepsTheVisionFrameAndBothTeamsInfo) {
  auto info = referee_info_from_idl(idl_referee());
  ASSERT_TRUE(info) << info.error().message;
  EXPECT_EQ(info->command, wm::RefereeCommand::kBallPlacementYellow);
  EXPECT_EQ(info->command_counter, 7u);
  EXPECT_EQ(info->designated_position, wm::Vec2(1.5, -0.5));  // vision frame, as sent
  EXPECT_EQ(info->blue_team_on_positive_half, true);
  EXPECT_EQ(info->next_command, wm::RefereeCommand::kDirectFreeYellow);
  EXPECT_EQ(info->yellow_goalkeeper, 1u);
  EXPECT_EQ(info->blue_goalkeeper, 4u);
  EXPECT_TRUE(info->yellow_can_place_ball);
  EXPECT_FALSE(info->blue_can_place_ball);
  EXPECT_EQ(info->yellow_max_allowed_bots, 10u);
  EXPECT_EQ(info->blue_max_allowed_bots, 6u);

  idl::referee::RefereeState bare;
  bare.command(idl::referee::COMMAND_STOP);
  auto stop = referee_info_from_idl(bare);
  ASSERT_TRUE(stop);
  EXPECT_EQ(stop->command, wm::RefereeCommand::kStop);
  EXPECT_FALSE(stop->blue_team_on_positive_half);
  EXPECT_FALSE(stop->designated_position);
  EXPECT_FALSE(stop->next_command);
}

TEST(DomainIdlConvert, RefereeStateWithNonFiniteOrUnknownValuesIsRejected) {
  auto nan = idl_referee();
  nan.designated_position().y(kNaN);
  auto rejected = referee_info_from_idl(nan);
  ASSERT_FALSE(rejected);
  EXPECT_NE(rejected.error().message.find("designated_position"), std::string::npos);

  auto unknown = idl_referee();
  unknown.command(static_cast<idl::referee::Command>(40));
  EXPECT_FALSE(referee_info_from_idl(unknown));
  auto unknown_next = idl_referee();
  unknown_next.next_command(static_cast<idl::referee::Command>(-1));
  EXPECT_FALSE(referee_info_from_idl(unknown_next));
}

idl::vision::Geometry idl_geometry() {
  idl::vision::Geometry g;
  auto& f = g.field();
  f.field_length(9.0);
  f.field_width(6.0);
  f.goal_width(1.0);
  f.goal_depth(0.18);
  f.boundary_width(0.3);
  f.penalty_area_depth(1.0);
  f.penalty_area_width(2.0);
  f.center_circle_radius(0.5);
  f.goal_center_to_penalty_mark(6.0);
  return g;
}

TEST(DomainIdlConvert, GeometryGivesTheFieldSize) {
  auto field = field_from_idl(idl_geometry());
  ASSERT_TRUE(field) << field.error().message;
  EXPECT_EQ(field->field_length, 9.0);
  EXPECT_EQ(field->field_width, 6.0);
  EXPECT_EQ(field->goal_width, 1.0);
  EXPECT_EQ(field->goal_depth, 0.18);
  EXPECT_EQ(field->boundary_width, 0.3);
  EXPECT_EQ(field->penalty_area_depth, 1.0);
  EXPECT_EQ(field->penalty_area_width, 2.0);
  EXPECT_EQ(field->center_circle_radius, 0.5);
  EXPECT_EQ(field->goal_center_to_penalty_mark, 6.0);
  EXPECT_EQ(field->ball_radius, 0.0215);  // not sent: the rulebook's
  EXPECT_EQ(field->max_robot_radius, 0.09);

  auto sent = idl_geometry();
  sent.field().ball_radius(0.02);
  sent.field().max_robot_radius(0.085);
  EXPECT_EQ(field_from_idl(sent)->ball_radius, 0.02);
  EXPECT_EQ(field_from_idl(sent)->max_robot_radius, 0.085);
}

TEST(DomainIdlConvert, GeometryWithMissingOrNonFiniteDimensionsIsRejected) {
  EXPECT_FALSE(field_from_idl(idl::vision::Geometry{}));  // all zero: nothing received yet
  auto nan = idl_geometry();
  nan.field().field_width(kNaN);
  auto rejected = field_from_idl(nan);
  ASSERT_FALSE(rejected);
  EXPECT_NE(rejected.error().message.find("field_width"), std::string::npos);
  auto inf = idl_geometry();
  inf.field().ball_radius(kInf);
  EXPECT_FALSE(field_from_idl(inf));
  auto negative = idl_geometry();
  negative.field().goal_width(-1.0);
  EXPECT_FALSE(field_from_idl(negative));
}

}  // namespace
}  // namespace ssl
