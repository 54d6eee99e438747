// The vision_gateway process between real processes: our simulator multicasts SSL_WrapperPackets on a
// private port, the gateway publishes them over DDS on a private domain, and `sslctl topic echo` (or a
// reader in this test, for system.health) checks what comes out: metres, camera ids, robots, geometry.
// Garbage, foreign senders and tracked vision are counted on system.health while publishing goes on; a
// silent group is reported as WARN; bad flags and configs exit non-zero. Each test has its own DDS domain
// (160-165) and ports (431xx-436xx). Nothing sleeps to wait for discovery: every wait is for data with a
// timeout.
#include <gtest/gtest.h>
#include <signal.h>

#include <array>
#include <chrono>
#include <cmath>
#include <functional>
#include <map>
#include <nlohmann/json.hpp>
#include <random>
#include <set>
#include <thread>

#include "libs/dds/participant.h"
#include "libs/league/decode.h"
#include "libs/net/multicast.h"
#include "libs/net/udp.h"
#include "tests/support/process.h"

namespace ssl::testing {
namespace {

using std::chrono::milliseconds;
using std::chrono::seconds;
using SteadyClock = std::chrono::steady_clock;
constexpr auto kTimeout = seconds(30);

/// Ports of one simulator instance (vision, control, blue, yellow, grsim) from a base.
struct Ports {
  int vision, control, blue, yellow, grsim;
  explicit Ports(int base)
      : vision(base), control(base + 1), blue(base + 2), yellow(base + 3), grsim(base + 4) {}
};

ChildProcess start(const std::string& program, const std::vector<std::string>& args) {
  auto child = ChildProcess::start(bin_dir() / program, args);
  EXPECT_TRUE(child) << child.error().message;
  return std::move(child).value();
}

ChildProcess start_simulator(const Ports& ports) {
  return start("simulator", {"--no-dds", "--mode", "realtime", "--realism", "none", "--interface",
                             "127.0.0.1", "--vision-port", std::to_string(ports.vision), "--control-port",
                             std::to_string(ports.control), "--blue-port", std::to_string(ports.blue),
                             "--yellow-port", std::to_string(ports.yellow), "--grsim-port",
                             std::to_string(ports.grsim), "--log-level", "warn"});
}

ChildProcess start_gateway(int vision_port, int domain, std::vector<std::string> extra = {}) {
  std::vector<std::string> args = {"--vision-port", std::to_string(vision_port),
                                   "--domain",      std::to_string(domain),
                                   "--interface",   "127.0.0.1",
                                   "--log-level",   "warn"};
  args.insert(args.end(), extra.begin(), extra.end());
  return start("vision_gateway", args);
}

/// Reads `count` JSON lines from a child, failing the test with its stderr when they do not come.
std::vector<nlohmann::json> read_json_lines(ChildProcess& child, std::size_t count) {
  std::vector<nlohmann::json> lines;
  while (lines.size() < count) {
    auto line = child.read_line(kTimeout);
    if (!line) {
      ADD_FAILURE() << "expected " << count << " lines, got " << lines.size()
                    << "; stderr: " << child.drain_stderr();
      break;
    }
    lines.push_back(nlohmann::json::parse(*line));
  }
  return lines;
}

std::vector<nlohmann::json> echo(const std::string& topic, int domain, int count) {
  auto sslctl = start("sslctl", {"topic", "echo", topic, "--domain", std::to_string(domain), "--count",
                                 std::to_string(count), "--timeout", "30"});
  auto lines = read_json_lines(sslctl, static_cast<std::size_t>(count));
  EXPECT_EQ(sslctl.wait(kTimeout), 0) << sslctl.drain_stderr();
  return lines;
}

void stop(ChildProcess& child) {
  child.signal(SIGTERM);
  EXPECT_EQ(child.wait(kTimeout), 0) << child.drain_stderr();
}

/// A value of the gateway's health counters (0 when absent).
std::uint64_t counter(const idl::system::Health& health, const std::string& name) {
  for (const auto& c : health.counters()) {
    if (c.name() == name) return c.value();
  }
  return 0;
}

/// A system.health reader of this test on one domain.
class HealthWatch {
 public:
  explicit HealthWatch(int domain) {
    auto participant = dds::Participant::create({.domain_id = domain, .name = "vision_gateway_process_test"});
    EXPECT_TRUE(participant) << participant.error().message;
    if (!participant) return;
    participant_.emplace(std::move(*participant));
    auto reader = participant_->make_reader(dds::topics::kSystemHealth);
    EXPECT_TRUE(reader) << reader.error().message;
    if (reader) reader_.emplace(std::move(*reader));
  }

