#include "services/planner/adapter/convert.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

namespace ssl::planner {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr double kInf = std::numeric_limits<double>::infinity();

idl::world::RobotState idl_robot(std::uint32_t id, double x, double y, double theta) {
  idl::world::RobotState r;
  r.id(id);
  r.pose().x(x);
  r.pose().y(y);
  r.pose().theta(theta);
  r.velocity().x(0.5);
  r.velocity().y(-0.25);
  r.angular_velocity(1.5);
  r.visible(true);
  r.confidence(0.9);
  return r;
}

idl::world::WorldState idl_world() {
  idl::world::WorldState w;
  w.team(idl::common::TEAM_COLOR_BLUE);
  w.sequence_number(42);
  w.stamp().capture_unix_ns(1'700'000'000'000'000'000);
  w.stamp().receive_unix_ns(1'700'000'000'001'000'000);
  w.stamp().camera_id(3);
  w.stamp().frame_number(1234);
  w.publish_unix_ns(1'700'000'000'002'000'000);
  w.has_ball(true);
  w.ball().position().x(1.0);
  w.ball().position().y(-2.0);
  w.ball().position().z(0.0215);
  w.ball().velocity().x(3.0);
  w.ball().velocity().y(0.5);
  w.ball().visible(true);
  w.ball().confidence(0.8);
  w.ball().last_seen_unix_ns(1'700'000'000'000'000'000);
  w.friendly().push_back(idl_robot(0, -4.0, 0.0, 0.0));
  w.friendly().push_back(idl_robot(5, -1.0, 1.0, 0.5));
  w.enemy().push_back(idl_robot(2, 3.0, -1.0, 3.0));
  w.possession(idl::world::POSSESSION_FRIENDLY);
  w.has_possessing_robot(true);
  w.possessing_robot(5);
  return w;
}

TEST(PlannerConvert, WorldStateKeepsTheTeamFrameAndEveryField) {
  auto world = from_idl(idl_world());
  ASSERT_TRUE(world) << world.error().message;
  EXPECT_EQ(world->team, TeamColor::kBlue);
  EXPECT_FALSE(world->flipped);
  auto flipped = idl_world();
  flipped.flipped(true);
  EXPECT_TRUE(from_idl(flipped)->flipped) << "the team frame world_model derived travels with the state";
  EXPECT_EQ(world->stamp.capture_time.nanoseconds(), 1'700'000'000'000'000'000);
  EXPECT_EQ(world->stamp.receive_time.nanoseconds(), 1'700'000'000'001'000'000);
  EXPECT_EQ(world->stamp.camera_id, 3u);
  EXPECT_EQ(world->stamp.frame_number, 1234u);
  EXPECT_EQ(world->predicted_to.nanoseconds(), 1'700'000'000'002'000'000);
  ASSERT_TRUE(world->has_ball);
  EXPECT_EQ(world->ball.position, wm::Vec3(1.0, -2.0, 0.0215));
  EXPECT_EQ(world->ball.velocity, wm::Vec3(3.0, 0.5, 0.0));
  EXPECT_TRUE(world->ball.visible);
  EXPECT_DOUBLE_EQ(world->ball.confidence, 0.8);
  EXPECT_FALSE(world->ball.airborne);
  ASSERT_EQ(world->friendly.size(), 2u);
  EXPECT_EQ(world->friendly[1].id, 5u);
  EXPECT_EQ(world->friendly[1].position, wm::Vec2(-1.0, 1.0));
  EXPECT_DOUBLE_EQ(world->friendly[1].orientation, 0.5);
  EXPECT_EQ(world->friendly[1].velocity, wm::Vec2(0.5, -0.25));
  EXPECT_DOUBLE_EQ(world->friendly[1].angular_velocity, 1.5);
  EXPECT_TRUE(world->friendly[1].visible);
  ASSERT_EQ(world->enemy.size(), 1u);
  EXPECT_EQ(world->enemy[0].position, wm::Vec2(3.0, -1.0));
  EXPECT_EQ(world->possession, wm::Possession::kFriendly);
  EXPECT_EQ(world->possessing_robot, 5u);

  EXPECT_FALSE(world->ball.in_dribbler);
  auto chipped = idl_world();
  chipped.ball().position().z(0.4);
  chipped.ball().airborne(true);
  chipped.ball().in_dribbler(true);
  EXPECT_TRUE(from_idl(chipped)->ball.airborne);
  EXPECT_TRUE(from_idl(chipped)->ball.in_dribbler);
  auto no_ball = idl_world();
  no_ball.has_ball(false);
  no_ball.ball().position().x(kNaN);  // not looked at without has_ball
  ASSERT_TRUE(from_idl(no_ball));
  EXPECT_FALSE(from_idl(no_ball)->has_ball);
}

TEST(PlannerConvert, WorldStateWithNonFiniteOrImpossibleValuesIsRejected) {
  auto robot_nan = idl_world();
  robot_nan.friendly()[1].pose().x(kNaN);
  auto rejected = from_idl(robot_nan);
  ASSERT_FALSE(rejected);
  EXPECT_NE(rejected.error().message.find("friendly robot 5 pose"), std::string::npos) << rejected.error().message;

  auto enemy_inf = idl_world();
  enemy_inf.enemy()[0].angular_velocity(kInf);
  EXPECT_FALSE(from_idl(enemy_inf));

  auto ball_nan = idl_world();
  ball_nan.ball().velocity().z(kNaN);
  EXPECT_FALSE(from_idl(ball_nan));

  auto bad_id = idl_world();
  bad_id.friendly()[0].id(16);
  EXPECT_FALSE(from_idl(bad_id));

  auto no_team = idl_world();
  no_team.team(idl::common::TEAM_COLOR_UNKNOWN);
  EXPECT_FALSE(from_idl(no_team));

  auto bad_possession = idl_world();
  bad_possession.possession(static_cast<idl::world::Possession>(9));
  EXPECT_FALSE(from_idl(bad_possession));
}

TEST(PlannerConvert, RefereeStateDropsTheSideTheTeamFrameComesWithWorldState) {
  idl::referee::RefereeState r;
  r.command(idl::referee::COMMAND_STOP);
  r.has_blue_team_on_positive_half(true);
  r.blue_team_on_positive_half(true);
  r.blue().can_place_ball(false);
  auto referee = from_idl(r);
  ASSERT_TRUE(referee) << referee.error().message;
  EXPECT_EQ(referee->command, wm::RefereeCommand::kStop);
  EXPECT_FALSE(referee->blue_team_on_positive_half) << "never re-derived from the referee";
  EXPECT_FALSE(referee->blue_can_place_ball);

  r.command(static_cast<idl::referee::Command>(40));
  EXPECT_FALSE(from_idl(r)) << "rejected by the shared conversion";
}

TEST(PlannerConvert, GeometryIsTheSharedConversion) {
  idl::vision::Geometry g;
  EXPECT_FALSE(from_idl(g)) << "all zero: nothing received yet";
  auto& f = g.field();
  f.field_length(9.0);
  f.field_width(6.0);
  f.goal_width(1.0);
  f.goal_depth(0.18);
  f.penalty_area_depth(1.0);
  f.penalty_area_width(2.0);
  f.center_circle_radius(0.5);
  f.goal_center_to_penalty_mark(6.0);
  f.boundary_width_goal_line(0.3);
  auto field = from_idl(g);
  ASSERT_TRUE(field) << field.error().message;
  EXPECT_EQ(*field, FieldGeometry::division_b()) << "the division B numbers, the rest from the rulebook";
}

TEST(PlannerConvert, RobotCommandsCarryTheWorldStampAndEveryField) {
  const std::vector<RobotCommand> commands = {
      {.id = 1, .forward = 1.0, .left = -0.5, .angular = 2.0},
      {.id = 3, .forward = 0.1, .kick = KickType::kChip, .kick_speed = 4.0, .chip_angle = 0.7, .dribbler_rpm = 3000},
      {.id = 4, .kick = KickType::kFlat, .kick_speed = 6.5},
  };
  idl::common::VisionStamp stamp;
  stamp.capture_unix_ns(111);
  stamp.receive_unix_ns(222);
  stamp.camera_id(2);
  stamp.frame_number(99);
  std::uint64_t non_finite = 0;
  const auto out = to_idl(commands, TeamColor::kYellow, stamp, 17, 333, &non_finite);
  EXPECT_EQ(out.team(), idl::common::TEAM_COLOR_YELLOW);
  EXPECT_EQ(out.sequence_number(), 17u);
  EXPECT_EQ(out.stamp(), stamp);
  EXPECT_EQ(out.publish_unix_ns(), 333);
  ASSERT_EQ(out.commands().size(), 3u);
  EXPECT_EQ(out.commands()[0].id(), 1u);
  EXPECT_EQ(out.commands()[0].forward(), 1.0);
  EXPECT_EQ(out.commands()[0].left(), -0.5);
  EXPECT_EQ(out.commands()[0].angular(), 2.0);
  EXPECT_EQ(out.commands()[0].kick(), idl::robot::KICK_NONE);
  EXPECT_EQ(out.commands()[1].kick(), idl::robot::KICK_CHIP);
  EXPECT_EQ(out.commands()[1].kick_speed(), 4.0);
  EXPECT_EQ(out.commands()[1].chip_angle(), 0.7);
  EXPECT_EQ(out.commands()[1].dribbler_rpm(), 3000.0);
  EXPECT_EQ(out.commands()[2].kick(), idl::robot::KICK_FLAT);
  EXPECT_EQ(out.commands()[2].kick_speed(), 6.5);
  EXPECT_EQ(non_finite, 0u);
}

TEST(PlannerConvert, ANonFiniteCommandBecomesAStopAndIsCounted) {
  std::uint64_t non_finite = 0;
  const auto out = to_idl(RobotCommand{.id = 2, .forward = kNaN, .left = 1.0, .kick = KickType::kFlat,
                                       .kick_speed = 5.0, .dribbler_rpm = 1000},
                          &non_finite);
  EXPECT_EQ(non_finite, 1u);
  EXPECT_EQ(out.id(), 2u);
  EXPECT_EQ(out.forward(), 0.0);
  EXPECT_EQ(out.left(), 0.0);
  EXPECT_EQ(out.angular(), 0.0);
  EXPECT_EQ(out.kick(), idl::robot::KICK_NONE);
  EXPECT_EQ(out.kick_speed(), 0.0);
  EXPECT_EQ(out.dribbler_rpm(), 0.0);
  (void)to_idl(RobotCommand{.id = 2, .dribbler_rpm = kInf}, &non_finite);
  EXPECT_EQ(non_finite, 2u);
}

TEST(PlannerConvert, DebugCarriesPlayRolesTreeAndTargets) {
  PlannerOutput out;
  out.play = "stop";
  out.game_tactic = "defending/press_ball";
  out.tick = 12;
  out.roles = {{.robot_id = 0, .role = "goalkeeper", .tactic = "guard_goal", .skill = "move_to",
                .target = Vec2(-5.8, 0.1)},
               {.robot_id = 3, .role = "defender", .tactic = "stop_formation", .skill = "move_to",
                .target = Vec2(-3.0, 1.0), .path = {Vec2(-3.4, 1.0), Vec2(-3.2, 1.0), Vec2(-3.0, 1.0)},
                .tracking_error = 0.02}};
  out.tree = {{.name = "root", .depth = 0, .status = TreeNodeInfo::Status::kRunning},
              {.name = "referee_override", .depth = 1, .status = TreeNodeInfo::Status::kRunning},
              {.name = "stop", .depth = 2, .status = TreeNodeInfo::Status::kSuccess},
              {.name = "halt", .depth = 2, .status = TreeNodeInfo::Status::kFailure},
              {.name = "strategy", .depth = 1, .status = TreeNodeInfo::Status::kIdle}};
  idl::common::VisionStamp stamp;
  stamp.frame_number(5);
  const auto debug = to_idl(out, TeamColor::kBlue, stamp, 0.0004);
  EXPECT_EQ(debug.team(), idl::common::TEAM_COLOR_BLUE);
  EXPECT_EQ(debug.tick(), 12u);
  EXPECT_EQ(debug.stamp(), stamp);
  EXPECT_EQ(debug.play(), "stop");
  EXPECT_EQ(debug.game_tactic(), "defending/press_ball");
  EXPECT_EQ(debug.tick_duration(), 0.0004);
  ASSERT_EQ(debug.roles().size(), 2u);
  EXPECT_EQ(debug.roles()[0].role(), "goalkeeper");
  EXPECT_EQ(debug.roles()[1].robot_id(), 3u);
  EXPECT_EQ(debug.roles()[1].tactic(), "stop_formation");
  EXPECT_EQ(debug.roles()[1].skill(), "move_to");
  ASSERT_EQ(debug.paths().size(), 2u);
  EXPECT_EQ(debug.paths()[0].destination().x(), -5.8);
  EXPECT_EQ(debug.paths()[1].robot_id(), 3u);
  EXPECT_TRUE(debug.paths()[0].points().empty());
  EXPECT_FALSE(debug.paths()[0].has_tracking_error());
  ASSERT_EQ(debug.paths()[1].points().size(), 3u);
  EXPECT_EQ(debug.paths()[1].points()[1].x(), -3.2);
  EXPECT_TRUE(debug.paths()[1].has_tracking_error());
  EXPECT_EQ(debug.paths()[1].tracking_error(), 0.02);
  ASSERT_EQ(debug.tree().size(), 5u);
  EXPECT_EQ(debug.tree()[1].name(), "referee_override");
  EXPECT_EQ(debug.tree()[2].depth(), 2u);
  EXPECT_EQ(debug.tree()[0].status(), idl::planner::NODE_STATUS_RUNNING);
  EXPECT_EQ(debug.tree()[2].status(), idl::planner::NODE_STATUS_SUCCESS);
  EXPECT_EQ(debug.tree()[3].status(), idl::planner::NODE_STATUS_FAILURE);
  EXPECT_EQ(debug.tree()[4].status(), idl::planner::NODE_STATUS_IDLE);
}

}  // namespace
}  // namespace ssl::planner
