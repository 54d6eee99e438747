// The league's streams through both gateways onto typed topics, end to end across processes: the test
// writes an SSL log file (vision from two cameras, geometry, referee states with a game event), replays it
// with `sslctl log replay` onto loopback multicast, runs `vision_gateway` and `referee_gateway`, and reads
// vision.detection, vision.geometry, referee.state and referee.event with a DDS reader of its own.
#include <gtest/gtest.h>
#include <signal.h>

#include <cmath>
#include <filesystem>
#include <set>

#include "libs/dds/participant.h"
#include "libs/league/log_file.h"
#include "proto/ssl_gc_referee_message.pb.h"
#include "proto/ssl_vision_wrapper.pb.h"
#include "tests/support/process.h"

namespace ssl::testing {
namespace {

using std::chrono::seconds;
using Clock = std::chrono::steady_clock;
constexpr int kDomain = 157;
constexpr int kVisionPort = 26910;
constexpr int kRefereePort = 26911;
constexpr std::int64_t kStartNs = 1'700'000'000'000'000'000;

std::string vision_frame(std::uint32_t camera, std::uint32_t frame_number, double t_capture) {
  SSL_WrapperPacket packet;
  SSL_DetectionFrame* frame = packet.mutable_detection();
  frame->set_frame_number(frame_number);
  frame->set_t_capture(t_capture);
  frame->set_t_sent(t_capture + 0.004);
  frame->set_camera_id(camera);
  auto* ball = frame->add_balls();
  ball->set_confidence(0.9f);
  ball->set_x(camera == 0 ? -1500.0f : 1500.0f);
  ball->set_y(250.0f);
  ball->set_pixel_x(10);
  ball->set_pixel_y(20);
  auto* robot = frame->add_robots_blue();
  robot->set_confidence(1.0f);
  robot->set_robot_id(4);
  robot->set_x(-2000.0f);
  robot->set_y(1000.0f);
  robot->set_orientation(0.5f);
  robot->set_pixel_x(1);
  robot->set_pixel_y(2);
  return packet.SerializeAsString();
}

std::string geometry() {
  SSL_WrapperPacket packet;
  SSL_GeometryFieldSize* field = packet.mutable_geometry()->mutable_field();
  field->set_field_length(12000);
  field->set_field_width(9000);
  field->set_goal_width(1800);
  field->set_goal_depth(180);
  field->set_boundary_width(300);
  return packet.SerializeAsString();
}

std::string referee(std::uint32_t counter, Referee::Command command, bool with_event, std::uint64_t t_us) {
  Referee referee;
  referee.set_packet_timestamp(t_us);
  referee.set_stage(Referee::NORMAL_FIRST_HALF);
  referee.set_command(command);
  referee.set_command_counter(counter);
  referee.set_command_timestamp(t_us);
  for (Referee::TeamInfo* team : {referee.mutable_yellow(), referee.mutable_blue()}) {
    team->set_name(team == referee.mutable_yellow() ? "Yellow Team" : "Blue Team");
    team->set_score(team == referee.mutable_blue() ? 2 : 1);
    team->set_red_cards(0);
    team->set_yellow_cards(0);
    team->set_timeouts(4);
    team->set_timeout_time(300'000'000);
    team->set_goalkeeper(0);
  }
  if (command == Referee::BALL_PLACEMENT_BLUE) {
    referee.mutable_designated_position()->set_x(1500.0f);
    referee.mutable_designated_position()->set_y(-750.0f);
  }
  if (with_event) {
    GameEvent* event = referee.add_game_events();
    event->set_id("event-1");
    event->set_type(GameEvent::BALL_LEFT_FIELD_TOUCH_LINE);
    event->mutable_ball_left_field_touch_line()->set_by_team(::YELLOW);
    event->mutable_ball_left_field_touch_line()->set_by_bot(3);
    event->mutable_ball_left_field_touch_line()->mutable_location()->set_x(2.0f);
    event->mutable_ball_left_field_touch_line()->mutable_location()->set_y(4.5f);
  }
  return referee.SerializeAsString();
}

/// One second of a match: 60 Hz frames from cameras 0 and 1, a geometry packet, and the referee going
/// from STOP to BALL_PLACEMENT_BLUE with a ball-out event.
std::filesystem::path write_log() {
  const auto path = std::filesystem::temp_directory_path() / ("gateways_" + std::to_string(getpid()) + ".log");
  auto writer = league::LogWriter::open(path);
  EXPECT_TRUE(writer) << writer.error().message;
  const double t0 = static_cast<double>(kStartNs) * 1e-9;
  EXPECT_TRUE(writer->write(kStartNs, league::MessageType::kVision2014, geometry()).ok());
  for (std::uint32_t i = 0; i < 60; ++i) {
    const std::int64_t t = kStartNs + i * 16'666'667;
    for (std::uint32_t camera : {0u, 1u}) {
      EXPECT_TRUE(writer->write(t, league::MessageType::kVision2014, vision_frame(camera, i + 1, t0 + i / 60.0)).ok());
    }
    if (i % 10 == 0) {
      const bool placement = i >= 30;
      EXPECT_TRUE(writer
                      ->write(t, league::MessageType::kRefbox2013,
                              referee(placement ? 2 : 1, placement ? Referee::BALL_PLACEMENT_BLUE : Referee::STOP,
                                      placement, static_cast<std::uint64_t>(t / 1000)))
                      .ok());
    }
  }
  EXPECT_TRUE(writer->close().ok());
  return path;
}

ChildProcess start(const std::string& program, const std::vector<std::string>& args) {
  auto child = ChildProcess::start(bin_dir() / program, args);
  EXPECT_TRUE(child) << child.error().message;
  return std::move(child).value();
}

TEST(GatewaysLogReplayTest, ReplayedLogAppearsOnVisionAndRefereeTopics) {
  const auto log = write_log();
  auto participant = dds::Participant::create({.domain_id = kDomain, .name = "gateways_test"});
  ASSERT_TRUE(participant) << participant.error().message;
  auto detections = participant->make_reader(dds::topics::kVisionDetection);
  auto geometries = participant->make_reader(dds::topics::kVisionGeometry);
  auto states = participant->make_reader(dds::topics::kRefereeState);
  auto events = participant->make_reader(dds::topics::kRefereeEvent);
  ASSERT_TRUE(detections && geometries && states && events);

  const std::string domain = std::to_string(kDomain);
  auto vision_gateway = start("vision_gateway", {"--domain", domain, "--interface", "127.0.0.1", "--vision-port",
                                                 std::to_string(kVisionPort), "--log-level", "warn"});
  auto referee_gateway = start("referee_gateway", {"--domain", domain, "--interface", "127.0.0.1", "--referee-port",
                                                   std::to_string(kRefereePort), "--log-level", "warn"});
  // Both gateways are up once their writers matched our readers.
  ASSERT_TRUE(detections->wait_for_match(1, seconds(20))) << vision_gateway.drain_stderr();
  ASSERT_TRUE(states->wait_for_match(1, seconds(20))) << referee_gateway.drain_stderr();

  // Replayed in a loop until everything was seen: the gateways' sockets may join the groups a moment
  // after their DDS writers exist.
  auto replay = start("sslctl", {"log", "replay", log.string(), "--loop", "--speed", "4", "--interface", "127.0.0.1",
                                 "--vision-port", std::to_string(kVisionPort), "--referee-port",
                                 std::to_string(kRefereePort)});
  std::set<std::uint32_t> cameras;
  bool detection_checked = false;
  bool geometry_checked = false;
  bool placement_seen = false;
  bool event_seen = false;
  const auto deadline = Clock::now() + seconds(30);
  while (Clock::now() < deadline && !(cameras.size() == 2 && detection_checked && geometry_checked &&
                                      placement_seen && event_seen)) {
    detections->wait_for_data(std::chrono::milliseconds(100));
    for (const auto& sample : detections->take()) {
      const auto& frame = sample.data;
      cameras.insert(frame.camera_id());
      ASSERT_EQ(frame.balls().size(), 1u);
      ASSERT_EQ(frame.robots_blue().size(), 1u);
      EXPECT_NEAR(frame.balls()[0].x(), frame.camera_id() == 0 ? -1.5 : 1.5, 1e-6);
      EXPECT_NEAR(frame.balls()[0].y(), 0.25, 1e-6);
      EXPECT_NEAR(frame.robots_blue()[0].x(), -2.0, 1e-6);
      EXPECT_NEAR(frame.robots_blue()[0].orientation(), 0.5, 1e-6);
      EXPECT_EQ(frame.robots_blue()[0].robot_id(), 4u);
      // Capture time is the log's (vision clock), kept to the microsecond through the double seconds.
      EXPECT_NEAR(static_cast<double>(frame.capture_unix_ns() - kStartNs) * 1e-9, (frame.frame_number() - 1) / 60.0,
                  1e-5);
      EXPECT_GT(frame.receive_unix_ns(), 0);
      detection_checked = true;
    }
    for (const auto& sample : geometries->take()) {
      EXPECT_DOUBLE_EQ(sample.data.field().field_length(), 12.0);
      EXPECT_DOUBLE_EQ(sample.data.field().goal_width(), 1.8);
      geometry_checked = true;
    }
    for (const auto& sample : states->take()) {
      const auto& state = sample.data;
      EXPECT_EQ(state.blue().name(), "Blue Team");
      EXPECT_EQ(state.blue().score(), 2u);
      if (state.command() == idl::referee::COMMAND_BALL_PLACEMENT_BLUE) {
        ASSERT_TRUE(state.has_designated_position());
        EXPECT_NEAR(state.designated_position().x(), 1.5, 1e-6);
        EXPECT_NEAR(state.designated_position().y(), -0.75, 1e-6);
        EXPECT_EQ(state.command_counter(), 2u);
        placement_seen = true;
      }
    }
    for (const auto& sample : events->take()) {
      const auto& event = sample.data.event();
      EXPECT_EQ(event.type(), idl::referee::GAME_EVENT_BALL_LEFT_FIELD_TOUCH_LINE);
      EXPECT_EQ(event.by_team(), idl::common::TEAM_COLOR_YELLOW);
      EXPECT_NEAR(event.location().y(), 4.5, 1e-6);
      event_seen = true;
    }
  }
  EXPECT_EQ(cameras, (std::set<std::uint32_t>{0, 1}));
  EXPECT_TRUE(detection_checked);
  EXPECT_TRUE(geometry_checked);
  EXPECT_TRUE(placement_seen);
  EXPECT_TRUE(event_seen);

  replay.signal(SIGINT);
  EXPECT_EQ(replay.wait(seconds(10)), 0) << replay.drain_stderr();
  vision_gateway.signal(SIGTERM);
  referee_gateway.signal(SIGTERM);
  EXPECT_EQ(vision_gateway.wait(seconds(10)), 0) << vision_gateway.drain_stderr();
  EXPECT_EQ(referee_gateway.wait(seconds(10)), 0) << referee_gateway.drain_stderr();
  std::filesystem::remove(log);
}

}  // namespace
}  // namespace ssl::testing