  /// Reads until a vision_gateway sample satisfies `predicate`; returns it (nullopt and a failure on
  /// timeout).
  std::optional<idl::system::Health> wait(const std::function<bool(const idl::system::Health&)>& predicate,
                                          std::chrono::seconds timeout = seconds(30)) {
    if (!reader_) return std::nullopt;
    const auto deadline = SteadyClock::now() + timeout;
    std::optional<idl::system::Health> last;
    while (SteadyClock::now() < deadline) {
      reader_->wait_for_data(milliseconds(500));
      for (auto& sample : reader_->take()) {
        if (sample.data.service() != "vision_gateway") continue;
        last = sample.data;
        if (predicate(sample.data)) return sample.data;
      }
    }
    std::string counters;
    if (last) {
      for (const auto& c : last->counters()) counters += " " + c.name() + "=" + std::to_string(c.value());
    }
    ADD_FAILURE() << "no matching system.health sample; last: " << (last ? last->status() : "none") << ";"
                  << counters;
    return std::nullopt;
  }

 private:
  std::optional<dds::Participant> participant_;
  std::optional<dds::Reader<idl::system::Health>> reader_;
};

/// Sends a simulation control request until the simulator answers (it may still be starting).
bool teleport(int control_port, const SimulatorCommand& command) {
  auto socket = net::UdpSocket::open("127.0.0.1", 0);
  if (!socket) return false;
  const std::string bytes = command.SerializeAsString();
  std::array<std::uint8_t, 65536> buffer;
  const auto simulator = *net::Endpoint::from_parts("127.0.0.1", control_port);
  for (int attempt = 0; attempt < 50; ++attempt) {
    (void)socket->send_to(simulator, league::byte_span(bytes));
    const auto reply = socket->receive(buffer, milliseconds(200));
    if (!reply.ok()) continue;
    auto response = league::decode_simulator_response(std::span(buffer).first(reply.size));
    return response && response->errors_size() == 0;
  }
  return false;
}

std::int64_t now_unix_ns() {
  return std::chrono::duration_cast<std::chrono::nanoseconds>(
             std::chrono::system_clock::now().time_since_epoch())
      .count();
}

TEST(VisionGatewayProcess, PublishesSimulatorVisionPerCameraInMetresWithGeometry) {
  const Ports ports(23100);
  const int domain = 160;
  auto simulator = start_simulator(ports);
  auto gateway = start_gateway(ports.vision, domain);

  SimulatorCommand command;
  auto* robot = command.mutable_control()->add_teleport_robot();
  robot->mutable_id()->set_id(1);
  robot->mutable_id()->set_team(::BLUE);
  robot->set_x(2.0f);  // the simulation protocol speaks metres
  robot->set_y(-1.0f);
  robot->set_orientation(0.5f);
  auto* ball = command.mutable_control()->mutable_teleport_ball();
  ball->set_x(-1.0f);
  ball->set_y(0.5f);
  ASSERT_TRUE(teleport(ports.control, command)) << simulator.drain_stderr();

  const auto frames = echo("vision.detection", domain, 60);
  ASSERT_EQ(frames.size(), 60u);
  std::set<std::uint32_t> cameras;
  std::set<std::uint32_t> blue_ids;
  std::set<std::uint32_t> yellow_ids;
  bool robot_seen = false;
  bool ball_seen = false;
  std::map<std::uint32_t, std::uint32_t> newest_frame;
  for (const auto& frame : frames) {
    const std::uint32_t camera = frame["camera_id"];
    cameras.insert(camera);
    // Capture, sent and receive times are Unix ns on this host (realtime simulator), in order.
    const std::int64_t capture = frame["capture_unix_ns"];
    EXPECT_LT(std::abs(capture - now_unix_ns()), std::int64_t{60'000'000'000});
    EXPECT_GE(frame["sent_unix_ns"].get<std::int64_t>(), capture);
    EXPECT_GE(frame["receive_unix_ns"].get<std::int64_t>(), capture);
    EXPECT_EQ(frame["source"], "VISION_SOURCE_OTHER");
    for (const char* team : {"robots_blue", "robots_yellow"}) {
      for (const auto& r : frame[team]) {
        // Metres: every robot is on a 12 m x 9 m field (millimetres would be thousands).
        EXPECT_LE(std::abs(r["x"].get<double>()), 6.5);
        EXPECT_LE(std::abs(r["y"].get<double>()), 5.0);
        EXPECT_NEAR(r["height"].get<double>(), 0.143, 1e-6);
        (std::string(team) == "robots_blue" ? blue_ids : yellow_ids)
            .insert(r["robot_id"].get<std::uint32_t>());
      }
    }
    for (const auto& r : frame["robots_blue"]) {
      if (r["robot_id"] == 1 && std::abs(r["x"].get<double>() - 2.0) < 0.005 &&
          std::abs(r["y"].get<double>() + 1.0) < 0.005 &&
          std::abs(r["orientation"].get<double>() - 0.5) < 0.01) {
        robot_seen = true;
      }
    }
    for (const auto& b : frame["balls"]) {
      if (std::abs(b["x"].get<double>() + 1.0) < 0.005 && std::abs(b["y"].get<double>() - 0.5) < 0.005) {
        ball_seen = true;
      }
    }
    // Frames of one camera come out in order, never twice.
    const std::uint32_t number = frame["frame_number"];
    if (newest_frame.contains(camera)) {
      EXPECT_GT(number, newest_frame[camera]);
    }
    newest_frame[camera] = number;
  }
  EXPECT_EQ(cameras, (std::set<std::uint32_t>{0, 1, 2, 3}));
  EXPECT_EQ(blue_ids.size(), 11u);
  EXPECT_EQ(yellow_ids.size(), 11u);
  EXPECT_TRUE(robot_seen) << "blue 1 not seen at (2.0, -1.0) m";
  EXPECT_TRUE(ball_seen) << "ball not seen at (-1.0, 0.5) m";

  // Geometry: transient local, so this late reader gets the one published sample.
  const auto geometry = echo("vision.geometry", domain, 1);
  ASSERT_EQ(geometry.size(), 1u);
  const auto& field = geometry[0]["field"];
  EXPECT_DOUBLE_EQ(field["field_length"].get<double>(), 12.0);
  EXPECT_DOUBLE_EQ(field["field_width"].get<double>(), 9.0);
  EXPECT_DOUBLE_EQ(field["goal_width"].get<double>(), 1.8);
  EXPECT_DOUBLE_EQ(field["penalty_area_depth"].get<double>(), 1.8);
  EXPECT_DOUBLE_EQ(field["center_circle_radius"].get<double>(), 0.5);
  EXPECT_EQ(field["lines"].size(), 12u);
  EXPECT_EQ(field["arcs"].size(), 1u);
  EXPECT_DOUBLE_EQ(field["arcs"][0]["radius"].get<double>(), 0.5);
  EXPECT_TRUE(field["defaulted_fields"].empty()) << field["defaulted_fields"];  // our simulator sends all
  EXPECT_EQ(geometry[0]["calibrations"].size(), 4u);
  EXPECT_NEAR(geometry[0]["calibrations"][0]["tz"].get<double>(), 4.0, 1e-6);  // camera height, metres

  // Geometry is published once, not with every geometry packet (one per second from the simulator).
  HealthWatch health_watch(domain);
  const auto health =
      health_watch.wait([](const idl::system::Health& h) { return counter(h, "geometry_packets") >= 3; });
  ASSERT_TRUE(health);
  EXPECT_EQ(counter(*health, "geometry_updates"), 1u);
  EXPECT_EQ(health->level(), idl::system::HEALTH_OK) << health->status();
  EXPECT_GT(health->rate_hz(), 100.0);  // 4 cameras at 75 Hz; wide bounds: not a performance check
  EXPECT_GT(health->latency_p99(), 0.0);
  EXPECT_EQ(counter(*health, "duplicates"), 0u);
  EXPECT_EQ(counter(*health, "malformed"), 0u);

  stop(gateway);
  stop(simulator);
}

TEST(VisionGatewayProcess, GarbageAndForeignSendersAreCountedWhilePublishingGoesOn) {
  const Ports ports(23200);
  const int domain = 161;
  auto simulator = start_simulator(ports);
  auto gateway = start_gateway(ports.vision, domain);
  HealthWatch health_watch(domain);
  // First the gateway locks onto the simulator.
  ASSERT_TRUE(health_watch.wait([](const auto& h) { return counter(h, "frames_published") > 0; }));

  auto sender = net::MulticastSender::open("224.5.23.2", ports.vision, "127.0.0.1");
  ASSERT_TRUE(sender) << sender.error().message;
  std::mt19937 random(11);
  constexpr int kGarbage = 300;
  const auto burst_start = std::chrono::steady_clock::now();
  for (int i = 0; i < kGarbage; ++i) {
    std::vector<std::uint8_t> bytes(1 + random() % 200);
    for (auto& byte : bytes) byte = static_cast<std::uint8_t>(random() | 0x80);  // unterminated varints
    ASSERT_TRUE(sender->send(bytes).ok());
    // Paced, so that the burst never overflows the gateway's socket buffer (an exact count is checked).
    std::this_thread::sleep_for(milliseconds(1));
  }
  const double burst_seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - burst_start).count();
  // Valid packets from another sender (this test): a stray vision source.
  constexpr int kForeign = 20;
  for (int i = 0; i < kForeign; ++i) {
    SSL_WrapperPacket packet;
    auto* frame = packet.mutable_detection();
    frame->set_frame_number(1'000'000 + i);
    frame->set_t_capture(1.78e9);
    frame->set_t_sent(1.78e9);
    frame->set_camera_id(0);
    ASSERT_TRUE(sender->send(league::byte_span(packet.SerializeAsString())).ok());
  }

  // On a loaded machine the kernel may drop a few loopback datagrams while the gateway waits for a CPU, so
  // this accepts 90 %; exact counting is checked without sockets by the VisionGatewayMalformed tests.
  const auto health = health_watch.wait([](const idl::system::Health& h) {
    return counter(h, "malformed") >= kGarbage * 9 / 10 && counter(h, "foreign_source") >= kForeign * 9 / 10;
  });
  ASSERT_TRUE(health);
  EXPECT_LE(counter(*health, "malformed"), static_cast<std::uint64_t>(kGarbage));
  EXPECT_LE(counter(*health, "foreign_source"), static_cast<std::uint64_t>(kForeign));
  EXPECT_GE(health->dropped(), counter(*health, "malformed") + counter(*health, "foreign_source"));
  EXPECT_EQ(health->level(), idl::system::HEALTH_OK) << health->status();

  // Still publishing the simulator's frames, none of the stray's (frame numbers from 1,000,000).
  for (const auto& frame : echo("vision.detection", domain, 20)) {
    EXPECT_LT(frame["frame_number"].get<std::uint32_t>(), 1'000'000u);
  }
  const auto later = health_watch.wait([&](const idl::system::Health& h) {
    return counter(h, "frames_published") > counter(*health, "frames_published") + 100;
  });
  EXPECT_TRUE(later);

  stop(gateway);
  // Malformed packets are logged at a throttled rate (one line per second): a burst of 300 gives a line per
  // started second of the burst (0.3 s on a quiet machine, longer when it is loaded) plus the summary.
  int malformed_lines = 0;
  while (auto line = gateway.read_line(milliseconds(100))) {
    if (line->find("malformed vision packet") != std::string::npos) ++malformed_lines;
  }
  EXPECT_GE(malformed_lines, 1);
  EXPECT_LE(malformed_lines, static_cast<int>(std::ceil(burst_seconds)) + 2) << "burst took " << burst_seconds << " s";
  EXPECT_LT(malformed_lines, kGarbage / 10);
  stop(simulator);
}

TEST(VisionGatewayProcess, SilentGroupIsReportedAsWarn) {
  const int domain = 162;
  auto gateway = start_gateway(23300, domain);
  HealthWatch health_watch(domain);
  const auto health = health_watch.wait([](const auto&) { return true; });
  ASSERT_TRUE(health);
  EXPECT_EQ(health->level(), idl::system::HEALTH_WARN) << health->status() << "; errors " << health->errors();
  EXPECT_NE(health->status().find("no vision"), std::string::npos) << health->status();
  EXPECT_EQ(health->rate_hz(), 0.0) << health->status();
  stop(gateway);
}

TEST(VisionGatewayProcess, FixedSourceIgnoresEveryOtherHost) {
  const Ports ports(23400);
  const int domain = 163;
  auto simulator = start_simulator(ports);  // sends from 127.0.0.1
  auto gateway = start_gateway(ports.vision, domain, {"--set", "source=127.0.0.2"});
  HealthWatch health_watch(domain);
  const auto health = health_watch.wait([](const auto& h) { return counter(h, "foreign_source") > 100; });
  ASSERT_TRUE(health);
  EXPECT_EQ(counter(*health, "frames_published"), 0u);
  EXPECT_EQ(health->level(), idl::system::HEALTH_WARN);
  stop(gateway);
  stop(simulator);
}

TEST(VisionGatewayProcess, RestartedSimulatorIsFollowedAfterTheSourceTimeout) {
  const Ports ports(23600);
  const int domain = 165;
  auto gateway = start_gateway(ports.vision, domain);
  HealthWatch health_watch(domain);
  std::optional<ChildProcess> simulator = start_simulator(ports);
  const auto before = health_watch.wait([](const auto& h) { return counter(h, "frames_published") > 0; });
  ASSERT_TRUE(before);
  stop(*simulator);
  simulator.reset();
  // A new process sends from a new port: auto selection takes it once the old sender was silent for
  // source_timeout (1 s); its frame numbers start again without being "out of order".
  simulator.emplace(start_simulator(ports));
  const auto after = health_watch.wait([](const idl::system::Health& h) {
    return counter(h, "source_switches") == 1 && h.level() == idl::system::HEALTH_OK && h.rate_hz() > 100;
  });
  ASSERT_TRUE(after);
  EXPECT_EQ(counter(*after, "out_of_order"), 0u);
  EXPECT_GT(counter(*after, "frames_published"), counter(*before, "frames_published"));
  stop(*simulator);
  stop(gateway);
}

TEST(VisionGatewayProcess, TrackedVisionIsDecodedAndCountedWhenEnabled) {
  const int domain = 164;
  const int vision_port = 23500;
  const int tracker_port = 23501;
  auto gateway = start_gateway(
      vision_port, domain,
      {"--set", "tracker.enabled=true", "--set", "tracker.port=" + std::to_string(tracker_port)});
  HealthWatch health_watch(domain);
  ASSERT_TRUE(health_watch.wait([](const auto&) { return true; }));  // the gateway is up

  auto sender = net::MulticastSender::open("224.5.23.2", tracker_port, "127.0.0.1");
  ASSERT_TRUE(sender);
  for (std::uint32_t i = 0; i < 10; ++i) {
    TrackerWrapperPacket packet;
    packet.set_uuid("5e1f");
    packet.set_source_name("TestTracker");
    packet.mutable_tracked_frame()->set_frame_number(i);
    packet.mutable_tracked_frame()->set_timestamp(1.78e9 + i * 0.01);
    ASSERT_TRUE(sender->send(league::byte_span(packet.SerializeAsString())).ok());
  }
  const std::uint8_t garbage[] = {0x0a, 0xff, 0xff};
  for (int i = 0; i < 5; ++i) ASSERT_TRUE(sender->send(garbage).ok());

  const auto health = health_watch.wait([](const idl::system::Health& h) {
    return counter(h, "tracker_packets") >= 10 && counter(h, "tracker_malformed") >= 5;
  });
  ASSERT_TRUE(health);
  EXPECT_EQ(counter(*health, "tracker_packets"), 10u);
  EXPECT_EQ(counter(*health, "tracker_frames"), 10u);
  EXPECT_EQ(counter(*health, "tracker_sources"), 1u);
  EXPECT_EQ(counter(*health, "tracker_malformed"), 5u);
  EXPECT_NE(health->status().find("tracker: TestTracker"), std::string::npos) << health->status();
  stop(gateway);
}

TEST(VisionGatewayProcess, BadFlagsAndConfigsExitNonZeroWithAClearMessage) {
  auto unknown = start("vision_gateway", {"--no-such-flag"});
  const auto unknown_code = unknown.wait(kTimeout);
  ASSERT_TRUE(unknown_code);
  EXPECT_NE(*unknown_code, 0);
  EXPECT_NE(unknown.drain_stderr().find("--no-such-flag"), std::string::npos);

  auto missing = start("vision_gateway", {"--config", "/nonexistent/vision_gateway.yaml"});
  EXPECT_EQ(missing.wait(kTimeout), 1);
  std::string out;
  while (auto line = missing.read_line(milliseconds(100))) out += *line;
  EXPECT_NE((out + missing.drain_stderr()).find("/nonexistent/vision_gateway.yaml"), std::string::npos)
      << out;

  auto bad_port = start("vision_gateway", {"--vision-port", "70000"});
  EXPECT_EQ(bad_port.wait(kTimeout), 1);
  out.clear();
  while (auto line = bad_port.read_line(milliseconds(100))) out += *line;
  EXPECT_NE((out + bad_port.drain_stderr()).find("network.vision_port"), std::string::npos) << out;

  auto help = start("vision_gateway", {"--help"});
  out.clear();
  while (auto line = help.read_line(seconds(5))) out += *line + "\n";
  EXPECT_EQ(help.wait(kTimeout), 0);
  for (const char* flag : {"--config", "--domain", "--interface", "--log-level", "--vision-port"}) {
    EXPECT_NE(out.find(flag), std::string::npos) << flag;
  }

  auto printed =
      start("vision_gateway", {"--print-config", "--vision-port", "23999", "--set", "source=10.0.0.8",
                               "--interface", "10.0.0.7", "--set", "tracker.enabled=true"});
  out.clear();
  while (auto line = printed.read_line(seconds(5))) out += *line + "\n";
  EXPECT_EQ(printed.wait(kTimeout), 0);
  EXPECT_NE(out.find("vision_port: 23999"), std::string::npos) << out;
  EXPECT_NE(out.find("interface: \"10.0.0.7\""), std::string::npos) << out;
  EXPECT_NE(out.find("source: \"10.0.0.8\""), std::string::npos) << out;
  EXPECT_NE(out.find("enabled: true"), std::string::npos) << out;
}

}  // namespace
}  // namespace ssl::testing
