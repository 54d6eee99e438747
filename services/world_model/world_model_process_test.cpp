// Process test: starts the real `world_model --team yellow` on a private DDS domain, publishes vision and
// referee samples from here, and checks world.state (yellow partition) is in yellow's team frame. Waits
// only for matches and data, with timeouts (never sleeps for discovery).
#include <gtest/gtest.h>
#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>

#include <chrono>
#include <cmath>
#include <numbers>
#include <string>
#include <thread>

#include "libs/dds/participant.h"
#include "libs/time/clock.h"

extern char** environ;

namespace ssl {
namespace {

using namespace std::chrono_literals;
constexpr int kDomain = 147;

class Process {
 public:
  explicit Process(std::vector<std::string> args) {
    std::vector<char*> argv;
    for (auto& a : args) argv.push_back(a.data());
    argv.push_back(nullptr);
    if (posix_spawn(&pid_, argv[0], nullptr, nullptr, argv.data(), environ) != 0) pid_ = -1;
  }
  ~Process() {
    if (pid_ <= 0) return;
    kill(pid_, SIGTERM);
    int status = 0;
    waitpid(pid_, &status, 0);
  }
  bool started() const { return pid_ > 0; }
  bool running() const { return pid_ > 0 && waitpid(pid_, nullptr, WNOHANG) == 0; }

 private:
  pid_t pid_ = -1;
};

TEST(WorldModelProcess, YellowWorldStateIsInYellowsTeamFrame) {
  Process world_model({WORLD_MODEL_BINARY, "--team", "yellow", "--domain", std::to_string(kDomain)});
  ASSERT_TRUE(world_model.started());
  auto participant = dds::Participant::create({.domain_id = kDomain, .name = "world_model_process_test"});
  ASSERT_TRUE(participant) << participant.error().message;
  auto detections = participant->make_writer(dds::topics::kVisionDetection);
  auto geometry = participant->make_writer(dds::topics::kVisionGeometry);
  auto referee = participant->make_writer(dds::topics::kRefereeState);
  auto world = participant->make_reader(dds::topics::kWorldState, TeamColor::kYellow);
  ASSERT_TRUE(detections && geometry && referee && world);
  ASSERT_TRUE(detections->wait_for_match(1, 30s)) << "world_model never subscribed to vision.detection";
  ASSERT_TRUE(referee->wait_for_match(1, 10s));
  ASSERT_TRUE(world->wait_for_match(1, 10s));

  idl::vision::Geometry g;
  g.field().field_length(12.0);
  g.field().field_width(9.0);
  g.field().ball_radius(0.0215);
  ASSERT_TRUE(geometry->write(g));
  idl::referee::RefereeState r;
  r.command(idl::referee::COMMAND_STOP);
  r.command_counter(1);
  r.has_blue_team_on_positive_half(true);
  r.blue_team_on_positive_half(false);  // yellow defends +x: its team frame is turned by pi
  ASSERT_TRUE(referee->write(r));

  time::RealClock clock;
  bool checked = false;
  std::uint32_t frame_number = 0;
  const auto deadline = std::chrono::steady_clock::now() + 30s;
  while (!checked && std::chrono::steady_clock::now() < deadline) {
    ASSERT_TRUE(world_model.running());
    idl::vision::DetectionFrame f;
    f.camera_id(0);
    f.frame_number(++frame_number);
    const std::int64_t now = clock.now().nanoseconds();
    f.capture_unix_ns(now);
    f.sent_unix_ns(now);
    f.receive_unix_ns(now);
    idl::vision::RobotDetection robot;
    robot.robot_id(4);
    robot.x(2.0);
    robot.y(1.0);
    robot.orientation(0.3);
    robot.has_orientation(true);
    robot.confidence(1.0f);
    f.robots_yellow().push_back(robot);
    robot.robot_id(1);
    robot.x(-3.0);
    f.robots_blue().push_back(robot);
    idl::vision::BallDetection ball;
    ball.x(1.0);
    ball.y(0.5);
    ball.confidence(1.0f);
    f.balls().push_back(ball);
    ASSERT_TRUE(detections->write(f));
    if (!world->wait_for_data(50ms)) continue;
    for (const auto& s : world->take()) {
      const auto& w = s.data;
      if (w.friendly().size() != 1 || !w.has_ball() || w.friendly()[0].pose().x() > 0) continue;
      EXPECT_EQ(w.team(), idl::common::TEAM_COLOR_YELLOW);
      EXPECT_EQ(w.friendly()[0].id(), 4u);
      EXPECT_NEAR(w.friendly()[0].pose().x(), -2.0, 0.01);
      EXPECT_NEAR(w.friendly()[0].pose().y(), -1.0, 0.01);
      EXPECT_NEAR(w.friendly()[0].pose().theta(), 0.3 - std::numbers::pi, 0.01);
      ASSERT_EQ(w.enemy().size(), 1u);
      EXPECT_NEAR(w.enemy()[0].pose().x(), 3.0, 0.01);
      EXPECT_NEAR(w.ball().position().x(), -1.0, 0.01);
      EXPECT_NEAR(w.ball().position().y(), -0.5, 0.01);
      EXPECT_GT(w.stamp().capture_unix_ns(), 0);
      EXPECT_GT(w.sequence_number(), 0u);
      checked = true;
      break;
    }
  }
  EXPECT_TRUE(checked) << "no world.state in yellow's frame within 30 s";
}

}  // namespace
}  // namespace ssl
