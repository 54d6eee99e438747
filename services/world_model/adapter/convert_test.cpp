#include "services/world_model/adapter/convert.h"

#include <gtest/gtest.h>

#include <limits>

namespace ssl::wm {
namespace {

TEST(WorldModelConvert, DetectionFrameKeepsVisionFrameAndTimes) {
  idl::vision::DetectionFrame in;
  in.camera_id(2);
  in.frame_number(7);
  in.capture_unix_ns(1'000'000'000);
  in.sent_unix_ns(1'012'000'000);
  idl::vision::RobotDetection r;
  r.robot_id(3);
  r.x(1.5);
  r.y(-0.5);
  r.orientation(0.2);
  r.has_orientation(true);
  r.confidence(0.9f);
  in.robots_blue().push_back(r);
  idl::vision::BallDetection b;
  b.x(0.1);
  b.y(0.2);
  b.confidence(1.0f);
  in.balls().push_back(b);
  const auto out = from_idl(in);
  ASSERT_TRUE(out.has_value());
  EXPECT_EQ(out->camera_id, 2u);
  EXPECT_EQ(out->capture_time.nanoseconds(), 1'000'000'000);
  EXPECT_EQ(out->sent_time.nanoseconds(), 1'012'000'000);
  ASSERT_EQ(out->robots_blue.size(), 1u);
  EXPECT_EQ(out->robots_blue[0].position, Vec2(1.5, -0.5));
  EXPECT_DOUBLE_EQ(out->robots_blue[0].orientation, 0.2);
  ASSERT_EQ(out->balls.size(), 1u);
  EXPECT_EQ(out->balls[0].position, Vec2(0.1, 0.2));
}

TEST(WorldModelConvert, NonFiniteDetectionDropsTheFrame) {
  idl::vision::DetectionFrame in;
  idl::vision::BallDetection b;
  b.x(std::numeric_limits<double>::quiet_NaN());
  in.balls().push_back(b);
  EXPECT_FALSE(from_idl(in).has_value());
}

TEST(WorldModelConvert, RefereeCommandsMapOneToOne) {
  idl::referee::RefereeState in;
  in.command(idl::referee::COMMAND_BALL_PLACEMENT_BLUE);
  in.has_blue_team_on_positive_half(true);
  in.blue_team_on_positive_half(true);
  in.has_designated_position(true);
  in.designated_position().x(1.0);
  const Result<RefereeInfo> out = from_idl(in);
  ASSERT_TRUE(out) << out.error().message;
  EXPECT_EQ(out->command, RefereeCommand::kBallPlacementBlue);
  EXPECT_EQ(out->blue_team_on_positive_half, std::optional<bool>(true));
  EXPECT_EQ(out->designated_position, std::optional<Vec2>(Vec2(1.0, 0)));
  in.command(idl::referee::COMMAND_HALT);
  EXPECT_EQ(from_idl(in)->command, RefereeCommand::kHalt);
}

TEST(WorldModelConvert, CorruptRefereeStatesAndGeometriesAreRejected) {
  idl::referee::RefereeState referee;
  referee.command(static_cast<idl::referee::Command>(40));
  EXPECT_FALSE(from_idl(referee)) << "an unknown command is not cast into the enum";
  referee.command(idl::referee::COMMAND_STOP);
  referee.has_designated_position(true);
  referee.designated_position().x(std::numeric_limits<double>::quiet_NaN());
  EXPECT_FALSE(from_idl(referee));
  EXPECT_FALSE(from_idl(idl::vision::Geometry{})) << "no dimensions: nothing to fuse with";
}

TEST(WorldModelConvert, WorldStateCarriesStampTeamFrameAndPossession) {
  WorldState in;
  in.team = TeamColor::kYellow;
  in.flipped = true;
  in.stamp.capture_time = time::Timestamp::from_nanoseconds(42);
  in.stamp.camera_id = 3;
  in.has_ball = true;
  in.ball.position = Vec3(1, 2, 0.3);
  in.ball.airborne = true;
  in.friendly.push_back({.id = 4, .position = Vec2(-1, 0), .orientation = 0.5});
  in.possession = Possession::kEnemy;
  in.possessing_robot = 7;
  const auto out = to_idl(in, 9, 100);
  EXPECT_EQ(out.team(), idl::common::TEAM_COLOR_YELLOW);
  EXPECT_TRUE(out.flipped());
  EXPECT_EQ(out.sequence_number(), 9u);
  EXPECT_EQ(out.stamp().capture_unix_ns(), 42);
  EXPECT_EQ(out.stamp().camera_id(), 3u);
  EXPECT_DOUBLE_EQ(out.ball().position().y(), 2);
  EXPECT_DOUBLE_EQ(out.ball().position().z(), 0.3);
  EXPECT_TRUE(out.ball().airborne());
  EXPECT_FALSE(out.ball().in_dribbler());
  ASSERT_EQ(out.friendly().size(), 1u);
  EXPECT_DOUBLE_EQ(out.friendly()[0].pose().theta(), 0.5);
  EXPECT_EQ(out.possession(), idl::world::POSSESSION_ENEMY);
  EXPECT_TRUE(out.has_possessing_robot());
  EXPECT_EQ(out.possessing_robot(), 7u);
}

}  // namespace
}  // namespace ssl::wm
