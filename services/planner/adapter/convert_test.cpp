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

TEST(PlannerConvert, EveryRefereeCommandMapsByName) {
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
    EXPECT_EQ(command_from_idl(command), core) << i;
    EXPECT_EQ(static_cast<std::size_t>(core), i) << "the core's order is the league's";
  }
  EXPECT_EQ(command_from_idl(static_cast<r::Command>(18)), std::nullopt);
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

TEST(PlannerConvert, RefereeStateKeepsTheVisionFrameAndOurTeamInfo) {
  auto blue = from_idl(idl_referee(), TeamColor::kBlue);
  ASSERT_TRUE(blue) << blue.error().message;
  EXPECT_EQ(blue->info.command, wm::RefereeCommand::kBallPlacementYellow);
  EXPECT_EQ(blue->info.command_counter, 7u);
  EXPECT_EQ(blue->info.designated_position, wm::Vec2(1.5, -0.5));  // vision frame, as sent
  EXPECT_FALSE(blue->info.blue_team_on_positive_half) << "the side comes with world.state (its team frame)";
  EXPECT_EQ(blue->info.next_command, wm::RefereeCommand::kDirectFreeYellow);
  EXPECT_EQ(blue->info.yellow_goalkeeper, 1u);
  EXPECT_EQ(blue->info.blue_goalkeeper, 4u);
  EXPECT_FALSE(blue->our_can_place_ball);
  EXPECT_EQ(blue->our_max_allowed_bots, 6u);

  auto yellow = from_idl(idl_referee(), TeamColor::kYellow);
  ASSERT_TRUE(yellow);
  EXPECT_TRUE(yellow->our_can_place_ball);
  EXPECT_EQ(yellow->our_max_allowed_bots, 10u);

  idl::referee::RefereeState bare;
  bare.command(idl::referee::COMMAND_STOP);
  auto stop = from_idl(bare, TeamColor::kBlue);
  ASSERT_TRUE(stop);
  EXPECT_EQ(stop->info.command, wm::RefereeCommand::kStop);
  EXPECT_FALSE(stop->info.designated_position);
  EXPECT_FALSE(stop->info.next_command);
}

TEST(PlannerConvert, RefereeStateWithNonFiniteOrUnknownValuesIsRejected) {
  auto nan = idl_referee();
  nan.designated_position().y(kNaN);
  auto rejected = from_idl(nan, TeamColor::kBlue);
  ASSERT_FALSE(rejected);
  EXPECT_NE(rejected.error().message.find("designated_position"), std::string::npos);

  auto unknown = idl_referee();
  unknown.command(static_cast<idl::referee::Command>(40));
  EXPECT_FALSE(from_idl(unknown, TeamColor::kBlue));
  auto unknown_next = idl_referee();
  unknown_next.next_command(static_cast<idl::referee::Command>(-1));
  EXPECT_FALSE(from_idl(unknown_next, TeamColor::kBlue));
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

TEST(PlannerConvert, GeometryGivesTheFieldSize) {
  auto field = from_idl(idl_geometry());
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
  EXPECT_EQ(from_idl(sent)->ball_radius, 0.02);
  EXPECT_EQ(from_idl(sent)->max_robot_radius, 0.085);
}

TEST(PlannerConvert, GeometryWithMissingOrNonFiniteDimensionsIsRejected) {
  EXPECT_FALSE(from_idl(idl::vision::Geometry{}));  // all zero: nothing received yet
  auto nan = idl_geometry();
  nan.field().field_width(kNaN);
  auto rejected = from_idl(nan);
  ASSERT_FALSE(rejected);
  EXPECT_NE(rejected.error().message.find("field_width"), std::string::npos);
  auto inf = idl_geometry();
  inf.field().ball_radius(kInf);
  EXPECT_FALSE(from_idl(inf));
  auto negative = idl_geometry();
  negative.field().goal_width(-1.0);
  EXPECT_FALSE(from_idl(negative));
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
  out.tick = 12;
  out.roles = {{.robot_id = 0, .role = "goalkeeper", .tactic = "guard_goal", .skill = "move_to",
                .target = Vec2(-5.8, 0.1)},
               {.robot_id = 3, .role = "defender", .tactic = "stop_formation", .skill = "move_to",
                .target = Vec2(-3.0, 1.0)}};
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
  EXPECT_EQ(debug.tick_duration(), 0.0004);
  ASSERT_EQ(debug.roles().size(), 2u);
  EXPECT_EQ(debug.roles()[0].role(), "goalkeeper");
  EXPECT_EQ(debug.roles()[1].robot_id(), 3u);
  EXPECT_EQ(debug.roles()[1].tactic(), "stop_formation");
  EXPECT_EQ(debug.roles()[1].skill(), "move_to");
  ASSERT_EQ(debug.paths().size(), 2u);
  EXPECT_EQ(debug.paths()[0].destination().x(), -5.8);
  EXPECT_EQ(debug.paths()[1].robot_id(), 3u);
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
