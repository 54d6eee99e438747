#include "services/console/core/console_state.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

namespace ssl::console {
namespace {

using nlohmann::json;
using referee::Command;

const time::Timestamp kT0 = time::Timestamp::from_milliseconds(1'700'000'000'000);

time::Timestamp at(double seconds) { return kT0 + time::duration_from_seconds(seconds); }

referee::RefereeState referee_state(Command command, std::uint32_t counter) {
  referee::RefereeState state;
  state.source = referee::RefereeSource::kBuiltin;
  state.command = command;
  state.command_counter = counter;
  state.stage = referee::Stage::kNormalFirstHalf;
  state.stage_time_left = std::chrono::seconds(300);
  state.yellow.name = "Yellow";
  state.blue.name = "Blue";
  return state;
}

CameraView camera_with_ball(geom::Vec2 ball) {
  CameraView camera{.camera_id = 0};
  camera.balls.push_back(ball);
  camera.robots.push_back({.team = TeamColor::kBlue, .id = 2, .position = {1, 1}, .heading = 0.5});
  return camera;
}

TEST(ConsoleState, AFlippedTeamsWorldIsDrawnInTheVisionFrame) {
  ConsoleState state;
  TeamWorld world{.flipped = true};
  world.ball = BallView{.position = {1.0, 0.5}, .velocity = {2.0, 0.0}};
  world.robots.push_back({.team = TeamColor::kYellow, .id = 4, .position = {-3.0, 1.0}, .heading = 0.0, .velocity = {1, 0}});
  world.possession = Possession::kOurs;
  state.on_world(TeamColor::kYellow, world, at(0));
  const json frame = state.frame_json(at(0.25));
  const json& yellow = frame["teams"]["yellow"];
  EXPECT_TRUE(frame["teams"]["blue"].is_null());
  EXPECT_DOUBLE_EQ(yellow["age"].get<double>(), 0.25);
  EXPECT_DOUBLE_EQ(yellow["ball"]["x"].get<double>(), -1.0);
  EXPECT_DOUBLE_EQ(yellow["ball"]["y"].get<double>(), -0.5);
  EXPECT_DOUBLE_EQ(yellow["ball"]["vx"].get<double>(), -2.0);
  const json& robot = yellow["robots"][0];
  EXPECT_EQ(robot["team"], "yellow");
  EXPECT_EQ(robot["id"], 4);
  EXPECT_DOUBLE_EQ(robot["x"].get<double>(), 3.0);
  EXPECT_DOUBLE_EQ(robot["y"].get<double>(), -1.0);
  EXPECT_NEAR(std::abs(robot["a"].get<double>()), std::numbers::pi, 1e-12);
  EXPECT_EQ(yellow["possession"], "yellow");
}

TEST(ConsoleState, PathsAndTreesOfTheDebugAreInTheVisionFrameToo) {
  ConsoleState state;
  state.on_world(TeamColor::kBlue, TeamWorld{.flipped = true}, at(0));
  TeamDebug debug{.play = "kickoff", .tactic = "attack", .tick_duration = 0.0004};
  debug.paths.push_back({.id = 1, .points = {{0, 0}, {1, 2}}, .destination = {2, 2}});
  debug.tree.push_back({"root", 0, NodeStatus::kRunning});
  debug.tree.push_back({"shoot", 1, NodeStatus::kFailure});
  debug.roles.push_back({1, "attacker", "shoot", "kick"});
  state.on_debug(TeamColor::kBlue, debug);
  const json blue = state.frame_json(at(0))["teams"]["blue"];
  EXPECT_EQ(blue["paths"][0]["points"][1], json::array({-1.0, -2.0}));
  EXPECT_EQ(blue["paths"][0]["destination"], json::array({-2.0, -2.0}));
  EXPECT_EQ(blue["tree"][1]["status"], "failure");
  EXPECT_EQ(blue["tree"][1]["depth"], 1);
  EXPECT_EQ(blue["roles"][0]["role"], "attacker");
  EXPECT_DOUBLE_EQ(blue["tick_ms"].get<double>(), 0.4);
}

TEST(ConsoleState, NotANumberNeverReachesThePage) {
  ConsoleState state;
  CameraView camera{.camera_id = 1};
  camera.balls.emplace_back(std::nan(""), 1.0);
  state.on_vision(camera, at(0));
  const json frame = state.frame_json(at(0));
  EXPECT_TRUE(frame["vision"]["balls"][0]["x"].is_null());
  EXPECT_TRUE(json::accept(frame.dump())) << "the frame is not valid JSON";
}

TEST(ConsoleState, CommandsGoalsAndStatusMessagesAreLoggedOnceEach) {
  ConsoleState state;
  EXPECT_TRUE(state.on_referee(referee_state(Command::kHalt, 0), at(0)));
  EXPECT_FALSE(state.on_referee(referee_state(Command::kHalt, 0), at(0.1)));  // the same again
  referee::RefereeState stop = referee_state(Command::kStop, 1);
  EXPECT_TRUE(state.on_referee(stop, at(1)));
  referee::RefereeState goal = referee_state(Command::kStop, 1);
  goal.blue.score = 1;
  goal.status_message = "Goal for blue";
  EXPECT_TRUE(state.on_referee(goal, at(2)));
  EXPECT_FALSE(state.on_referee(goal, at(2.1)));
  referee::RefereeState placement = goal;
  placement.command = Command::kBallPlacementYellow;
  placement.command_counter = 2;
  placement.designated_position = geom::Vec2(1.25, -0.5);
  EXPECT_TRUE(state.on_referee(placement, at(3)));

  const std::vector<LogEntry> entries = state.take_new_entries();
  ASSERT_EQ(entries.size(), 5u);
  EXPECT_EQ(entries[0].text, "HALT");
  EXPECT_EQ(entries[1].text, "STOP");
  EXPECT_EQ(entries[2].kind, LogKind::kGoal);
  EXPECT_EQ(entries[2].team, TeamColor::kBlue);
  EXPECT_EQ(entries[2].text, "goal blue: yellow 0 : 1 blue");
  EXPECT_EQ(entries[3].kind, LogKind::kStatus);
  EXPECT_EQ(entries[4].text, "BALL_PLACEMENT_YELLOW to (1.25, -0.50)");
  EXPECT_EQ(entries[4].team, TeamColor::kYellow);
  EXPECT_TRUE(state.take_new_entries().empty());
  // The page's log: newest first.
  EXPECT_EQ(state.log_json()["entries"][0]["text"], "BALL_PLACEMENT_YELLOW to (1.25, -0.50)");
}

TEST(ConsoleState, TheLogKeepsTheLastTwenty) {
  ConsoleState state;
  for (int i = 0; i < 25; ++i) state.on_operator("action " + std::to_string(i), at(i));
  const json entries = state.log_json()["entries"];
  ASSERT_EQ(entries.size(), EventLog::kCapacity);
  EXPECT_EQ(entries.front()["text"], "action 24");
  EXPECT_EQ(entries.back()["text"], "action 5");
}

TEST(ConsoleState, FoulsAreToldApartFromOtherEvents) {
  ConsoleState state;
  state.on_referee_event({.event = {.type = referee::GameEventType::kBotCrashUnique, .by_team = referee::Team::kYellow,
                                    .by_bot = 3u}},
                         at(0));
  state.on_referee_event({.event = {.type = referee::GameEventType::kBallLeftFieldTouchLine}}, at(1));
  const std::vector<LogEntry> entries = state.take_new_entries();
  ASSERT_EQ(entries.size(), 2u);
  EXPECT_EQ(entries[0].kind, LogKind::kFoul);
  EXPECT_EQ(entries[0].text, "BOT_CRASH_UNIQUE by yellow 3");
  EXPECT_EQ(entries[0].team, TeamColor::kYellow);
  EXPECT_EQ(entries[1].kind, LogKind::kEvent);
}

TEST(ConsoleState, KeepOutZonesFollowTheCommand) {
  ConsoleState state;
  state.on_geometry(FieldGeometry::division_b());
  state.on_vision(camera_with_ball({1.0, 2.0}), at(0));
  const double radius = 0.5 + 0.09;

  state.on_referee(referee_state(Command::kStop, 1), at(0));
  json zones = state.referee_json()["keep_out"];
  ASSERT_EQ(zones.size(), 1u);
  EXPECT_EQ(zones[0]["kind"], "circle");
  EXPECT_EQ(zones[0]["team"], "both");
  EXPECT_EQ(zones[0]["center"], json::array({1.0, 2.0}));
  EXPECT_DOUBLE_EQ(zones[0]["radius"].get<double>(), radius);

  state.on_referee(referee_state(Command::kDirectFreeBlue, 2), at(1));
  zones = state.referee_json()["keep_out"];
  ASSERT_EQ(zones.size(), 1u);
  EXPECT_EQ(zones[0]["team"], "yellow");

  referee::RefereeState placement = referee_state(Command::kBallPlacementBlue, 3);
  placement.designated_position = geom::Vec2(-2, 0);
  state.on_referee(placement, at(2));
  zones = state.referee_json()["keep_out"];
  ASSERT_EQ(zones.size(), 1u);
  EXPECT_EQ(zones[0]["kind"], "stadium");
  EXPECT_EQ(zones[0]["a"], json::array({1.0, 2.0}));
  EXPECT_EQ(zones[0]["b"], json::array({-2.0, 0.0}));
  EXPECT_EQ(zones[0]["team"], "yellow");

  state.on_referee(referee_state(Command::kNormalStart, 4), at(3));
  EXPECT_TRUE(state.referee_json()["keep_out"].empty());
}

TEST(ConsoleState, HealthAgesAndRobotWarnings) {
  ConsoleState state({.battery_low_volts = 14.0, .link_low_quality = 0.5});
  state.on_health({.service = "planner/blue", .level = HealthLevel::kWarn, .latency_p99 = 0.002}, at(0));
  state.on_feedback({.team = TeamColor::kBlue, .id = 1, .battery_voltage = 13.9, .link_quality = 0.9}, at(0));
  state.on_feedback({.team = TeamColor::kYellow, .id = 2, .battery_voltage = 15.0, .link_quality = 0.4}, at(0));
  state.on_feedback({.team = TeamColor::kYellow, .id = 3}, at(0));  // the simulator reports neither
  const json health = state.health_json(at(4));
  EXPECT_EQ(health["services"][0]["level"], "warn");
  EXPECT_DOUBLE_EQ(health["services"][0]["age_s"].get<double>(), 4.0);
  EXPECT_DOUBLE_EQ(health["services"][0]["latency_p99_ms"].get<double>(), 2.0);
  const json robots = health["robots"];
  ASSERT_EQ(robots.size(), 3u);
  EXPECT_TRUE(robots[0]["battery_low"]);
  EXPECT_FALSE(robots[0]["link_low"]);
  EXPECT_FALSE(robots[1]["battery_low"]);
  EXPECT_TRUE(robots[1]["link_low"]);
  EXPECT_TRUE(robots[2]["battery_v"].is_null());
  EXPECT_FALSE(robots[2]["battery_low"]);
  EXPECT_FALSE(health["estop"]["engaged"]);
}

TEST(ConsoleState, EstopChangesAreLogged) {
  ConsoleState state;
  state.on_estop({.engaged = true, .source = "console", .reason = "space bar"}, at(0));
  state.on_estop({.engaged = true, .source = "console", .reason = "space bar"}, at(0.5));
  state.on_estop({.engaged = false, .source = "sslctl"}, at(1));
  const std::vector<LogEntry> entries = state.take_new_entries();
  ASSERT_EQ(entries.size(), 2u);
  EXPECT_EQ(entries[0].text, "e-stop engaged by console: space bar");
  EXPECT_EQ(entries[1].text, "e-stop released by sslctl");
  EXPECT_TRUE(state.health_json(at(1))["estop"]["engaged"] == false);
}

TEST(ConsoleState, TheProfilePanelShowsEveryRuleAsAPill) {
  ConsoleState state;
  EXPECT_TRUE(state.hello_json(true, false)["profile"].is_null());
  referee::RefereeProfile profile;
  profile.name = "strict_ai";
  profile.rules.goal_detection.enabled = true;
  profile.rules.crash.enabled = false;
  state.set_profile(profile);
  const json hello = state.hello_json(false, true);
  EXPECT_FALSE(hello["operator"]);
  EXPECT_TRUE(hello["simulator"]);
  EXPECT_EQ(hello["profile"]["name"], "strict_ai");
  int pills = 0;
  bool goal_on = false;
  bool crash_off = false;
  for (const json& section : hello["profile"]["sections"]) {
    for (const json& field : section["fields"]) {
      if (!field.contains("on")) continue;
      ++pills;
      if (section["title"] == "Goal detection" && field["label"] == "enabled") goal_on = field["on"];
      if (field["label"] == "crash") crash_off = !field["on"].get<bool>();
    }
  }
  EXPECT_GE(pills, 16);  // every rule of RefereeRules
  EXPECT_TRUE(goal_on);
  EXPECT_TRUE(crash_off);
}

TEST(ConsoleState, TheReportCountsScoreFoulsAndPlacements) {
  ConsoleState state;
  state.on_referee(referee_state(Command::kNormalStart, 1), at(0));
  referee::RefereeState placement = referee_state(Command::kBallPlacementBlue, 2);
  placement.yellow.foul_counter = 2;
  state.on_referee(placement, at(10));
  referee::RefereeState free_kick = referee_state(Command::kDirectFreeBlue, 3);
  free_kick.yellow.foul_counter = 2;
  free_kick.blue.score = 1;
  free_kick.game_events.push_back({.id = "p1", .type = referee::GameEventType::kPlacementSucceeded});
  state.on_referee(free_kick, at(20));
  const json report = state.report_json();
  EXPECT_DOUBLE_EQ(report["duration_s"].get<double>(), 20.0);
  EXPECT_EQ(report["score"]["blue"], 1);
  EXPECT_EQ(report["fouls"]["yellow"], 2);
  EXPECT_EQ(report["placements"]["tried"], 1);
  EXPECT_EQ(report["placements"]["succeeded"], 1);
  EXPECT_DOUBLE_EQ(report["in_play_share"].get<double>(), 0.5);
}

TEST(ConsoleState, ParametersAreListedPerTargetWithTheLastAnswer) {
  ConsoleState state;
  ParameterStateView planner{.target = "planner/blue"};
  planner.params.push_back({.key = "planner.limits.max_speed", .type = "number", .value = "3", .min = 0.1, .max = 10.0,
                            .unit = "m/s", .doc = "normal play"});
  EXPECT_TRUE(state.on_parameters(planner));
  EXPECT_FALSE(state.on_parameters(planner));  // nothing new
  planner.revision = 7;
  planner.accepted = false;
  planner.reason = "out of range";
  EXPECT_TRUE(state.on_parameters(planner));
  const json params = state.params_json()["params"];
  ASSERT_EQ(params.size(), 1u);
  EXPECT_EQ(params[0]["target"], "planner/blue");
  EXPECT_EQ(params[0]["value"], "3");
  EXPECT_DOUBLE_EQ(params[0]["max"].get<double>(), 10.0);
  EXPECT_EQ(params[0]["status"], "rejected");
  EXPECT_EQ(params[0]["reason"], "out of range");
  EXPECT_EQ(params[0]["revision"], 7);
  ASSERT_NE(state.parameters("planner/blue"), nullptr);
  EXPECT_EQ(state.parameters("world_model/blue"), nullptr);
}

}  // namespace
}  // namespace ssl::console
