// robot_link as a process, end to end through DDS: a planner stand-in (`sslctl topic pub robot.commands`)
// drives robot 0 forward; a UdpSocket stands in for the simulator and timestamps the RobotControl
// datagrams robot_link sends. Killing the planner (SIGKILL) must stop the robot within the watchdog's
// 100 ms plus one send period (a functional bound with a small scheduling margin, not a benchmark); the
// e-stop stops every robot, stays latched when its writer dies, and only an explicit release restores
// commands; referee HALT stops robots; against our real simulator, robot.feedback is published; a radio
// base station stand-in answers command frames with a status frame whose values reach robot.feedback.
// Each test has its own DDS domain (121-125) and UDP ports (27211-27230).
#include <gtest/gtest.h>
#include <signal.h>

#include <array>
#include <iostream>
#include <cmath>
#include <nlohmann/json.hpp>
#include <optional>
#include <stdexcept>
#include <thread>

#include "libs/league/decode.h"
#include "libs/net/udp.h"
#include "services/robot_link/radio/radio_frame.h"
#include "tests/support/process.h"

namespace ssl::testing {
namespace {

using std::chrono::milliseconds;
using std::chrono::seconds;
using SteadyClock = std::chrono::steady_clock;

constexpr auto kTimeout = seconds(30);
constexpr auto kWatchdog = milliseconds(100);
constexpr auto kSendPeriod = milliseconds(10);
constexpr auto kSchedulingMargin = milliseconds(50);
constexpr const char* kDriveForward =
    R"({"team": "TEAM_COLOR_BLUE", "commands": [{"id": 0, "forward": 1.0}]})";

ChildProcess start(const std::string& program, const std::vector<std::string>& args) {
  auto child = ChildProcess::start(bin_dir() / program, args);
  EXPECT_TRUE(child) << child.error().message;
  return std::move(child).value();
}

ChildProcess start_robot_link(int domain, int sim_port) {
  return start("robot_link", {"--team", "blue", "--domain", std::to_string(domain), "--backend", "sim",
                              "--sim-host", "127.0.0.1", "--sim-port", std::to_string(sim_port),
                              "--interface", "127.0.0.1", "--log-level", "info"});
}

/// The planner stand-in: robot 0 forward at 1 m/s, 50 Hz, once robot_link's reader is matched.
ChildProcess start_planner(int domain, int repeat) {
  return start("sslctl", {"topic", "pub", "robot.commands", "--team", "blue", "--domain",
                          std::to_string(domain), "--wait-readers", "1", "--wait-timeout", "30", "--repeat",
                          std::to_string(repeat), "--rate", "50", kDriveForward});
}

/// Stands in for the simulator's blue port: receives and timestamps robot_link's RobotControl datagrams.
class SimStandIn {
 public:
  explicit SimStandIn(int port) : socket_(open(port)) {}

  struct Datagram {
    SteadyClock::time_point received;
    RobotControl control;
    net::Endpoint sender;
  };

  /// The next RobotControl datagram, nullopt on timeout (undecodable datagrams fail the test).
  std::optional<Datagram> next(milliseconds timeout = milliseconds(1000)) {
    const auto result = socket_.receive(buffer_, timeout);
    if (!result.ok()) return std::nullopt;
    const auto received = SteadyClock::now();
    auto control = league::decode_robot_control(std::span(buffer_).first(result.size));
    EXPECT_TRUE(control) << control.error().message;
    if (!control) return std::nullopt;
    ++count_;
    last_ = control->ShortDebugString();
    return Datagram{received, std::move(*control), result.sender};
  }

  /// Receives until robot 0's command satisfies `predicate`, up to `timeout`.
  template <typename Predicate>
  std::optional<Datagram> wait_for(Predicate predicate, milliseconds timeout) {
    const auto deadline = SteadyClock::now() + timeout;
    while (SteadyClock::now() < deadline) {
      auto datagram = next();
      if (datagram && robot0(datagram->control) && predicate(*robot0(datagram->control))) return datagram;
    }
    return std::nullopt;
  }

  /// Every datagram within `duration` passes `predicate` for robot 0; returns how many arrived.
  template <typename Predicate>
  int all_for(Predicate predicate, milliseconds duration, const std::string& what) {
    const auto deadline = SteadyClock::now() + duration;
    int count = 0;
    while (SteadyClock::now() < deadline) {
      auto datagram = next(milliseconds(100));
      if (!datagram || !robot0(datagram->control)) continue;
      ++count;
      EXPECT_TRUE(predicate(*robot0(datagram->control)))
          << what << ": " << datagram->control.ShortDebugString();
    }
    return count;
  }

  /// How many datagrams arrived and the newest one, for failure messages.
  std::string last() const { return std::to_string(count_) + " datagrams, newest: " + last_; }

