// Tests of the match report: the pure builder with scripted referee states at explicit times, and
// `sslctl match report` on an SSL log file (the function and the binary) and live on loopback multicast
// (ports 25400-25499).
#include <gtest/gtest.h>

#include <chrono>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <thread>

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

std::string vision_bytes(const Vec2& ball_m) {
  SSL_WrapperPacket packet;
  SSL_DetectionFrame* frame = packet.mutable_detection();
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
  for (const auto& [t, state] : small_match().samples) {
    send(*vision_out, vision_bytes({0.5, 0.5}));
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
}

}  // namespace
}  // namespace ssl::sslctl
