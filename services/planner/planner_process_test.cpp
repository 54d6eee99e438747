// The planner as a real process, end to end through DDS, on its own domains (230, 231; 232 and 188 for the
// in-process node tests). `sslctl topic pub` stands in for world_model (world.state with robots and a ball)
// and referee_gateway (referee.state HALT, then STOP); a DDS reader here (and `sslctl topic echo`) reads
// robot.commands and planner.debug. Checked: HALT gives all-zero commands; STOP keeps every robot at or
// below 1.5 m/s; commands carry the world state's VisionStamp; planner.debug names the play; without
// world.state nothing is published and health says "no world state"; the command line (--help, unknown
// flags, a broken config, --print-config, --print-tree). Waits only for matches and data, with timeouts.
#include <gtest/gtest.h>
#include <signal.h>

#include <array>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <limits>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <thread>

#include "libs/common/deploy_files.h"
#include "libs/dds/participant.h"
#include "libs/time/clock.h"
#include "services/planner/adapter/planner_node.h"
#include "tests/support/process.h"

namespace ssl::planner {
namespace {

using namespace std::chrono_literals;
using testing::ChildProcess;
using testing::bin_dir;
using SteadyClock = std::chrono::steady_clock;

constexpr auto kTimeout = 30s;
constexpr std::int64_t kCaptureNs = 1'700'000'000'123'456'789;
constexpr std::int64_t kReceiveNs = 1'700'000'000'124'000'000;
constexpr std::uint32_t kFrameNumber = 4711;
constexpr std::uint32_t kCameraId = 2;

ChildProcess start(const std::string& program, const std::vector<std::string>& args) {
  auto child = ChildProcess::start(bin_dir() / program, args);
  EXPECT_TRUE(child) << child.error().message;
  return std::move(child).value();
}

ChildProcess start_planner(int domain, std::vector<std::string> extra = {}) {
  std::vector<std::string> args = {"--team", "blue", "--domain", std::to_string(domain), "--log-level", "info"};
  args.insert(args.end(), extra.begin(), extra.end());
  return start("planner", args);
}

/// Blue's world in blue's team frame: three robots (robot 1 right next to the ball), a ball, two enemies.
std::string world_json() {
  nlohmann::json robot = {{"pose", {{"x", -4.0}, {"y", 0.0}, {"theta", 0.0}}}, {"visible", true}, {"confidence", 1.0}};
  nlohmann::json world = {
      {"team", "TEAM_COLOR_BLUE"},
      {"sequence_number", 1},
      {"stamp",
       {{"capture_unix_ns", kCaptureNs}, {"receive_unix_ns", kReceiveNs}, {"camera_id", kCameraId},
        {"frame_number", kFrameNumber}}},
      {"publish_unix_ns", kReceiveNs},
      {"has_ball", true},
      {"ball", {{"position", {{"x", 0.0}, {"y", 0.0}, {"z", 0.0215}}}, {"visible", true}, {"confidence", 1.0}}},
      {"possession", "POSSESSION_NONE"}};
  const double positions[][3] = {{0, -5.5, 0.0}, {1, 0.15, 0.05}, {2, -2.0, 1.5}};
  for (const auto& p : positions) {
    robot["id"] = static_cast<int>(p[0]);
    robot["pose"] = {{"x", p[1]}, {"y", p[2]}, {"theta", 0.0}};
    world["friendly"].push_back(robot);
  }
  for (const auto& p : {std::array{3.0, 1.0}, std::array{2.0, -1.0}}) {
    robot["id"] = static_cast<int>(world["enemy"].size());
    robot["pose"] = {{"x", p[0]}, {"y", p[1]}, {"theta", 3.14}};
    world["enemy"].push_back(robot);
  }
  return world.dump();
}

ChildProcess publish_world(int domain, int repeat) {
  return start("sslctl", {"topic", "pub", "world.state", "--team", "blue", "--domain", std::to_string(domain),
                          "--wait-readers", "1", "--wait-timeout", "30", "--repeat", std::to_string(repeat),
                          "--rate", "100", world_json()});
}

ChildProcess publish_referee(int domain, const std::string& command, int counter) {
  const nlohmann::json state = {{"command", command}, {"command_counter", counter},
                                {"has_blue_team_on_positive_half", true}, {"blue_team_on_positive_half", false}};
  return start("sslctl", {"topic", "pub", "referee.state", "--domain", std::to_string(domain), "--wait-readers",
                          "1", "--wait-timeout", "30", "--linger", "-1", state.dump()});
}

std::string output_of(ChildProcess& child) { return child.drain_stderr(); }

double speed(const idl::robot::RobotCommand& c) { return std::hypot(c.forward(), c.left()); }

bool all_zero(const idl::robot::RobotCommands& commands) {
  for (const auto& c : commands.commands()) {
    if (c.forward() != 0 || c.left() != 0 || c.angular() != 0 || c.kick() != idl::robot::KICK_NONE ||
        c.kick_speed() != 0 || c.dribbler_rpm() != 0) {
      return false;
    }
  }
  return true;
}

/// A test-side participant with readers of blue's robot.commands and planner.debug.
struct Observer {
  explicit Observer(int domain) {
    auto p = dds::Participant::create({.domain_id = domain, .name = "planner_process_test"});
    EXPECT_TRUE(p) << p.error().message;
    participant.emplace(std::move(*p));
    auto c = participant->make_reader(dds::topics::kRobotCommands, TeamColor::kBlue);
    auto d = participant->make_reader(dds::topics::kPlannerDebug, TeamColor::kBlue);
    EXPECT_TRUE(c && d);
    commands.emplace(std::move(*c));
    debug.emplace(std::move(*d));
  }