  /// Discards every datagram already queued (e.g. while a test was busy elsewhere).
  void drain() {
    while (socket_.receive(buffer_, std::chrono::nanoseconds(0)).ok()) {
    }
  }

  /// Binds 127.0.0.1:port. The port is in the kernel's ephemeral range, so another process's short-lived
  /// socket may hold it for a moment: retry for a while before failing.
  static net::UdpSocket open(int port) {
    auto socket = net::UdpSocket::open("127.0.0.1", port);
    for (int attempt = 0; !socket && attempt < 50; ++attempt) {
      std::this_thread::sleep_for(milliseconds(100));
      socket = net::UdpSocket::open("127.0.0.1", port);
    }
    if (!socket) throw std::runtime_error(socket.error().message);
    return std::move(socket).value();
  }

  static const ::RobotCommand* robot0(const RobotControl& control) {
    for (const ::RobotCommand& command : control.robot_commands()) {
      if (command.id() == 0) return &command;
    }
    return nullptr;
  }

 private:
  net::UdpSocket socket_;
  std::array<std::uint8_t, 65536> buffer_{};
  int count_ = 0;
  std::string last_;
};

/// What a child printed so far (stdout lines within `wait`, then stderr), for failure messages.
std::string output_of(ChildProcess& child, milliseconds wait = milliseconds(200)) {
  std::string text;
  while (auto line = child.read_line(wait)) text += *line + "\n";
  return text + child.drain_stderr();
}

double forward(const ::RobotCommand& command) { return command.move_command().local_velocity().forward(); }

bool stopped(const ::RobotCommand& command) {
  const auto& velocity = command.move_command().local_velocity();
  return command.move_command().has_local_velocity() && velocity.forward() == 0 && velocity.left() == 0 &&
         velocity.angular() == 0 && command.kick_speed() == 0 && command.dribbler_speed() == 0;
}

bool driving(const ::RobotCommand& command) { return std::abs(forward(command) - 1.0) < 1e-3; }

/// Health of robot_link/blue as JSON (sslctl health --json), or null.
nlohmann::json robot_link_health(int domain) {
  auto health = start("sslctl", {"health", "--json", "--listen", "2.5", "--domain", std::to_string(domain)});
  while (auto line = health.read_line(kTimeout)) {
    auto json = nlohmann::json::parse(*line, nullptr, false);
    if (json.is_object() && json.value("service", "") == "robot_link/blue") return json;
  }
  return nullptr;
}

std::uint64_t counter(const nlohmann::json& health, const std::string& name) {
  for (const auto& entry : health["counters"]) {
    if (entry["name"] == name) return entry["value"].get<std::uint64_t>();
  }
  ADD_FAILURE() << "no counter " << name << " in " << health.dump();
  return 0;
}

TEST(RobotLinkProcessTest, WatchdogStopsTheRobotWithin100MsWhenThePlannerIsKilled) {
  SimStandIn sim(27211);
  auto robot_link = start_robot_link(121, 27211);
  auto planner = start_planner(121, 1000);

  ASSERT_TRUE(sim.wait_for(driving, kTimeout))
      << "robot 0 never driven at 1 m/s; last datagram: " << sim.last()
      << "\nrobot_link: " << output_of(robot_link) << "\nplanner: " << output_of(planner);
  const int steady = sim.all_for(driving, milliseconds(300), "steady driving before the kill");
  EXPECT_GE(steady, 15) << "about 30 datagrams at 100 Hz";

  const auto killed = SteadyClock::now();  // the planner's last command was written before this
  planner.signal(SIGKILL);
  auto first_stop = sim.wait_for(stopped, seconds(5));
  ASSERT_TRUE(first_stop) << "robot 0 was never stopped";
  const auto to_stop = std::chrono::duration_cast<milliseconds>(first_stop->received - killed);
  EXPECT_LE(to_stop, kWatchdog + kSendPeriod + kSchedulingMargin)
      << "zero velocity " << to_stop.count() << " ms after the planner died";
  RecordProperty("stop_after_kill_ms", static_cast<int>(to_stop.count()));
  std::cout << "robot 0 stopped " << to_stop.count() << " ms after the planner was killed\n";

  // It stays stopped, and datagrams keep flowing (the heartbeat, every 10 ms) without a planner.
  const int after = sim.all_for(stopped, milliseconds(500), "after the planner died");
  EXPECT_GE(after, 25) << "about 50 datagrams at 100 Hz";
  EXPECT_EQ(planner.wait(kTimeout), 128 + SIGKILL);

  robot_link.signal(SIGTERM);
  EXPECT_EQ(robot_link.wait(kTimeout), 0) << robot_link.drain_stderr();
}

TEST(RobotLinkProcessTest, EstopStopsEveryRobotStaysLatchedWhenItsWriterDiesAndReleaseRestoresCommands) {
  SimStandIn sim(27212);
  auto robot_link = start_robot_link(122, 27212);
  auto planner = start_planner(122, 3000);
  ASSERT_TRUE(sim.wait_for(driving, kTimeout))
      << "last datagram: " << sim.last() << "\nrobot_link: " << output_of(robot_link)
      << "\nplanner: " << output_of(planner);

  auto estop_on = start("sslctl", {"estop", "on", "--domain", "122", "--reason", "process test"});
  ASSERT_TRUE(sim.wait_for(stopped, seconds(10)))
      << "e-stop did not stop robot 0; " << sim.last() << "\nrobot_link: " << output_of(robot_link)
      << "\nsslctl estop on: " << output_of(estop_on);
  sim.all_for(stopped, milliseconds(300), "e-stop engaged, planner still commanding");

  // The console / sslctl dies without releasing: liveliness is lost after its 1 s lease, the stop holds.
  estop_on.signal(SIGKILL);
  EXPECT_EQ(estop_on.wait(kTimeout), 128 + SIGKILL);
  sim.all_for(stopped, milliseconds(2500), "e-stop writer gone");

  auto estop_off = start("sslctl", {"estop", "off", "--domain", "122", "--linger", "5"});
  ASSERT_TRUE(sim.wait_for(driving, seconds(10)))
      << "commands did not flow again after the release; " << sim.last()
      << "\nrobot_link: " << output_of(robot_link) << "\nsslctl estop off: " << output_of(estop_off);

  const auto health = robot_link_health(122);
  ASSERT_TRUE(health.is_object()) << "no system.health from robot_link/blue";
  SCOPED_TRACE(health.dump());
  EXPECT_GE(counter(health, "estop_engagements"), 1u);
  EXPECT_GE(counter(health, "estop_ticks"), 100u);
  EXPECT_GE(counter(health, "estop_writers_lost_while_engaged"), 1u);
  EXPECT_EQ(counter(health, "estop_engaged"), 0u);

  // On exit robot_link leaves every robot stopped, even with the planner still commanding.
  sim.drain();
  robot_link.signal(SIGTERM);
  EXPECT_TRUE(sim.wait_for(stopped, seconds(5))) << "no final stop; " << sim.last();
  EXPECT_EQ(robot_link.wait(kTimeout), 0) << robot_link.drain_stderr();
  planner.signal(SIGTERM);
  estop_off.signal(SIGTERM);
  EXPECT_EQ(planner.wait(kTimeout), 0);
  EXPECT_EQ(estop_off.wait(kTimeout), 0);
}

TEST(RobotLinkProcessTest, RefereeHaltStopsEveryRobotWhateverThePlannerSays) {
  SimStandIn sim(27213);
  auto robot_link = start_robot_link(123, 27213);
  auto planner = start_planner(123, 3000);
  ASSERT_TRUE(sim.wait_for(driving, kTimeout))
      << "last datagram: " << sim.last() << "\nrobot_link: " << output_of(robot_link)
      << "\nplanner: " << output_of(planner);

  auto halt = start("sslctl", {"topic", "pub", "referee.state", "--domain", "123", "--linger", "-1",
                               R"({"command": "COMMAND_HALT", "command_counter": 1})"});
  ASSERT_TRUE(sim.wait_for(stopped, seconds(10)))
      << "HALT did not stop robot 0; " << sim.last() << "\nrobot_link: " << output_of(robot_link)
      << "\nreferee: " << output_of(halt);
  sim.all_for(stopped, milliseconds(300), "HALT");

  auto start_game = start("sslctl", {"topic", "pub", "referee.state", "--domain", "123", "--linger", "-1",
                                     R"({"command": "COMMAND_FORCE_START", "command_counter": 2})"});
  ASSERT_TRUE(sim.wait_for(driving, seconds(10)))
      << "commands did not flow after HALT; " << sim.last() << "\nrobot_link: " << output_of(robot_link);

  for (ChildProcess* child : {&halt, &start_game, &planner, &robot_link}) child->signal(SIGTERM);
  EXPECT_EQ(robot_link.wait(kTimeout), 0) << robot_link.drain_stderr();
}

TEST(RobotLinkProcessTest, DrivesOurSimulatorAndPublishesItsFeedback) {
  auto simulator =
      start("simulator", {"--no-dds", "--mode",      "realtime",  "--realism",     "none",  "--robots",
                          "2",        "--interface", "127.0.0.1", "--vision-port", "27220", "--control-port",
                          "27221",    "--blue-port", "27222",     "--yellow-port", "27223", "--grsim-port",
                          "27224",    "--log-level", "warn"});
  auto robot_link = start_robot_link(124, 27222);
  auto feedback = start("sslctl", {"topic", "echo", "robot.feedback", "--team", "blue", "--domain", "124",
                                   "--count", "1", "--timeout", "30"});
  auto planner = start_planner(124, 1500);

  const auto line = feedback.read_line(kTimeout);
  ASSERT_TRUE(line) << feedback.drain_stderr() << robot_link.drain_stderr() << simulator.drain_stderr();
  const auto json = nlohmann::json::parse(*line);
  EXPECT_LT(json["robot_id"].get<int>(), 2);
  EXPECT_EQ(json["team"], "TEAM_COLOR_BLUE");
  EXPECT_TRUE(json.contains("ball_in_dribbler"));
  EXPECT_EQ(feedback.wait(kTimeout), 0);

  const auto health = robot_link_health(124);
  ASSERT_TRUE(health.is_object()) << "no system.health from robot_link/blue";
  SCOPED_TRACE(health.dump());
  EXPECT_GT(counter(health, "feedback_received"), 0u);
  EXPECT_GT(counter(health, "commands_received"), 0u);
  EXPECT_EQ(counter(health, "send_errors"), 0u);

  for (ChildProcess* child : {&planner, &robot_link, &simulator}) child->signal(SIGTERM);
  EXPECT_EQ(robot_link.wait(kTimeout), 0) << robot_link.drain_stderr();
}

TEST(RobotLinkProcessTest, RadioStatusFramesReachRobotFeedbackWithLinkQuality) {
  // The base station stand-in: receives robot_link's command frames and answers each with a status frame.
  net::UdpSocket base_station = SimStandIn::open(27230);
  auto robot_link = start("robot_link", {"--team", "blue", "--domain", "125", "--backend", "radio",
                                         "--set", "radio.transport=udp", "radio.host=127.0.0.1",
                                         "radio.port=27230", "--interface", "127.0.0.1", "--log-level",
                                         "info"});
  auto feedback = start("sslctl", {"topic", "echo", "robot.feedback", "--team", "blue", "--domain", "125",
                                   "--count", "1", "--timeout", "30"});
  // Commands keep the frames (and so the base station's answers) flowing after the start-up stop.
  auto planner = start_planner(125, 1500);
  const robot_link::radio::StatusFrame status{
      .sequence = 7,
      .robots = {{.robot_id = 3, .ball_in_dribbler = true, .battery_voltage = 15.9, .kicker_charge = 0.5,
                  .link_quality = 0.87}}};
  const auto encoded = robot_link::radio::encode_status_frame(status);
  ASSERT_TRUE(encoded) << encoded.error().message;

  std::array<std::uint8_t, 65536> buffer{};
  std::optional<std::string> line;
  int command_frames = 0;
  const auto deadline = SteadyClock::now() + kTimeout;
  while (!line && SteadyClock::now() < deadline) {
    const auto received = base_station.receive(buffer, milliseconds(100));
    if (received.ok()) {
      const auto frame = robot_link::radio::decode_frame(std::span(buffer).first(received.size));
      ASSERT_TRUE(frame) << frame.error().message;
      ASSERT_TRUE(std::holds_alternative<robot_link::radio::CommandFrame>(*frame));
      ++command_frames;
      ASSERT_TRUE(base_station.send_to(received.sender, *encoded).ok());
    }
    line = feedback.read_line(milliseconds(0));
  }
  ASSERT_TRUE(line) << command_frames << " command frames\n" << robot_link_health(125).dump() << "\n"
                    << feedback.drain_stderr() << robot_link.drain_stderr();
  const auto json = nlohmann::json::parse(*line);
  SCOPED_TRACE(json.dump());
  EXPECT_EQ(json["robot_id"], 3);
  EXPECT_EQ(json["team"], "TEAM_COLOR_BLUE");
  EXPECT_EQ(json["ball_in_dribbler"], true);
  EXPECT_EQ(json["has_battery"], true);
  EXPECT_NEAR(json["battery_voltage"].get<double>(), 15.9, 1e-3);
  EXPECT_EQ(json["has_kicker_charge"], true);
  EXPECT_NEAR(json["kicker_charge"].get<double>(), 0.5, 1e-9);
  EXPECT_EQ(json["has_link_quality"], true);
  EXPECT_NEAR(json["link_quality"].get<double>(), 0.87, 1e-9);
  EXPECT_EQ(feedback.wait(kTimeout), 0);

  for (ChildProcess* child : {&planner, &robot_link}) child->signal(SIGTERM);
  EXPECT_EQ(robot_link.wait(kTimeout), 0) << robot_link.drain_stderr();
}

}  // namespace
}  // namespace ssl::testing
