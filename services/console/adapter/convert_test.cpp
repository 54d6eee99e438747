#include "services/console/adapter/convert.h"

#include <gtest/gtest.h>

#include "proto/ssl_simulation_control.pb.h"

namespace ssl::console {
namespace {

TEST(ConsoleConvert, WorldStateKeepsItsTeamFrameAndColours) {
  idl::world::WorldState world;
  world.team(idl::common::TEAM_COLOR_YELLOW);
  world.flipped(true);
  world.has_ball(true);
  idl::world::BallState ball;
  idl::common::Vec3 position;
  position.x(1);
  position.y(2);
  position.z(0.1);
  ball.position(position);
  world.ball(ball);
  idl::world::RobotState ours;
  ours.id(3);
  idl::common::Pose2 pose;
  pose.x(-1);
  pose.y(0.5);
  pose.theta(0.25);
  ours.pose(pose);
  world.friendly({ours});
  idl::world::RobotState theirs;
  theirs.id(7);
  world.enemy({theirs});
  world.possession(idl::world::POSSESSION_ENEMY);
  const TeamWorld converted = from_idl(world);
  EXPECT_TRUE(converted.flipped);
  ASSERT_TRUE(converted.ball);
  EXPECT_EQ(converted.ball->position, geom::Vec2(1, 2));
  EXPECT_DOUBLE_EQ(converted.ball->height, 0.1);
  ASSERT_EQ(converted.robots.size(), 2u);
  EXPECT_EQ(converted.robots[0].team, TeamColor::kYellow);
  EXPECT_EQ(converted.robots[0].position, geom::Vec2(-1, 0.5));
  EXPECT_DOUBLE_EQ(converted.robots[0].heading, 0.25);
  EXPECT_EQ(converted.robots[1].team, TeamColor::kBlue);
  EXPECT_EQ(converted.robots[1].id, 7u);
  EXPECT_EQ(converted.possession, Possession::kTheirs);
}

TEST(ConsoleConvert, OperatorCommandsCarryTheLeagueCommand) {
  const auto command = to_idl(RefereeAction{.command = referee::Command::kBallPlacementYellow,
                                            .designated = geom::Vec2(1, -1)},
                              "console (127.0.0.1)", 42);
  EXPECT_EQ(command.command(), idl::referee::COMMAND_BALL_PLACEMENT_YELLOW);
  EXPECT_TRUE(command.has_designated_position());
  EXPECT_DOUBLE_EQ(command.designated_position().y(), -1);
  EXPECT_EQ(command.author(), "console (127.0.0.1)");
  EXPECT_EQ(command.stamp_unix_ns(), 42);
}

TEST(ConsoleConvert, PlacingIsTheSimulationProtocolsTeleport) {
  ::SimulatorCommand ball;
  ASSERT_TRUE(ball.ParseFromString(simulator_command({.object = PlaceObject::kBall, .position = {1.5, -2}}, 0)));
  ASSERT_TRUE(ball.control().has_teleport_ball());
  EXPECT_FLOAT_EQ(ball.control().teleport_ball().x(), 1.5f);
  EXPECT_FLOAT_EQ(ball.control().teleport_ball().y(), -2.0f);
  EXPECT_FLOAT_EQ(ball.control().teleport_ball().vx(), 0.0f);
  EXPECT_EQ(ball.control().teleport_robot_size(), 0);

  ::SimulatorCommand robot;
  ASSERT_TRUE(robot.ParseFromString(simulator_command(
      {.object = PlaceObject::kRobot, .team = TeamColor::kBlue, .id = 5, .position = {-1, 1}}, 1.25)));
  ASSERT_EQ(robot.control().teleport_robot_size(), 1);
  const ::TeleportRobot& teleport = robot.control().teleport_robot(0);
  EXPECT_EQ(teleport.id().id(), 5u);
  EXPECT_EQ(teleport.id().team(), ::BLUE);
  EXPECT_FLOAT_EQ(teleport.orientation(), 1.25f);
  EXPECT_TRUE(teleport.present());
  EXPECT_FALSE(robot.control().has_teleport_ball());
}

}  // namespace
}  // namespace ssl::console