  /// Reads robot.commands until `predicate` holds for one sample (nullopt on timeout); the newest
  /// planner.debug play is kept in `play`.
  template <typename Predicate>
  std::optional<idl::robot::RobotCommands> wait_for(Predicate predicate, std::chrono::milliseconds timeout) {
    const auto deadline = SteadyClock::now() + timeout;
    while (SteadyClock::now() < deadline) {
      commands->wait_for_data(50ms);
      take_debug();
      for (auto& s : commands->take()) {
        ++received;
        if (predicate(s.data)) return std::move(s.data);
      }
    }
    return std::nullopt;
  }

  void take_debug() {
    for (auto& s : debug->take()) {
      play = s.data.play();
      last_debug = std::move(s.data);
      ++debug_received;
    }
  }

  std::optional<dds::Participant> participant;
  std::optional<dds::Reader<idl::robot::RobotCommands>> commands;
  std::optional<dds::Reader<idl::planner::PlannerDebug>> debug;
  std::string play;
  idl::planner::PlannerDebug last_debug;
  std::uint64_t received = 0;
  std::uint64_t debug_received = 0;
};

bool has_world_stamp(const idl::robot::RobotCommands& c) {
  return c.stamp().frame_number() == kFrameNumber && c.commands().size() == 3;
}

TEST(PlannerProcess, HaltStopsEveryRobotAndStopKeepsThemSlowWithTheWorldStamp) {
  constexpr int kDomain = 230;
  auto planner = start_planner(kDomain);
  Observer observer(kDomain);
  ASSERT_TRUE(observer.commands->wait_for_match(1, kTimeout)) << "planner never offered robot.commands\n"
                                                              << output_of(planner);
  auto halt = publish_referee(kDomain, "COMMAND_HALT", 1);
  auto world = publish_world(kDomain, 6000);

  // HALT: every command is zero, whatever the world looks like.
  auto first = observer.wait_for(has_world_stamp, kTimeout);
  ASSERT_TRUE(first) << "no robot.commands computed from our world.state\nplanner: " << output_of(planner)
                     << "\nworld: " << output_of(world);
  EXPECT_EQ(first->team(), idl::common::TEAM_COLOR_BLUE);
  EXPECT_EQ(first->stamp().capture_unix_ns(), kCaptureNs);
  EXPECT_EQ(first->stamp().receive_unix_ns(), kReceiveNs);
  EXPECT_EQ(first->stamp().camera_id(), kCameraId);
  EXPECT_GT(first->publish_unix_ns(), kReceiveNs);
  EXPECT_GT(first->sequence_number(), 0u);
  std::uint64_t previous_sequence = first->sequence_number();
  int halted = 0;
  observer.wait_for(
      [&](const idl::robot::RobotCommands& c) {
        EXPECT_GT(c.sequence_number(), previous_sequence);
        previous_sequence = c.sequence_number();
        if (!has_world_stamp(c)) return false;
        EXPECT_TRUE(all_zero(c)) << "a command moves under HALT";
        return ++halted >= 30;
      },
      kTimeout);
  EXPECT_GE(halted, 30);
  observer.take_debug();
  EXPECT_NE(observer.play.find("halt"), std::string::npos) << "planner.debug play under HALT: " << observer.play;
  EXPECT_EQ(observer.last_debug.stamp().frame_number(), kFrameNumber);
  EXPECT_FALSE(observer.last_debug.tree().empty());

  // STOP: robots move (robot 1 stands next to the ball) but never faster than 1.5 m/s.
  halt.signal(SIGTERM);
  EXPECT_EQ(halt.wait(kTimeout), 0) << output_of(halt);
  auto stop = publish_referee(kDomain, "COMMAND_STOP", 2);
  ASSERT_TRUE(observer.wait_for([&](const auto&) { return observer.play == "stop"; }, kTimeout))
      << "planner.debug never showed the stop play; last play '" << observer.play << "'\n" << output_of(planner);
  double fastest = 0;
  int stopped_ticks = 0;
  observer.wait_for(
      [&](const idl::robot::RobotCommands& c) {
        for (const auto& command : c.commands()) {
          EXPECT_LE(speed(command), 1.5) << "robot " << command.id() << " too fast during STOP";
          fastest = std::max(fastest, speed(command));
        }
        return ++stopped_ticks >= 100;
      },
      kTimeout);
  EXPECT_GE(stopped_ticks, 100);
  EXPECT_GT(fastest, 0.0) << "nobody moves during STOP although robot 1 is 0.16 m from the ball";

  // The CLI sees the same: one robot.commands sample as JSON with the world's stamp.
  auto echo = start("sslctl", {"topic", "echo", "robot.commands", "--team", "blue", "--domain",
                               std::to_string(kDomain), "--count", "1", "--timeout", "30"});
  const auto line = echo.read_line(kTimeout);
  ASSERT_TRUE(line) << echo.drain_stderr();
  const auto json = nlohmann::json::parse(*line);
  EXPECT_EQ(json["team"], "TEAM_COLOR_BLUE");
  EXPECT_EQ(json["stamp"]["frame_number"], kFrameNumber);
  EXPECT_EQ(json["commands"].size(), 3u);
  EXPECT_EQ(echo.wait(kTimeout), 0);

  for (ChildProcess* child : {&world, &stop}) child->signal(SIGTERM);
  planner.signal(SIGTERM);
  EXPECT_EQ(planner.wait(kTimeout), 0) << output_of(planner);
}

std::optional<nlohmann::json> planner_health(int domain, const std::string& wanted_status) {
  // sslctl health prints one JSON object per service it heard within --listen.
  for (int attempt = 0; attempt < 10; ++attempt) {
    auto health = start("sslctl", {"health", "--json", "--listen", "2", "--domain", std::to_string(domain)});
    while (auto line = health.read_line(10s)) {
      auto json = nlohmann::json::parse(*line, nullptr, false);
      if (json.is_object() && json.value("service", "") == "planner/blue" &&
          json.value("status", "") == wanted_status) {
        return json;
      }
    }
    health.wait(10s);
  }
  return std::nullopt;
}

std::uint64_t counter(const nlohmann::json& health, const std::string& name) {
  for (const auto& c : health["counters"]) {
    if (c["name"] == name) return c["value"].get<std::uint64_t>();
  }
  return 0;
}

TEST(PlannerProcess, WithoutWorldStatePublishesNothingAndWarns) {
  constexpr int kDomain = 231;
  auto planner = start_planner(kDomain);
  Observer observer(kDomain);
  ASSERT_TRUE(observer.commands->wait_for_match(1, kTimeout)) << output_of(planner);
  auto stop = publish_referee(kDomain, "COMMAND_STOP", 1);

  const auto warn = planner_health(kDomain, "no world state");
  ASSERT_TRUE(warn) << "no health WARN 'no world state' from planner/blue\n" << output_of(planner);
  EXPECT_EQ((*warn)["level"], "HEALTH_WARN");
  EXPECT_EQ(counter(*warn, "ticks"), 0u);
  observer.commands->wait_for_data(200ms);
  EXPECT_TRUE(observer.commands->take().empty()) << "robot.commands without any world.state";

  // World states come: commands flow and health turns OK.
  auto world = publish_world(kDomain, 200);  // 2 s at 100 Hz
  ASSERT_TRUE(observer.wait_for(has_world_stamp, kTimeout)) << output_of(planner);
  EXPECT_EQ(world.wait(kTimeout), 0) << output_of(world);

  // They stop: so do the commands (within the 0.1 s stale timeout plus scheduling), and health warns again.
  observer.commands->wait_for_data(300ms);
  (void)observer.commands->take();
  observer.commands->wait_for_data(500ms);
  EXPECT_TRUE(observer.commands->take().empty()) << "robot.commands after world.state stopped";
  const auto again = planner_health(kDomain, "no world state");
  ASSERT_TRUE(again);
  EXPECT_GT(counter(*again, "ticks"), 0u);
  EXPECT_EQ(counter(*again, "inputs_rejected"), 0u);

  stop.signal(SIGTERM);
  planner.signal(SIGTERM);
  EXPECT_EQ(planner.wait(kTimeout), 0) << output_of(planner);
}

TEST(PlannerProcess, CommandLine) {
  auto help = start("planner", {"--help"});
  std::string text;
  while (auto line = help.read_line(10s)) text += *line + "\n";
  EXPECT_EQ(help.wait(kTimeout), 0);
  for (const char* flag : {"--config", "--domain", "--interface", "--log-level", "--team", "--set",
                           "--print-config", "--print-tree", "--dot"}) {
    EXPECT_NE(text.find(flag), std::string::npos) << flag << " missing from --help:\n" << text;
  }

  auto unknown = start("planner", {"--frobnicate"});
  EXPECT_NE(unknown.wait(kTimeout), 0);
  EXPECT_NE(unknown.drain_stderr().find("frobnicate"), std::string::npos);

  auto bad_team = start("planner", {"--team", "green"});
  EXPECT_NE(bad_team.wait(kTimeout), 0);

  const std::string broken = ::testing::TempDir() + "planner_broken.yaml";
  {
    auto path = find_deploy_file("config/planner.yaml");
    ASSERT_TRUE(path) << path.error().message;
    std::ifstream deployed(*path);
    ASSERT_TRUE(deployed) << *path;
    std::string yaml((std::istreambuf_iterator<char>(deployed)), std::istreambuf_iterator<char>());
    yaml.replace(yaml.find("stop_speed: 1.5"), 15, "stop_speed: 2.5");
    std::ofstream(broken) << yaml;
  }
  auto bad_config = start("planner", {"--config", broken});
  std::string error;  // the log (stdout) names the file, line and key
  while (auto line = bad_config.read_line(10s)) error += *line + "\n";
  EXPECT_EQ(bad_config.wait(kTimeout), 1);
  error += bad_config.drain_stderr();
  EXPECT_NE(error.find("planner.stop_speed"), std::string::npos) << error;
  EXPECT_NE(error.find(broken), std::string::npos) << error;
  std::remove(broken.c_str());

  auto missing = start("planner", {"--config", "/nonexistent/planner.yaml"});
  EXPECT_EQ(missing.wait(kTimeout), 1);

  auto print = start("planner", {"--print-config", "--team", "yellow", "--set", "tick_rate=50"});
  std::string printed;
  while (auto line = print.read_line(10s)) printed += *line + "\n";
  EXPECT_EQ(print.wait(kTimeout), 0);
  EXPECT_NE(printed.find("team: yellow"), std::string::npos) << printed;
  EXPECT_NE(printed.find("tick_rate: 50"), std::string::npos) << printed;

  auto tree = start("planner", {"--print-tree"});
  std::string ascii;
  while (auto line = tree.read_line(10s)) ascii += *line + "\n";
  EXPECT_EQ(tree.wait(kTimeout), 0) << tree.drain_stderr();
  EXPECT_FALSE(ascii.empty());

  auto dot = start("planner", {"--print-tree", "--dot"});
  std::string graph;
  while (auto line = dot.read_line(10s)) graph += *line + "\n";
  EXPECT_EQ(dot.wait(kTimeout), 0) << dot.drain_stderr();
  EXPECT_NE(graph.find("digraph"), std::string::npos) << graph;
}

// The node in-process with the deployed planner config, on `clock`.
Result<PlannerNode> deployed_node(dds::Participant& participant, time::Clock& clock) {
  auto path = find_deploy_file("config/planner.yaml");
  if (!path) return path.error();
  auto config = load_planner_config(*path, {});
  if (!config) return config.error();
  return PlannerNode::create(participant, *config, clock);
}

// The node in-process (domain 232) with a simulated clock: inputs with NaN are rejected and counted, and
// nothing computed from them is published; a good world state then ticks.
TEST(PlannerNodeInProcess, NonFiniteInputsAreRejectedAndCounted) {
  constexpr int kDomain = 232;
  auto participant = dds::Participant::create({.domain_id = kDomain, .name = "planner_node_test"});
  ASSERT_TRUE(participant) << participant.error().message;
  time::SimulatedClock clock(time::Timestamp::from_seconds(1.7e9));
  auto node = deployed_node(*participant, clock);
  ASSERT_TRUE(node) << node.error().message;
  auto world_writer = participant->make_writer(dds::topics::kWorldState, TeamColor::kBlue);
  auto referee_writer = participant->make_writer(dds::topics::kRefereeState);
  auto commands = participant->make_reader(dds::topics::kRobotCommands, TeamColor::kBlue);
  ASSERT_TRUE(world_writer && referee_writer && commands);
  ASSERT_TRUE(world_writer->wait_for_match(1, kTimeout));
  ASSERT_TRUE(referee_writer->wait_for_match(1, kTimeout));
  ASSERT_TRUE(commands->wait_for_match(1, kTimeout));

  auto poll_until = [&](auto done) {
    const auto deadline = SteadyClock::now() + 10s;
    while (!done() && SteadyClock::now() < deadline) {
      node->poll();
      std::this_thread::sleep_for(1ms);  // polling for data that is on its way, not for discovery
    }
    return done();
  };

  idl::referee::RefereeState referee;
  referee.command(idl::referee::COMMAND_STOP);
  referee.has_designated_position(true);
  referee.designated_position().x(std::nan(""));
  ASSERT_TRUE(referee_writer->write(referee));
  ASSERT_TRUE(poll_until([&] { return node->counters().referee_rejected == 1; }));

  idl::world::WorldState world;
  world.team(idl::common::TEAM_COLOR_BLUE);
  world.stamp().frame_number(9);
  idl::world::RobotState robot;
  robot.id(1);
  robot.pose().x(std::numeric_limits<double>::infinity());
  world.friendly().push_back(robot);
  ASSERT_TRUE(world_writer->write(world));
  ASSERT_TRUE(poll_until([&] { return node->counters().world_rejected == 1; }));

  idl::world::WorldState yellow = world;
  yellow.team(idl::common::TEAM_COLOR_YELLOW);
  yellow.friendly()[0].pose().x(-1.0);
  ASSERT_TRUE(world_writer->write(yellow));
  ASSERT_TRUE(poll_until([&] { return node->counters().world_rejected == 2; }));
  EXPECT_EQ(node->counters().ticks, 0u);
  EXPECT_TRUE(commands->take().empty());

  world.friendly()[0].pose().x(-1.0);
  ASSERT_TRUE(world_writer->write(world));
  ASSERT_TRUE(poll_until([&] { return node->counters().ticks == 1; }));
  ASSERT_TRUE(commands->wait_for_data(kTimeout));
  auto sample = commands->take_latest();
  ASSERT_TRUE(sample);
  EXPECT_EQ(sample->data.stamp().frame_number(), 9u);
  EXPECT_EQ(node->counters().inputs_rejected(), 3u);

  // The simulated clock moves past stale_world_timeout: no more ticks without a new world.state.
  clock.advance(std::chrono::milliseconds(500));
  for (int i = 0; i < 10; ++i) node->poll();
  EXPECT_EQ(node->counters().ticks, 1u);
}

// The node in-process (domain 188) on a simulated clock that never moves: every world.state is planned on
// as soon as it is taken, however soon after the previous tick (no hold-off), and its commands carry that
// sample's stamp.
TEST(PlannerNodeInProcess, EveryWorldStateIsPlannedOnAtOnce) {
  constexpr int kDomain = 188;
  auto participant = dds::Participant::create({.domain_id = kDomain, .name = "planner_node_at_once_test"});
  ASSERT_TRUE(participant) << participant.error().message;
  time::SimulatedClock clock(time::Timestamp::from_seconds(1.7e9));
  auto node = deployed_node(*participant, clock);
  ASSERT_TRUE(node) << node.error().message;
  auto world_writer = participant->make_writer(dds::topics::kWorldState, TeamColor::kBlue);
  auto commands = participant->make_reader(dds::topics::kRobotCommands, TeamColor::kBlue);
  ASSERT_TRUE(world_writer && commands);
  ASSERT_TRUE(world_writer->wait_for_match(1, kTimeout));
  ASSERT_TRUE(commands->wait_for_match(1, kTimeout));

  idl::world::WorldState world;
  world.team(idl::common::TEAM_COLOR_BLUE);
  idl::world::RobotState robot;
  robot.id(1);
  robot.visible(true);
  robot.pose().x(-1.0);
  world.friendly().push_back(robot);
  for (std::uint32_t frame = 1; frame <= 3; ++frame) {
    world.stamp().frame_number(frame);
    ASSERT_TRUE(world_writer->write(world));
    const auto deadline = SteadyClock::now() + 10s;
    while (node->counters().ticks < frame && SteadyClock::now() < deadline) {
      node->poll();
      std::this_thread::sleep_for(1ms);  // polling for data that is on its way, not for discovery
    }
    ASSERT_EQ(node->counters().ticks, frame) << "the same simulated instant as the previous tick";
    ASSERT_TRUE(commands->wait_for_data(kTimeout));
    auto sample = commands->take_latest();
    ASSERT_TRUE(sample);
    EXPECT_EQ(sample->data.stamp().frame_number(), frame);
  }
}

}  // namespace
}  // namespace ssl::planner
