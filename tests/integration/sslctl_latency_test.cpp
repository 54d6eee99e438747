// `sslctl latency` as an operator runs it: a child process listening on a private domain (158) while this
// test writes vision.detection, world.state (blue) and robot.commands (blue) stamped as if vision_gateway
// had received their camera frame 5 ms before each write. The per-stage figures it prints must show those
// 5 ms (plus DDS delivery), for exactly the stages that had samples. robot.sent (blue) carries robot_link's
// own send stamp, 4 ms after the gateway's: that stage shows exactly 4 ms, and heartbeat resends (stamped
// as if 50 ms late) are not counted.
#include <gtest/gtest.h>

#include <chrono>
#include <map>
#include <nlohmann/json.hpp>
#include <stdexcept>
#include <string>
#include <thread>

#include "libs/dds/participant.h"
#include "tests/support/process.h"

namespace ssl::testing {
namespace {

using namespace std::chrono_literals;
constexpr auto kTimeout = 20s;
constexpr int kDomain = 158;

std::int64_t now_ns() {
  return std::chrono::duration_cast<std::chrono::nanoseconds>(std::chrono::system_clock::now().time_since_epoch())
      .count();
}

template <typename T>
T value_of(Result<T> result) {
  if (!result) throw std::runtime_error(result.error().message);
  return std::move(result).value();
}

TEST(SslctlLatency, ReportsTheTimeSinceTheGatewayReceivedTheFramePerStage) {
  auto child = ChildProcess::start(bin_dir() / "sslctl",
                                   {"latency", "--domain", std::to_string(kDomain), "--listen", "4", "--json"});
  ASSERT_TRUE(child) << child.error().message;
  auto participant = value_of(dds::Participant::create({.domain_id = kDomain, .name = "sslctl_latency_test"}));
  auto vision = value_of(participant.make_writer(dds::topics::kVisionDetection));
  auto world = value_of(participant.make_writer(dds::topics::kWorldState, TeamColor::kBlue));
  auto commands = value_of(participant.make_writer(dds::topics::kRobotCommands, TeamColor::kBlue));
  auto sent = value_of(participant.make_writer(dds::topics::kRobotSent, TeamColor::kBlue));
  ASSERT_TRUE(vision.wait_for_match(1, kTimeout));
  ASSERT_TRUE(sent.wait_for_match(1, kTimeout));
  ASSERT_TRUE(world.wait_for_match(1, kTimeout));
  ASSERT_TRUE(commands.wait_for_match(1, kTimeout));
  constexpr std::int64_t kGatewayAgo = 5'000'000;  // ns
  for (int i = 0; i < 60; ++i) {
    idl::vision::DetectionFrame frame;
    frame.frame_number(static_cast<std::uint32_t>(i));
    frame.receive_unix_ns(now_ns() - kGatewayAgo);
    frame.capture_unix_ns(frame.receive_unix_ns() - 12'000'000);  // 12 ms vision delay
    ASSERT_TRUE(vision.write(frame));
    idl::world::WorldState state;
    state.stamp().receive_unix_ns(now_ns() - kGatewayAgo);
    ASSERT_TRUE(world.write(state));
    idl::robot::RobotCommands sample;
    sample.stamp().receive_unix_ns(now_ns() - kGatewayAgo);
    ASSERT_TRUE(commands.write(sample));
    idl::robot::CommandsSent out;
    out.stamp().receive_unix_ns(now_ns() - kGatewayAgo);
    out.sent_unix_ns(out.stamp().receive_unix_ns() + 4'000'000);
    ASSERT_TRUE(sent.write(out));
    out.resend(true);
    out.sent_unix_ns(out.stamp().receive_unix_ns() + 50'000'000);
    ASSERT_TRUE(sent.write(out));
    std::this_thread::sleep_for(10ms);  // paces the writes (100 Hz), not a wait for discovery
  }
  std::map<std::string, nlohmann::json> stages;
  while (auto line = child->read_line(kTimeout)) {
    const auto stage = nlohmann::json::parse(*line);
    stages[stage["stage"]] = stage;
  }
  EXPECT_EQ(child->wait(kTimeout), 0) << child->drain_stderr();
  for (const char* name : {"vision.detection", "world.state/blue", "robot.commands/blue"}) {
    ASSERT_TRUE(stages.count(name)) << name;
    EXPECT_GE(stages[name]["samples"].get<int>(), 50) << name;  // best effort: a few may be lost
    EXPECT_GE(stages[name]["p50_ms"].get<double>(), 5.0) << name;
    EXPECT_LT(stages[name]["p50_ms"].get<double>(), 50.0) << name;
  }
  const char* out = "command out of robot_link/blue";
  ASSERT_TRUE(stages.count(out));
  EXPECT_GE(stages[out]["samples"].get<int>(), 25);
  EXPECT_LE(stages[out]["samples"].get<int>(), 60) << "resends are not counted";
  EXPECT_NEAR(stages[out]["p50_ms"].get<double>(), 4.0, 1e-3);
  EXPECT_NEAR(stages[out]["max_ms"].get<double>(), 4.0, 1e-3) << "resends are not counted";
  ASSERT_TRUE(stages.count("vision delay"));
  EXPECT_NEAR(stages["vision delay"]["p50_ms"].get<double>(), 12.0, 1e-3);
  EXPECT_FALSE(stages.count("world.state/yellow")) << "no yellow samples were written";
  EXPECT_FALSE(stages.count("command out of robot_link/yellow"));
}

TEST(SslctlLatency, NothingToMeasureIsAnError) {
  auto child = ChildProcess::start(bin_dir() / "sslctl", {"latency", "--domain", "159", "--listen", "0.5"});
  ASSERT_TRUE(child) << child.error().message;
  EXPECT_EQ(child->wait(kTimeout), 1);
  EXPECT_NE(child->drain_stderr().find("no vision.detection, world.state, robot.commands or robot.sent sample"),
            std::string::npos);
}

}  // namespace
}  // namespace ssl::testing
