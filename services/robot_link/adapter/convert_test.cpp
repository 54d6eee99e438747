// IDL samples <-> robot_link's domain types.
#include "services/robot_link/adapter/convert.h"

#include <gtest/gtest.h>

namespace ssl::robot_link {
namespace {

TEST(RobotLinkConvertTest, RobotCommandsSampleBecomesDomainCommands) {
  idl::robot::RobotCommands sample;
  sample.team(idl::common::TEAM_COLOR_BLUE);
  idl::robot::RobotCommand wire;
  wire.id(4);
  wire.forward(1.25);
  wire.left(-0.5);
  wire.angular(3.0);
  wire.kick(idl::robot::KICK_CHIP);
  wire.kick_speed(4.5);
  wire.chip_angle(0.6);
  wire.dribbler_rpm(9000);
  sample.commands().push_back(wire);
  wire.id(5);
  wire.kick(idl::robot::KICK_FLAT);
  sample.commands().push_back(wire);

  const auto commands = commands_from_idl(sample);
  ASSERT_EQ(commands.size(), 2u);
  const RobotCommand expected{.id = 4,
                              .forward = 1.25,
                              .left = -0.5,
                              .angular = 3.0,
                              .kick = KickType::kChip,
                              .kick_speed = 4.5,
                              .chip_angle = 0.6,
                              .dribbler_rpm = 9000};
  EXPECT_EQ(commands[0], expected);
  EXPECT_EQ(commands[1].kick, KickType::kFlat);
  EXPECT_TRUE(team_matches(sample, TeamColor::kBlue));
  EXPECT_FALSE(team_matches(sample, TeamColor::kYellow));
  sample.team(idl::common::TEAM_COLOR_UNKNOWN);
  EXPECT_TRUE(team_matches(sample, TeamColor::kYellow))
      << "an unset team is accepted (the partition decides)";
}

TEST(RobotLinkConvertTest, HaltAndFeedback) {
  idl::referee::RefereeState state;
  state.command(idl::referee::COMMAND_HALT);
  EXPECT_TRUE(is_halt(state));
  state.command(idl::referee::COMMAND_STOP);
  EXPECT_FALSE(is_halt(state));

  const FeedbackReport report{.robot_id = 2, .ball_in_dribbler = true, .battery_voltage = 15.5};
  const auto sample = feedback_to_idl(report, TeamColor::kYellow, 123);
  EXPECT_EQ(sample.robot_id(), 2u);
  EXPECT_EQ(sample.team(), idl::common::TEAM_COLOR_YELLOW);
  EXPECT_TRUE(sample.ball_in_dribbler());
  EXPECT_TRUE(sample.has_battery());
  EXPECT_DOUBLE_EQ(sample.battery_voltage(), 15.5);
  EXPECT_FALSE(sample.has_kicker_charge());
  EXPECT_FALSE(sample.has_link_quality());
  EXPECT_EQ(sample.receive_unix_ns(), 123);

  const FeedbackReport radio{.robot_id = 4, .kicker_charge = 0.25, .link_quality = 0.875};
  const auto radio_sample = feedback_to_idl(radio, TeamColor::kBlue, 456);
  EXPECT_TRUE(radio_sample.has_kicker_charge());
  EXPECT_DOUBLE_EQ(radio_sample.kicker_charge(), 0.25);
  EXPECT_TRUE(radio_sample.has_link_quality());
  EXPECT_DOUBLE_EQ(radio_sample.link_quality(), 0.875);
  EXPECT_FALSE(radio_sample.has_battery());
}

}  // namespace
}  // namespace ssl::robot_link
