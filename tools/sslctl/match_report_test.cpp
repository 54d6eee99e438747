// Tests of the match report: the pure builder with scripted referee states at explicit times, and
// `sslctl match report` on an SSL log file (the function and the binary) and live on loopback multicast
// (ports 25400-25499).
#include <gtest/gtest.h>

#include <chrono>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <optional>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "libs/league/decode.h"
#include "libs/league/log_file.h"
#include "libs/net/multicast.h"
#include "services/referee_gateway/adapter/convert.h"
#include "tests/support/process.h"
#include "tools/sslctl/commands.h"
#include "tools/sslctl/match_report.h"

namespace ssl::sslctl {
namespace {

namespace fs = std::filesystem;
using geom::Vec2;
using referee::Command;
using referee::GameEvent;
using referee::GameEventType;
using referee::RefereeState;
using referee::Stage;
using referee::Team;

const time::Timestamp kStart = time::Timestamp::from_seconds(1'700'000'000.0);
time::Timestamp at(double seconds) { return kStart + time::duration_from_seconds(seconds); }

/// A small match: STOP, kickoff, play, a goal (its event repeated in later packets), half time with the
/// side swap, the second half, the final whistle.
struct Script {
  RefereeState state;
  std::vector<std::pair<double, RefereeState>> samples;

  Script() {
    state.source_identifier = "builtin:test";
    state.yellow.name = "Yellow FC";
    state.blue.name = "Blue FC";
    state.blue_team_on_positive_half = false;
  }
  void command(double t, Command command, Stage stage) {
    state.command = command;
    state.stage = stage;
    ++state.command_counter;
    samples.emplace_back(t, state);
  }
  void repeat(double t) { samples.emplace_back(t, state); }
};

Script small_match() {
  Script s;
  s.command(0, Command::kStop, Stage::kNormalFirstHalfPre);
  s.command(2, Command::kPrepareKickoffYellow, Stage::kNormalFirstHalfPre);
  s.command(4, Command::kNormalStart, Stage::kNormalFirstHalf);
  s.repeat(10);
  // A goal at 14 s: STOP with the GOAL event, repeated by every packet until play resumes.
  s.state.yellow.score = 1;
  s.state.stage_time_left = time::duration_from_seconds(290);
  s.state.game_events = {GameEvent{.id = "g1", .type = GameEventType::kGoal, .by_team = Team::kYellow, .by_bot = 3}};
  s.command(14, Command::kStop, Stage::kNormalFirstHalf);
  s.repeat(15);
  s.repeat(16);
  s.command(20, Command::kForceStart, Stage::kNormalFirstHalf);
  s.state.game_events.clear();
  s.repeat(25);
  s.command(30, Command::kHalt, Stage::kNormalHalfTime);
  s.state.blue_team_on_positive_half = true;
  s.command(40, Command::kStop, Stage::kNormalSecondHalfPre);
  s.command(42, Command::kForceStart, Stage::kNormalSecondHalf);
  s.command(50, Command::kHalt, Stage::kPostGame);
  return s;
}

MatchReport build(const Script& script, const std::vector<std::pair<double, Vec2>>& balls = {}) {
  MatchReportBuilder builder;
  std::size_t b = 0;
  for (const auto& [t, state] : script.samples) {
    while (b < balls.size() && balls[b].first <= t) {
      builder.on_ball(balls[b].second, at(balls[b].first));
      ++b;
    }
    builder.on_referee(state, at(t));
  }
  for (; b < balls.size(); ++b) builder.on_ball(balls[b].second, at(balls[b].first));
  return builder.report();
}

TEST(MatchReport, ScoreGoalsWithTheirTimesAndEachEventOnce) {
  const MatchReport report = build(small_match());
  EXPECT_EQ(report.source, "builtin:test");
  EXPECT_EQ(report.yellow.name, "Yellow FC");
  EXPECT_EQ(report.yellow.score, 1u);
  EXPECT_EQ(report.blue.score, 0u);
  ASSERT_EQ(report.goals.size(), 1u) << "the goal event is repeated by three packets";
  EXPECT_DOUBLE_EQ(report.goals[0].at, 14);
  EXPECT_EQ(report.goals[0].stage, Stage::kNormalFirstHalf);
  EXPECT_EQ(report.goals[0].stage_time_left, 290.0);
  EXPECT_EQ(report.goals[0].team, Team::kYellow);
  EXPECT_EQ(report.goals[0].by_bot, 3u);
  ASSERT_EQ(report.events.size(), 1u);
  EXPECT_EQ(report.events[0].type, GameEventType::kGoal);
  EXPECT_EQ(report.events[0].count, 1u);
  EXPECT_TRUE(report.final_whistle);
  EXPECT_EQ(report.final_stage, Stage::kPostGame);
  EXPECT_DOUBLE_EQ(report.duration, 50);
}

TEST(MatchReport, TimeInPlayStoppedAndHaltedAddUpExactlyBetweenSamples) {
  const MatchReport report = build(small_match());
  // In play: 4-14 (NORMAL_START), 20-30 (FORCE_START), 42-50; stopped: 0-4, 14-20, 40-42; halted: 30-40.
  EXPECT_DOUBLE_EQ(report.in_play, 10 + 10 + 8);
  EXPECT_DOUBLE_EQ(report.stopped, 4 + 6 + 2);
  EXPECT_DOUBLE_EQ(report.halted, 10);
  EXPECT_EQ(report.commands.at(Command::kStop), 3u);
  EXPECT_EQ(report.commands.at(Command::kForceStart), 2u);
  EXPECT_EQ(report.commands.at(Command::kHalt), 2u);
}

TEST(MatchReport, StagesAndTheSideSwapAreListedWithTheirTimes) {
  const MatchReport report = build(small_match());
  std::vector<Stage> stages;
  for (const auto& change : report.stages) stages.push_back(change.stage);
  EXPECT_EQ(stages, (std::vector<Stage>{Stage::kNormalFirstHalfPre, Stage::kNormalFirstHalf, Stage::kNormalHalfTime,
                                        Stage::kNormalSecondHalfPre, Stage::kNormalSecondHalf, Stage::kPostGame}));
  ASSERT_EQ(report.sides.size(), 2u);
  EXPECT_FALSE(report.sides[0].blue_on_positive_half);
  EXPECT_DOUBLE_EQ(report.sides[1].at, 40);
  EXPECT_TRUE(report.sides[1].blue_on_positive_half);
}

TEST(MatchReport, TheLongestStallCountsOnlyWhileInPlayAndEndsWhenTheBallMoves) {
  std::vector<std::pair<double, Vec2>> balls;
  // In play from 4 s: resting (4 cm of jitter) until 9 s, then moving; stopped 14-20 s with the ball
  // resting (does not count); in play again 20-30 s: resting 21-27.5 s, then moving.
  for (double t = 4; t < 9; t += 0.1) balls.emplace_back(t, Vec2(1.0 + 0.04 * (static_cast<int>(t * 10) % 2), 0));
  for (double t = 9; t < 14; t += 0.1) balls.emplace_back(t, Vec2(1.0 + (t - 9), 0));
  for (double t = 14; t < 20; t += 0.1) balls.emplace_back(t, Vec2(-2, 0));
  for (double t = 20; t < 21; t += 0.1) balls.emplace_back(t, Vec2(-2 + (t - 20), 0));
  for (double t = 21; t < 27.5; t += 0.1) balls.emplace_back(t, Vec2(-0.5, 0.5));
  balls.emplace_back(27.6, Vec2(0, 0));
  const MatchReport report = build(small_match(), balls);
  ASSERT_TRUE(report.longest_stall);
  EXPECT_NEAR(report.longest_stall->seconds, 6.4, 0.11) << "21.0 to 27.4: the 6 s stop does not count";
  EXPECT_NEAR(report.longest_stall->from, 21.0, 0.11);
  EXPECT_NEAR(report.longest_stall->ball.y(), 0.5, 1e-9);
}

TEST(MatchReport, WithoutBallSamplesTheStallIsUnknown) {
  const MatchReport report = build(small_match());
  EXPECT_FALSE(report.longest_stall);
  EXPECT_NE(to_text(report).find("unknown (no vision)"), std::string::npos);
  EXPECT_TRUE(nlohmann::json::parse(to_json(report))["longest_stall"].is_null());
}

TEST(MatchReport, TextAndJsonCarryTheSameFacts) {
  const MatchReport report = build(small_match());
  const std::string text = to_text(report);
  EXPECT_NE(text.find("Yellow FC (yellow) 1 : 0 Blue FC (blue), final whistle"), std::string::npos) << text;
  EXPECT_NE(text.find("0:14.0  yellow robot 3  (NORMAL_FIRST_HALF, 4:50.0 left)"), std::string::npos) << text;
  EXPECT_NE(text.find("in play 28.0 s"), std::string::npos) << text;
  const auto json = nlohmann::json::parse(to_json(report));
  EXPECT_EQ(json["teams"]["yellow"]["score"], 1);
  EXPECT_EQ(json["goals"][0]["team"], "yellow");
  EXPECT_EQ(json["goals"][0]["stage"], "NORMAL_FIRST_HALF");
  EXPECT_DOUBLE_EQ(json["time_s"]["in_play"].get<double>(), 28.0);
  EXPECT_EQ(json["game_events"][0]["type"], "GOAL");
  EXPECT_EQ(json["commands"]["STOP"], 3);
  EXPECT_EQ(json["final_whistle"], true);
}

using Robot = PlayAccount::Robot;

/// Yellow 3 at the origin, blue 5 `distance` m from it along x, blue 1 far away.
std::vector<Robot> two_robots_apart(double distance) {
  return {Robot{.team = TeamColor::kYellow, .id = 3, .position = Vec2(0, 0)},
          Robot{.team = TeamColor::kBlue, .id = 5, .position = Vec2(distance, 0)},
          Robot{.team = TeamColor::kBlue, .id = 1, .position = Vec2(2, 2)}};
}

TEST(MatchReport, TwoRobotCentresCloserThanTwoRadiiAndACentimetreMakeAContactFrame) {
  EXPECT_DOUBLE_EQ(MatchReportBuilder::kContactDistance, 0.19);
  MatchReportBuilder builder;
  builder.on_referee(small_match().samples[0].second, at(0));
  builder.on_robots(two_robots_apart(0.195), at(1));
  MatchReport report = builder.report();
  EXPECT_EQ(report.contact_frames, 0u) << "0.195 m apart is no contact";
  ASSERT_TRUE(report.closest_robots);
  EXPECT_DOUBLE_EQ(report.closest_robots->distance, 0.195);

  builder.on_frame(Vec2(1, 1), two_robots_apart(0.185), at(2));
  builder.on_robots(two_robots_apart(0.185), at(2));  // a second camera's frame of the same instant
  builder.on_robots(two_robots_apart(0.3), at(3));
  report = builder.report();
  EXPECT_EQ(report.contact_frames, 2u) << "0.185 m apart, counted per frame as delivered";
  EXPECT_EQ(report.robot_frames, 4u);
  ASSERT_TRUE(report.closest_robots);
  EXPECT_DOUBLE_EQ(report.closest_robots->distance, 0.185);
  EXPECT_DOUBLE_EQ(report.closest_robots->at, 2);
  EXPECT_EQ(report.closest_robots->first.team, TeamColor::kYellow);
  EXPECT_EQ(report.closest_robots->first.id, 3u);
  EXPECT_EQ(report.closest_robots->second.team, TeamColor::kBlue);
  EXPECT_EQ(report.closest_robots->second.id, 5u);
  EXPECT_NE(to_text(report).find("closest two 0.185 m apart at 0:02.0 (yellow 3, blue 5); contact frames"),
            std::string::npos)
      << to_text(report);
  const auto json = nlohmann::json::parse(to_json(report));
  EXPECT_EQ(json["contact_frames"], 2);
  EXPECT_DOUBLE_EQ(json["closest_robots"]["distance_m"].get<double>(), 0.185);
  EXPECT_EQ(json["closest_robots"]["robots"][1]["team"], "blue");
  EXPECT_EQ(json["closest_robots"]["robots"][1]["id"], 5);
}

TEST(MatchReport, APairsContactFramesUpToAQuarterSecondApartMakeOneEpisodeWithItsClosestDistanceAndCommand) {
  MatchReportBuilder builder;
  builder.on_referee(small_match().samples[0].second, at(0));
  builder.on_frame(Vec2(0.3, 0), two_robots_apart(0.185), at(1));
  builder.on_robots(two_robots_apart(0.170), at(1.25));  // the boundary: still the same episode
  builder.on_robots(two_robots_apart(0.180), at(1.3));
  builder.on_robots(two_robots_apart(0.180), at(1.56));  // 0.26 s later: a new episode
  builder.on_robots(two_robots_apart(0.3), at(2));
  const MatchReport report = builder.report();
  EXPECT_EQ(report.contact_frames, 4u);
  ASSERT_EQ(report.contacts.size(), 2u);
  const MatchReport::ContactEpisode& first = report.contacts[0];
  EXPECT_EQ(first.first.team, TeamColor::kBlue) << "ordered by team, then id";
  EXPECT_EQ(first.first.id, 5u);
  EXPECT_EQ(first.second.team, TeamColor::kYellow);
  EXPECT_EQ(first.second.id, 3u);
  EXPECT_DOUBLE_EQ(first.from, 1);
  EXPECT_NEAR(first.seconds, 0.3, 1e-9);
  EXPECT_EQ(first.frames, 3u);
  EXPECT_DOUBLE_EQ(first.closest, 0.170);
  ASSERT_TRUE(first.command);
  EXPECT_EQ(*first.command, small_match().samples[0].second.command);
  ASSERT_TRUE(first.ball_distance);
  EXPECT_NEAR(*first.ball_distance, 0.13, 1e-9) << "ball at 0.3 m, the robots at 0 and 0.17 m";
  EXPECT_EQ(report.contacts[1].frames, 1u);
  EXPECT_DOUBLE_EQ(report.contacts[1].from, 1.56);
  EXPECT_NE(to_text(report).find("contacts: 2 episodes"), std::string::npos) << to_text(report);
  const auto json = nlohmann::json::parse(to_json(report));
  ASSERT_EQ(json["contacts"].size(), 2u);
  EXPECT_DOUBLE_EQ(json["contacts"][0]["closest_m"].get<double>(), 0.170);
  EXPECT_EQ(json["contacts"][0]["frames"], 3);
  EXPECT_EQ(json["contacts"][1]["robots"][0]["team"], "blue");
}

TEST(MatchReport, ARobotDetectedTwiceInOneFrameIsNoContact) {
  MatchReportBuilder builder;
  const Robot robot{.team = TeamColor::kBlue, .id = 2, .position = Vec2(1, 1)};
  const std::vector<Robot> twice = {robot, robot, Robot{.team = TeamColor::kYellow, .id = 2, .position = Vec2(3, 1)}};
  builder.on_robots(twice, at(0));
  const MatchReport report = builder.report();
  EXPECT_EQ(report.contact_frames, 0u);
  ASSERT_TRUE(report.closest_robots);
  EXPECT_DOUBLE_EQ(report.closest_robots->distance, 2.0);
}

/// small_match() with a ball observation every 0.1 s from 0 to 49.9 s: inside the 9 x 6 m field but from 20 to
/// 30 s, when it lies beyond the touch line (y 3.1 m).
MatchReport with_ball_in_and_out(bool with_field) {
  MatchReportBuilder builder;
  if (with_field) builder.set_field(FieldGeometry::division_b());
  const Script s = small_match();
  std::size_t next = 0;
  for (int i = 0; i < 500; ++i) {
    const double t = i / 10.0;
    while (next < s.samples.size() && s.samples[next].first < t) {
      builder.on_referee(s.samples[next].second, at(s.samples[next].first));
      ++next;
    }
    builder.on_ball(t >= 20 && t < 30 ? Vec2(1, 3.1) : Vec2(1, 2.9), at(t));
  }
  for (; next < s.samples.size(); ++next) builder.on_referee(s.samples[next].second, at(s.samples[next].first));
  return builder.report();
}

TEST(MatchReport, InPlayFromVisionCountsOnlyWhileRunningWithTheBallInsideTheField) {
  const MatchReport report = with_ball_in_and_out(true);
  EXPECT_DOUBLE_EQ(report.in_play, 28) << "the referee's game ran 4-14, 20-30 and 42-50 s";
  ASSERT_TRUE(report.in_play_vision);
  // Each observation counts until the next one, for the referee's command before it: 4.1-14.1 s (the one at
  // 4.0 s came before NORMAL_START, the one at 14.0 s before STOP), 30.0-30.1 s (back inside, before HALT)
  // and 42.1-49.9 s (the last observation); 20-30 s the ball lies out of the field.
  EXPECT_NEAR(*report.in_play_vision, 10 + 0.1 + 7.8, 1e-6);
  const auto json = nlohmann::json::parse(to_json(report));
  EXPECT_NEAR(json["time_s"]["in_play_vision"].get<double>(), 17.9, 1e-6);
  EXPECT_NEAR(json["in_play_vision_share"].get<double>(), 17.9 / 50, 1e-6);
  EXPECT_NE(to_text(report).find("in play from vision (the ball seen inside the field): 17.9 s (36 % of 50.0 s)"),
            std::string::npos)
      << to_text(report);
}

TEST(MatchReport, WithoutTheFieldSizeInPlayFromVisionIsUnknown) {
  const MatchReport report = with_ball_in_and_out(false);
  EXPECT_FALSE(report.in_play_vision);
  EXPECT_NE(to_text(report).find("in play from vision: unknown"), std::string::npos);
  EXPECT_TRUE(nlohmann::json::parse(to_json(report))["time_s"]["in_play_vision"].is_null());
}

TEST(MatchReport, ABallUnseenForLongCountsOnlyUntilItIsNoLongerSeen) {
  MatchReportBuilder builder;
  builder.set_field(FieldGeometry::division_b());
  Script s;
  s.command(0, Command::kForceStart, Stage::kNormalFirstHalf);
  builder.on_referee(s.samples[0].second, at(0));
  builder.on_ball(Vec2(0, 0), at(1));
  builder.on_ball(Vec2(0, 0), at(4));  // 3 s unseen
  builder.on_ball(Vec2(0, 0), at(4.1));
  EXPECT_NEAR(*builder.report().in_play_vision, MatchReportBuilder::kBallUnseenAfter + 0.1, 1e-6);
}

TEST(MatchReport, PlacementsAndBallsOutPerTeam) {
  Script s;
  s.command(0, Command::kForceStart, Stage::kNormalFirstHalf);
  s.state.game_events = {
      GameEvent{.id = "o1", .type = GameEventType::kBallLeftFieldTouchLine, .by_team = Team::kYellow}};
  s.command(5, Command::kBallPlacementBlue, Stage::kNormalFirstHalf);
  s.repeat(6);
  s.command(8, Command::kDirectFreeBlue, Stage::kNormalFirstHalf);
  s.state.game_events = {
      GameEvent{.id = "o2", .type = GameEventType::kBallLeftFieldGoalLine, .by_team = Team::kYellow}};
  s.command(12, Command::kBallPlacementBlue, Stage::kNormalFirstHalf);
  s.command(15, Command::kDirectFreeBlue, Stage::kNormalFirstHalf);
  s.state.game_events = {GameEvent{.id = "o3", .type = GameEventType::kBallLeftFieldTouchLine, .by_team = Team::kBlue}};
  s.command(20, Command::kBallPlacementYellow, Stage::kNormalFirstHalf);
  const MatchReport report = build(s);
  EXPECT_EQ(report.blue.placements, 2u) << "the repeated packet at 6 s is no new command";
  EXPECT_EQ(report.yellow.placements, 1u);
  EXPECT_EQ(report.yellow.balls_out, 2u);
  EXPECT_EQ(report.blue.balls_out, 1u);
  EXPECT_NE(to_text(report).find("placements: yellow 1, blue 2; balls out: yellow 2, blue 1"), std::string::npos)
      << to_text(report);
  const auto json = nlohmann::json::parse(to_json(report));
  EXPECT_EQ(json["teams"]["blue"]["placements"], 2);
  EXPECT_EQ(json["teams"]["yellow"]["balls_out"], 2);
}

TEST(MatchReport, EachAvoidableFoulIsListedOnceWithItsTimeRobotPlaceAndCommand) {
  Script s;
  s.command(0, Command::kForceStart, Stage::kNormalFirstHalf);
  s.state.game_events = {GameEvent{.id = "f1",
                                   .type = GameEventType::kAttackerDoubleTouchedBall,
                                   .by_team = Team::kYellow,
                                   .by_bot = 4,
                                   .location = Vec2(1.5, -2.0)},
                         GameEvent{.id = "o1", .type = GameEventType::kBallLeftFieldTouchLine, .by_team = Team::kBlue}};
  s.command(7.5, Command::kStop, Stage::kNormalFirstHalf);
  s.repeat(8);  // the same events again: listed once
  s.state.game_events = {
      GameEvent{.id = "f2", .type = GameEventType::kBotTooFastInStop, .by_team = Team::kBlue, .by_bot = 2}};
  s.repeat(9);
  const MatchReport report = build(s);
  ASSERT_EQ(report.avoidable_fouls.size(), 2u) << "a ball out is no foul";
  const MatchReport::AvoidableFoul& touch = report.avoidable_fouls[0];
  EXPECT_DOUBLE_EQ(touch.at, 7.5);
  EXPECT_EQ(touch.type, GameEventType::kAttackerDoubleTouchedBall);
  EXPECT_EQ(touch.team, Team::kYellow);
  EXPECT_EQ(touch.by_bot, 4u);
  ASSERT_TRUE(touch.location);
  EXPECT_DOUBLE_EQ(touch.location->x(), 1.5);
  EXPECT_EQ(touch.command, Command::kStop);
  EXPECT_DOUBLE_EQ(report.avoidable_fouls[1].at, 9);
  EXPECT_EQ(report.avoidable_fouls[1].team, Team::kBlue);
  EXPECT_FALSE(report.avoidable_fouls[1].location);
  const std::string text = to_text(report);
  EXPECT_NE(text.find("avoidable fouls: 2"), std::string::npos) << text;
  EXPECT_NE(text.find("ATTACKER_DOUBLE_TOUCHED_BALL  yellow robot 4 at (1.50, -2.00), STOP"), std::string::npos)
      << text;
  const auto json = nlohmann::json::parse(to_json(report));
  ASSERT_EQ(json["avoidable_fouls"].size(), 2u);
  EXPECT_EQ(json["avoidable_fouls"][0]["type"], "ATTACKER_DOUBLE_TOUCHED_BALL");
  EXPECT_EQ(json["avoidable_fouls"][0]["by_bot"], 4);
  EXPECT_DOUBLE_EQ(json["avoidable_fouls"][0]["location"][1].get<double>(), -2.0);
  EXPECT_EQ(json["avoidable_fouls"][1]["location"], nullptr);
  EXPECT_EQ(json["avoidable_fouls"][1]["command"], "STOP");
}

TEST(MatchReport, SamplesGoingBackInTimeAreIgnored) {
  MatchReportBuilder builder;
  Script s = small_match();
  builder.on_referee(s.samples[3].second, at(10));
  builder.on_referee(s.samples[0].second, at(5));
  EXPECT_EQ(builder.report().referee_samples, 1u);
}

// ---------------------------------------------------------------------------------------------------
// The command

std::string referee_bytes(const RefereeState& state) { return referee::to_proto(state).SerializeAsString(); }

/// A camera frame with the ball and `robots` (metres), and with the field's geometry when `field` is given.
std::string vision_bytes(const Vec2& ball_m, const std::vector<Robot>& robots = {},
                         const std::optional<FieldGeometry>& field = std::nullopt) {
  SSL_WrapperPacket packet;
  if (field) {
    SSL_GeometryFieldSize* size = packet.mutable_geometry()->mutable_field();
    size->set_field_length(static_cast<int>(field->field_length * 1000));
    size->set_field_width(static_cast<int>(field->field_width * 1000));
    size->set_goal_width(static_cast<int>(field->goal_width * 1000));
    size->set_goal_depth(static_cast<int>(field->goal_depth * 1000));
    size->set_boundary_width(static_cast<int>(field->boundary_width * 1000));
  }
  SSL_DetectionFrame* frame = packet.mutable_detection();
  for (const Robot& robot : robots) {
    SSL_DetectionRobot* seen = robot.team == TeamColor::kBlue ? frame->add_robots_blue() : frame->add_robots_yellow();
    seen->set_confidence(0.9f);
    seen->set_robot_id(robot.id);
    seen->set_x(static_cast<float>(robot.position.x() * 1000));
    seen->set_y(static_cast<float>(robot.position.y() * 1000));
    seen->set_pixel_x(0);
    seen->set_pixel_y(0);
  }
  frame->set_frame_number(1);
  frame->set_t_capture(1.7e9);
  frame->set_t_sent(1.7e9);
  frame->set_camera_id(0);
  SSL_DetectionBall* ball = frame->add_balls();
  ball->set_confidence(0.9f);
  ball->set_x(static_cast<float>(ball_m.x() * 1000));
  ball->set_y(static_cast<float>(ball_m.y() * 1000));
  ball->set_pixel_x(0);
  ball->set_pixel_y(0);
  return packet.SerializeAsString();
}

fs::path write_log(const std::string& name) {
  const fs::path path = fs::temp_directory_path() / name;
  auto writer = league::LogWriter::open(path);
  EXPECT_TRUE(writer) << writer.error().message;
  const Script s = small_match();
  for (const auto& [t, state] : s.samples) {
    const std::int64_t ns = at(t).nanoseconds();
    EXPECT_TRUE(writer->write(ns - 1, league::MessageType::kVision2014, vision_bytes({1.0, 0.0})));
    EXPECT_TRUE(writer->write(ns, league::MessageType::kRefbox2013, referee_bytes(state)));
  }
  EXPECT_TRUE(writer->write(at(51).nanoseconds(), league::MessageType::kRefbox2013, "not a referee packet"));
  EXPECT_TRUE(writer->close());
  return path;
}

TEST(MatchReportCommand, ReadsAnSslLogFile) {
  const fs::path log = write_log("sslctl_match_report_test.log");
  std::ostringstream out, err;
  ShutdownSignal shutdown;
  ASSERT_EQ(match_report({.file = log.string(), .json = true}, shutdown, out, err), 0) << err.str();
  const auto json = nlohmann::json::parse(out.str());
  EXPECT_EQ(json["source"], "builtin:test");
  EXPECT_EQ(json["teams"]["yellow"]["score"], 1);
  EXPECT_EQ(json["goals"].size(), 1u);
  EXPECT_EQ(json["final_whistle"], true);
  EXPECT_EQ(json["malformed_packets"], 1) << "the garbage record is counted";
  EXPECT_EQ(json["ball_samples"], small_match().samples.size());
  fs::remove(log);
}

TEST(MatchReportCommand, TheBinaryPrintsTheReportOfALogAndRejectsBadFlags) {
  const fs::path log = write_log("sslctl_match_report_binary_test.log");
  auto child = testing::ChildProcess::start(testing::bin_dir() / "sslctl", {"match", "report", log.string()});
  ASSERT_TRUE(child) << child.error().message;
  std::string text;
  while (auto line = child->read_line(std::chrono::seconds(10))) text += *line + "\n";
  EXPECT_EQ(child->wait(std::chrono::seconds(10)), 0);
  EXPECT_NE(text.find("score: Yellow FC (yellow) 1 : 0 Blue FC (blue), final whistle"), std::string::npos) << text;
  auto bad = testing::ChildProcess::start(testing::bin_dir() / "sslctl", {"match", "report", "--duration", "-1"});
  ASSERT_TRUE(bad);
  EXPECT_NE(bad->wait(std::chrono::seconds(10)), 0);
  auto missing = testing::ChildProcess::start(testing::bin_dir() / "sslctl", {"match", "report", "/nonexistent.log"});
  ASSERT_TRUE(missing);
  EXPECT_EQ(missing->wait(std::chrono::seconds(10)), 1);
  fs::remove(log);
}

TEST(MatchReportCommand, ReadsTheLiveRefereeAndVisionMulticast) {
  constexpr int kRefereePort = 25401;
  constexpr int kVisionPort = 25402;
  auto referee_out = net::MulticastSender::open("224.5.23.1", kRefereePort, "127.0.0.1");
  auto vision_out = net::MulticastSender::open("224.5.23.2", kVisionPort, "127.0.0.1");
  ASSERT_TRUE(referee_out && vision_out);
  std::atomic<bool> ready{false};
  std::ostringstream out, err;
  ShutdownSignal shutdown;
  int status = -1;
  std::thread reader([&] {
    status = match_report({.referee_port = kRefereePort,
                           .vision_port = kVisionPort,
                           .duration_s = 30,
                           .until_final_whistle = true,
                           .json = true,
                           .on_ready = [&] { ready = true; }},
                          shutdown, out, err);
  });
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(10);
  while (!ready && std::chrono::steady_clock::now() < deadline) std::this_thread::sleep_for(std::chrono::milliseconds(5));
  ASSERT_TRUE(ready);
  const auto send = [](net::MulticastSender& sender, const std::string& bytes) {
    EXPECT_TRUE(sender.send({reinterpret_cast<const std::uint8_t*>(bytes.data()), bytes.size()}));
  };
  send(*vision_out, vision_bytes({0.5, 0.5}, {}, FieldGeometry::division_b()));
  for (const auto& [t, state] : small_match().samples) {
    send(*vision_out, vision_bytes({0.5, 0.5}, two_robots_apart(0.15)));
    if (state.stage == Stage::kPostGame) send(*referee_out, "garbage");
    send(*referee_out, referee_bytes(state));
  }
  reader.join();  // --until-final-whistle: it stops at POST_GAME (at the latest after --duration)
  ASSERT_EQ(status, 0) << err.str();
  const auto json = nlohmann::json::parse(out.str());
  EXPECT_EQ(json["teams"]["yellow"]["score"], 1);
  EXPECT_EQ(json["goals"].size(), 1u);
  EXPECT_EQ(json["final_whistle"], true);
  EXPECT_GE(json["ball_samples"].get<int>(), 1);
  EXPECT_EQ(json["malformed_packets"], 1);
  // The robots and the field's size of the vision packets.
  EXPECT_GE(json["robot_frames"].get<int>(), 1);
  EXPECT_EQ(json["contact_frames"], json["robot_frames"]) << "every frame with robots has two 0.15 m apart";
  EXPECT_NEAR(json["closest_robots"]["distance_m"].get<double>(), 0.15, 1e-4);
  EXPECT_FALSE(json["time_s"]["in_play_vision"].is_null()) << "the geometry packet gave the field's size";
}

}  // namespace
}  // namespace ssl::sslctl
