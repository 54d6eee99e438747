#include "services/console/core/actions.h"

#include <gtest/gtest.h>

namespace ssl::console {
namespace {

const FieldGeometry kField = FieldGeometry::division_b();  // 9 x 6 m, walls 0.3 m beyond the lines

TEST(ConsoleActions, RefereeCommandsByTheirLeagueNames) {
  auto stop = parse_referee_action(R"({"command":"STOP"})", kField);
  ASSERT_TRUE(stop) << stop.error().message;
  EXPECT_EQ(stop->command, referee::Command::kStop);
  EXPECT_FALSE(stop->designated);
  auto place = parse_referee_action(R"({"command":"BALL_PLACEMENT_BLUE","designated":[1.5,-2]})", kField);
  ASSERT_TRUE(place) << place.error().message;
  EXPECT_EQ(place->command, referee::Command::kBallPlacementBlue);
  EXPECT_EQ(*place->designated, geom::Vec2(1.5, -2));
  for (int i = 0; i <= static_cast<int>(referee::Command::kBallPlacementBlue); ++i) {
    const auto command = static_cast<referee::Command>(i);
    EXPECT_EQ(parse_command(referee::to_string(command)), command);
  }
}

TEST(ConsoleActions, BadRefereeBodiesAreRefusedWithTheReason) {
  EXPECT_NE(parse_referee_action("not json", kField).error().message.find("not JSON"), std::string::npos);
  EXPECT_NE(parse_referee_action("[1]", kField).error().message.find("object"), std::string::npos);
  EXPECT_NE(parse_referee_action("{}", kField).error().message.find("'command' is missing"), std::string::npos);
  EXPECT_NE(parse_referee_action(R"({"command":"COMMAND_STOP"})", kField).error().message.find("unknown referee command"),
            std::string::npos);
  EXPECT_NE(parse_referee_action(R"({"command":1})", kField).error().message.find("must be a string"), std::string::npos);
  EXPECT_NE(parse_referee_action(R"({"command":"STOP","designated":[1]})", kField).error().message.find("[x, y]"),
            std::string::npos);
  // Off the carpet: 4.5 + 0.3 m is the wall.
  EXPECT_NE(parse_referee_action(R"({"command":"STOP","designated":[4.81,0]})", kField).error().message.find("off the field"),
            std::string::npos);
  EXPECT_TRUE(parse_referee_action(R"({"command":"STOP","designated":[4.8,3.3]})", kField));
}

TEST(ConsoleActions, EstopNeedsABoolean) {
  auto on = parse_estop_action(R"({"engaged":true,"reason":"robot on fire"})");
  ASSERT_TRUE(on);
  EXPECT_TRUE(on->engaged);
  EXPECT_EQ(on->reason, "robot on fire");
  EXPECT_FALSE(parse_estop_action(R"({"engaged":"yes"})"));
  EXPECT_FALSE(parse_estop_action(R"({})"));
  EXPECT_FALSE(parse_estop_action(R"({"engaged":false,"reason":")" + std::string(kMaxTextLength + 1, 'x') + R"("})"));
}

TEST(ConsoleActions, PlacingTheBallOrARobot) {
  auto ball = parse_place_action(R"({"object":"ball","x":1,"y":2})", kField);
  ASSERT_TRUE(ball) << ball.error().message;
  EXPECT_EQ(ball->object, PlaceObject::kBall);
  EXPECT_EQ(ball->position, geom::Vec2(1, 2));
  auto robot = parse_place_action(R"({"object":"robot","team":"yellow","id":3,"x":-1,"y":0.5,"a":1.5})", kField);
  ASSERT_TRUE(robot) << robot.error().message;
  EXPECT_EQ(robot->team, TeamColor::kYellow);
  EXPECT_EQ(robot->id, 3u);
  EXPECT_EQ(robot->heading, 1.5);
  EXPECT_FALSE(parse_place_action(R"({"object":"robot","team":"red","id":3,"x":0,"y":0})", kField));
  EXPECT_FALSE(parse_place_action(R"({"object":"robot","team":"blue","id":16,"x":0,"y":0})", kField));
  EXPECT_FALSE(parse_place_action(R"({"object":"robot","team":"blue","id":-1,"x":0,"y":0})", kField));
  EXPECT_FALSE(parse_place_action(R"({"object":"goal","x":0,"y":0})", kField));
  EXPECT_FALSE(parse_place_action(R"({"object":"ball","x":0})", kField));
  EXPECT_FALSE(parse_place_action(R"({"object":"ball","x":0,"y":9})", kField));
  EXPECT_FALSE(parse_place_action(R"({"object":"ball","x":1e999,"y":0})", kField));  // parses as inf
}

TEST(ConsoleActions, ParameterBodies) {
  auto set = parse_param_action(R"({"target":"planner/blue","key":"skills.max_speed","value":"2.5"})");
  ASSERT_TRUE(set) << set.error().message;
  EXPECT_EQ(set->key, "skills.max_speed");
  EXPECT_FALSE(parse_param_action(R"({"target":"","key":"k","value":"1"})"));
  EXPECT_FALSE(parse_param_action(R"({"target":"planner/blue","key":"k","value":1})"));
  EXPECT_TRUE(parse_param_save_action(R"({"target":"planner/blue"})"));
  EXPECT_FALSE(parse_param_save_action(R"({"target":""})"));
}

TEST(ConsoleAccess, LoopbackWithoutATokenMayAct) {
  const AccessPolicy policy("127.0.0.1", "");
  EXPECT_TRUE(policy.allows(""));
  EXPECT_TRUE(policy.allows("anything"));
  EXPECT_TRUE(policy.operator_possible());
}

TEST(ConsoleAccess, AnotherAddressWithoutATokenIsReadOnly) {
  const AccessPolicy policy("0.0.0.0", "");
  EXPECT_FALSE(policy.allows(""));
  EXPECT_FALSE(policy.allows("guess"));
  EXPECT_FALSE(policy.operator_possible());
}

TEST(ConsoleAccess, WithATokenExactlyThatTokenMayAct) {
  for (const char* bind : {"0.0.0.0", "127.0.0.1"}) {
    const AccessPolicy policy(bind, "s3cret");
    EXPECT_TRUE(policy.allows("s3cret")) << bind;
    EXPECT_FALSE(policy.allows("")) << bind;
    EXPECT_FALSE(policy.allows("s3cre")) << bind;
    EXPECT_FALSE(policy.allows("s3cret!")) << bind;
    EXPECT_FALSE(policy.allows("S3cret")) << bind;
  }
  EXPECT_TRUE(is_loopback("127.0.0.2"));
  EXPECT_TRUE(is_loopback("localhost"));
  EXPECT_FALSE(is_loopback("198.18.0.1"));
}

}  // namespace
}  // namespace ssl::console
