// Wire <-> core conversions of the simulator: units at the edge (mm, degrees, Unix seconds), every command
// kind, grSim's legacy packet and ER-Force's realism message.
#include "services/simulator/adapter/convert.h"

#include <gtest/gtest.h>

#include "libs/league/field_geometry.h"
#include "proto/ssl_simulation_custom_erforce_realism.pb.h"

namespace ssl::sim {
namespace {

TEST(SimConvertTest, TeleportRobotAndBallKeepUnitsAndOptionalFields) {
  SimulatorCommand command;
  auto* robot = command.mutable_control()->add_teleport_robot();
  robot->mutable_id()->set_id(3);
  robot->mutable_id()->set_team(::YELLOW);
  robot->set_x(1.5f);
  robot->set_orientation(0.5f);
  robot->set_present(true);
  command.mutable_control()->mutable_teleport_ball()->set_x(-2.0f);
  command.mutable_control()->mutable_teleport_ball()->set_teleport_safely(true);
  command.mutable_control()->set_simulation_speed(2.0f);

  std::vector<SimError> errors;
  const ControlRequest request = control_from_proto(command, errors);
  EXPECT_TRUE(errors.empty());
  ASSERT_EQ(request.robots.size(), 1u);
  EXPECT_EQ(request.robots[0].key, (RobotKey{TeamColor::kYellow, 3}));
  EXPECT_DOUBLE_EQ(*request.robots[0].x, 1.5);
  EXPECT_FALSE(request.robots[0].y.has_value());
  EXPECT_DOUBLE_EQ(*request.robots[0].orientation, 0.5);
  EXPECT_EQ(request.robots[0].present, true);
  ASSERT_TRUE(request.ball.has_value());
  EXPECT_DOUBLE_EQ(*request.ball->x, -2.0);
  EXPECT_FALSE(request.ball->y.has_value());
  EXPECT_TRUE(request.ball->teleport_safely);
  EXPECT_DOUBLE_EQ(*request.simulation_speed, 2.0);
}

TEST(SimConvertTest, RobotWithoutTeamIsAnErrorAndLeftOut) {
  SimulatorCommand command;
  command.mutable_control()->add_teleport_robot()->mutable_id()->set_id(1);
  std::vector<SimError> errors;
  const ControlRequest request = control_from_proto(command, errors);
  EXPECT_TRUE(request.robots.empty());
  ASSERT_EQ(errors.size(), 1u);
  EXPECT_EQ(errors[0].code, "UNKNOWN_TEAM");
}

TEST(SimConvertTest, RobotCommandsConvertKickAngleFromDegreesAndEveryMoveKind) {
  RobotControl control;
  auto* local = control.add_robot_commands();
  local->set_id(1);
  local->mutable_move_command()->mutable_local_velocity()->set_forward(1.0f);
  local->mutable_move_command()->mutable_local_velocity()->set_left(-0.5f);
  local->mutable_move_command()->mutable_local_velocity()->set_angular(2.0f);
  local->set_kick_speed(4.0f);
  local->set_kick_angle(45.0f);
  local->set_dribbler_speed(1500.0f);
  auto* global = control.add_robot_commands();
  global->set_id(2);
  global->mutable_move_command()->mutable_global_velocity()->set_x(0.25f);
  auto* wheels = control.add_robot_commands();
  wheels->set_id(3);
  wheels->mutable_move_command()->mutable_wheel_velocity()->set_front_right(1.0f);
  wheels->mutable_move_command()->mutable_wheel_velocity()->set_back_right(2.0f);
  wheels->mutable_move_command()->mutable_wheel_velocity()->set_back_left(3.0f);
  wheels->mutable_move_command()->mutable_wheel_velocity()->set_front_left(4.0f);
  control.add_robot_commands()->set_id(16);  // out of range

  std::vector<SimError> errors;
  const auto commands = commands_from_proto(control, errors);
  ASSERT_EQ(commands.size(), 3u);
  ASSERT_EQ(errors.size(), 1u);
  EXPECT_EQ(errors[0].code, "INVALID_ROBOT_ID");

  EXPECT_EQ(commands[0].command.move, RobotCommand::Move::kLocalVelocity);
  EXPECT_DOUBLE_EQ(commands[0].command.velocity.x(), 1.0);
  EXPECT_DOUBLE_EQ(commands[0].command.velocity.y(), -0.5);
  EXPECT_DOUBLE_EQ(commands[0].command.velocity.z(), 2.0);
  EXPECT_DOUBLE_EQ(commands[0].command.kick_speed, 4.0);
  EXPECT_NEAR(commands[0].command.kick_angle, M_PI / 4, 1e-6);
  EXPECT_DOUBLE_EQ(commands[0].command.dribbler_rpm, 1500.0);
  EXPECT_EQ(commands[1].command.move, RobotCommand::Move::kGlobalVelocity);
  EXPECT_DOUBLE_EQ(commands[1].command.velocity.x(), 0.25);
  EXPECT_EQ(commands[2].command.move, RobotCommand::Move::kWheelVelocity);
  EXPECT_EQ(commands[2].command.wheel_velocity, (std::array<double, 4>{1, 2, 3, 4}));
}

TEST(SimConvertTest, GrsimPacketConvertsHeadingDegreesAndKickComponents) {
  grSim_Packet packet;
  packet.mutable_commands()->set_timestamp(0);
  packet.mutable_commands()->set_isteamyellow(true);
  auto* command = packet.mutable_commands()->add_robot_commands();
  command->set_id(4);
  command->set_kickspeedx(3.0f);
  command->set_kickspeedz(4.0f);
  command->set_veltangent(1.0f);
  command->set_velnormal(0.5f);
  command->set_velangular(-1.0f);
  command->set_spinner(true);
  command->set_wheelsspeed(false);
  auto* robot = packet.mutable_replacement()->add_robots();
  robot->set_x(1);
  robot->set_y(2);
  robot->set_dir(90);
  robot->set_id(5);
  robot->set_yellowteam(false);

  std::vector<SimError> errors;
  const GrsimInput input = grsim_from_proto(packet, errors);
  EXPECT_TRUE(errors.empty());
  EXPECT_EQ(input.team, TeamColor::kYellow);
  ASSERT_EQ(input.commands.size(), 1u);
  EXPECT_DOUBLE_EQ(input.commands[0].command.kick_speed, 5.0);
  EXPECT_NEAR(input.commands[0].command.kick_angle, std::atan2(4.0, 3.0), 1e-9);
  EXPECT_GT(input.commands[0].command.dribbler_rpm, 0);
  ASSERT_EQ(input.control.robots.size(), 1u);
  EXPECT_EQ(input.control.robots[0].key, (RobotKey{TeamColor::kBlue, 5}));
  EXPECT_NEAR(*input.control.robots[0].orientation, M_PI / 2, 1e-9);
  EXPECT_EQ(input.control.robots[0].present, true);
}

TEST(SimConvertTest, ErforceRealismArrivesAsAnyAndUnsupportedFieldsAreReported) {
  RealismConfigErForce erforce;
  erforce.set_stddev_ball_p(0.003f);
  erforce.set_missing_ball_detections(0.1f);
  erforce.set_vision_delay(12'000'000);
  erforce.set_robot_command_loss(0.2f);
  SimulatorCommand command;
  command.mutable_config()->mutable_realism_config()->add_custom()->PackFrom(erforce);

  std::vector<SimError> errors;
  const ControlRequest request = control_from_proto(command, errors);
  ASSERT_TRUE(request.realism.has_value());
  EXPECT_NEAR(request.realism->ball_position_stddev, 0.003, 1e-9);
  EXPECT_NEAR(request.realism->ball_missing_probability, 0.1, 1e-7);
  EXPECT_NEAR(request.realism->vision_delay, 0.012, 1e-12);
  ASSERT_EQ(errors.size(), 1u);
  EXPECT_EQ(errors[0].code, "UNSUPPORTED_REALISM");
  EXPECT_NE(errors[0].message.find("robot_command_loss"), std::string::npos);
}

TEST(SimConvertTest, DetectionFrameIsSentInMillimetresAndUnixSeconds) {
  DetectionFrame frame;
  frame.camera_id = 2;
  frame.frame_number = 17;
  frame.capture_time = time::Timestamp::from_milliseconds(1500);
  frame.sent_time = time::Timestamp::from_milliseconds(1510);
  BallDetection ball{};
  ball.x = 1.25;
  ball.y = -0.5;
  ball.confidence = 0.9f;
  frame.balls.push_back(ball);
  RobotDetection robot{};
  robot.robot_id = 7;
  robot.x = -3.0;
  robot.y = 0.001;
  robot.orientation = 1.0;
  robot.height = 0.143;
  robot.confidence = 1.0f;
  frame.robots_blue.push_back(robot);

  const auto unix_offset = std::chrono::seconds(1'700'000'000);
  const SSL_DetectionFrame wire = detection_to_proto(frame, unix_offset);
  EXPECT_TRUE(wire.IsInitialized());
  EXPECT_EQ(wire.camera_id(), 2u);
  EXPECT_EQ(wire.frame_number(), 17u);
  EXPECT_DOUBLE_EQ(wire.t_capture(), 1'700'000'001.5);
  EXPECT_NEAR(wire.t_sent() - wire.t_capture(), 0.010, 1e-6);
  ASSERT_EQ(wire.balls_size(), 1);
  EXPECT_FLOAT_EQ(wire.balls(0).x(), 1250.0f);
  EXPECT_FLOAT_EQ(wire.balls(0).y(), -500.0f);
  EXPECT_FALSE(wire.balls(0).has_z());
  ASSERT_EQ(wire.robots_blue_size(), 1);
  EXPECT_EQ(wire.robots_blue(0).robot_id(), 7u);
  EXPECT_FLOAT_EQ(wire.robots_blue(0).x(), -3000.0f);
  EXPECT_NEAR(wire.robots_blue(0).y(), 1.0f, 1e-3);
  EXPECT_FLOAT_EQ(wire.robots_blue(0).height(), 143.0f);
  EXPECT_EQ(wire.robots_yellow_size(), 0);
}

TEST(SimConvertTest, GeometryRoundTripsThroughTheWireInMillimetres) {
  GeometryData geometry;
  geometry.field = FieldGeometry::division_b();
  geometry.ball_radius = 0.0215;
  geometry.max_robot_radius = 0.09;
  FieldLine line;
  line.name = "TopTouchLine";
  line.p1 = Vec2(-4.5, 3.0);
  line.p2 = Vec2(4.5, 3.0);
  line.thickness = 0.01;
  line.type = FieldShapeType::kTopTouchLine;
  geometry.lines.push_back(line);

  const SSL_GeometryData wire = geometry_to_proto(geometry);
  EXPECT_TRUE(wire.IsInitialized()) << wire.InitializationErrorString();
  EXPECT_EQ(wire.field().field_length(), 9000);
  EXPECT_EQ(wire.field().field_width(), 6000);
  EXPECT_EQ(wire.field().goal_width(), 1000);
  EXPECT_EQ(wire.field().penalty_area_depth(), 1000);
  EXPECT_FLOAT_EQ(wire.field().ball_radius(), 21.5f);
  ASSERT_EQ(wire.field().field_lines_size(), 1);
  EXPECT_FLOAT_EQ(wire.field().field_lines(0).p1().y(), 3000.0f);
  EXPECT_EQ(wire.field().field_lines(0).type(), TopTouchLine);

  const FieldGeometry back = league::field_from_proto(wire.field());
  EXPECT_DOUBLE_EQ(back.field_length, 9.0);
  EXPECT_DOUBLE_EQ(back.field_width, 6.0);
  EXPECT_DOUBLE_EQ(back.goal_width, 1.0);
  EXPECT_DOUBLE_EQ(back.goal_center_to_penalty_mark, 6.0);
}

}  // namespace
}  // namespace ssl::sim
