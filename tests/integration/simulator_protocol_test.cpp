// The simulator process over real UDP, as another team's software would drive it: teleports through the
// simulation protocol appear in SSL-Vision multicast; grSim replacement packets work too; garbage and
// bad commands are answered with errors and counted, never a crash; lockstep mode steps on request.
#include <gtest/gtest.h>
#include <signal.h>

#include <array>
#include <cmath>
#include <random>

#include "libs/league/decode.h"
#include "libs/net/multicast.h"
#include "libs/net/udp.h"
#include "proto/ssl_simulation_synchronous.pb.h"
#include "tests/support/process.h"

namespace ssl::testing {
namespace {

using std::chrono::milliseconds;
using std::chrono::seconds;
using Clock = std::chrono::steady_clock;

/// Ports of one simulator instance; each test uses its own block so tests can run in parallel. Test ports stay
/// below Linux's ephemeral range (32768-60999), where a socket bound to port 0 anywhere could hold them.
struct Ports {
  int vision, control, blue, yellow, grsim;
  explicit Ports(int base) : vision(base), control(base + 1), blue(base + 2), yellow(base + 3), grsim(base + 4) {}
};

ChildProcess start_simulator(const Ports& ports, const std::string& mode) {
  auto child = ChildProcess::start(
      bin_dir() / "simulator",
      {"--no-dds", "--mode", mode, "--robots", "2", "--realism", "none", "--interface", "127.0.0.1",
       "--vision-port", std::to_string(ports.vision), "--control-port", std::to_string(ports.control),
       "--blue-port", std::to_string(ports.blue), "--yellow-port", std::to_string(ports.yellow), "--grsim-port",
       std::to_string(ports.grsim), "--log-level", "warn"});
  EXPECT_TRUE(child) << child.error().message;
  return std::move(child).value();
}

/// What the simulator printed so far (its log goes to stdout, errors to stderr), for failure messages.
std::string printed(ChildProcess& simulator) {
  std::string text = simulator.drain_stderr();
  while (auto line = simulator.read_line(milliseconds(0))) text += *line + "\n";
  return text;
}

net::Endpoint local(int port) { return *net::Endpoint::from_parts("127.0.0.1", port); }

/// Sends a request and waits for the reply on the same socket; the simulator may still be starting, so
/// the request is repeated (bounded) until a reply comes.
template <typename Reply>
std::optional<Reply> request(net::UdpSocket& socket, int port, const std::string& bytes) {
  std::array<std::uint8_t, 65536> buffer;
  for (int attempt = 0; attempt < 50; ++attempt) {
    EXPECT_TRUE(socket.send_to(local(port), league::byte_span(bytes)).ok());
    const auto reply = socket.receive(buffer, milliseconds(200));
    if (!reply.ok()) continue;
    auto decoded = league::decode<Reply>(std::span(buffer).first(reply.size));
    EXPECT_TRUE(decoded) << decoded.error().message;
    if (decoded) return *decoded;
    return std::nullopt;
  }
  return std::nullopt;
}

/// Waits (bounded) for a detection frame in which `predicate` holds.
template <typename Predicate>
bool see_in_vision(net::MulticastReceiver& vision, Predicate predicate, milliseconds timeout = seconds(15)) {
  std::array<std::uint8_t, 65536> buffer;
  const auto deadline = Clock::now() + timeout;
  while (Clock::now() < deadline) {
    const auto received = vision.receive(buffer, milliseconds(200));
    if (!received.ok()) continue;
    auto packet = league::decode_vision_wrapper(std::span(buffer).first(received.size));
    if (packet && packet->has_detection() && predicate(packet->detection())) return true;
  }
  return false;
}

bool has_robot(const google::protobuf::RepeatedPtrField<SSL_DetectionRobot>& robots, std::uint32_t id, double x_mm,
               double y_mm) {
  for (const auto& robot : robots) {
    if (robot.robot_id() == id && std::abs(robot.x() - x_mm) < 5 && std::abs(robot.y() - y_mm) < 5) return true;
  }
  return false;
}

TEST(SimulatorProtocolTest, TeleportThroughTheControlPortIsSeenInVision) {
  const Ports ports(22100);
  auto vision = net::MulticastReceiver::open("224.5.23.2", ports.vision, "127.0.0.1");
  ASSERT_TRUE(vision) << vision.error().message;
  auto simulator = start_simulator(ports, "realtime");
  auto client = net::UdpSocket::open("127.0.0.1", 0);
  ASSERT_TRUE(client);

  SimulatorCommand command;
  auto* robot = command.mutable_control()->add_teleport_robot();
  robot->mutable_id()->set_id(1);
  robot->mutable_id()->set_team(::BLUE);
  robot->set_x(2.0f);
  robot->set_y(-1.0f);
  robot->set_orientation(0.0f);
  auto* ball = command.mutable_control()->mutable_teleport_ball();
  ball->set_x(-1.0f);
  ball->set_y(0.5f);
  const auto response = request<SimulatorResponse>(*client, ports.control, command.SerializeAsString());
  ASSERT_TRUE(response) << simulator.drain_stderr();
  EXPECT_EQ(response->errors_size(), 0) << response->DebugString();

  EXPECT_TRUE(see_in_vision(*vision, [](const SSL_DetectionFrame& frame) {
    return has_robot(frame.robots_blue(), 1, 2000, -1000);
  }));
  EXPECT_TRUE(see_in_vision(*vision, [](const SSL_DetectionFrame& frame) {
    return frame.balls_size() == 1 && std::abs(frame.balls(0).x() + 1000) < 5 && std::abs(frame.balls(0).y() - 500) < 5;
  }));
  simulator.signal(SIGTERM);
  EXPECT_EQ(simulator.wait(seconds(10)), 0) << simulator.drain_stderr();
}

TEST(SimulatorProtocolTest, GarbageAndBadCommandsAreAnsweredWithErrorsAndTheSimulatorKeepsRunning) {
  const Ports ports(22200);
  auto simulator = start_simulator(ports, "realtime");
  auto client = net::UdpSocket::open("127.0.0.1", 0);
  ASSERT_TRUE(client);

  const std::string garbage = "\xff\xff\xff\xff\x0f garbage";
  const auto control_reply = request<SimulatorResponse>(*client, ports.control, garbage);
  ASSERT_TRUE(control_reply) << simulator.drain_stderr();
  ASSERT_EQ(control_reply->errors_size(), 1);
  EXPECT_EQ(control_reply->errors(0).code(), "DECODE_ERROR");

  const auto robot_reply = request<RobotControlResponse>(*client, ports.blue, garbage);
  ASSERT_TRUE(robot_reply);
  ASSERT_GE(robot_reply->errors_size(), 1);
  EXPECT_EQ(robot_reply->errors(0).code(), "DECODE_ERROR");

  RobotControl control;
  auto* absent = control.add_robot_commands();
  absent->set_id(9);  // only robots 0 and 1 are on the field
  absent->mutable_move_command()->mutable_local_velocity()->set_forward(1);
  absent->mutable_move_command()->mutable_local_velocity()->set_left(0);
  absent->mutable_move_command()->mutable_local_velocity()->set_angular(0);
  auto* present = control.add_robot_commands();
  present->set_id(0);
  present->set_dribbler_speed(100);
  const auto reply = request<RobotControlResponse>(*client, ports.yellow, control.SerializeAsString());
  ASSERT_TRUE(reply);
  ASSERT_EQ(reply->errors_size(), 1);
  EXPECT_EQ(reply->errors(0).code(), "UNKNOWN_ROBOT");
  EXPECT_EQ(reply->feedback_size(), 2);  // feedback for every yellow robot on the field

  // Random bytes of many lengths never take it down. They come from another socket, whose answers are
  // not read, so that the client's next reply is the one to its own request.
  auto sprayer = net::UdpSocket::open("127.0.0.1", 0);
  ASSERT_TRUE(sprayer);
  std::mt19937 random(7);
  for (int i = 0; i < 200; ++i) {
    std::string bytes(random() % 300, '\0');
    for (char& byte : bytes) byte = static_cast<char>(random());
    (void)sprayer->send_to(local(i % 2 == 0 ? ports.control : ports.grsim), league::byte_span(bytes));
  }
  const auto still_alive = request<SimulatorResponse>(*client, ports.control, SimulatorCommand().SerializeAsString());
  ASSERT_TRUE(still_alive) << "the simulator stopped answering; stderr: " << simulator.drain_stderr();
  EXPECT_EQ(still_alive->errors_size(), 0);
  simulator.signal(SIGTERM);
  EXPECT_EQ(simulator.wait(seconds(10)), 0) << simulator.drain_stderr();
}

TEST(SimulatorProtocolTest, GrsimReplacementMovesARobot) {
  const Ports ports(22300);
  auto vision = net::MulticastReceiver::open("224.5.23.2", ports.vision, "127.0.0.1");
  ASSERT_TRUE(vision);
  auto simulator = start_simulator(ports, "realtime");
  auto client = net::UdpSocket::open("127.0.0.1", 0);
  ASSERT_TRUE(client);

  grSim_Packet packet;
  auto* robot = packet.mutable_replacement()->add_robots();
  robot->set_x(-1.5);
  robot->set_y(1.25);
  robot->set_dir(90);
  robot->set_id(0);
  robot->set_yellowteam(true);
  // grSim answers nothing: send until vision shows the robot there (bounded by see_in_vision).
  const std::string bytes = packet.SerializeAsString();
  bool seen = false;
  for (int attempt = 0; attempt < 15 && !seen; ++attempt) {
    ASSERT_TRUE(client->send_to(local(ports.grsim), league::byte_span(bytes)).ok());
    seen = see_in_vision(*vision, [](const SSL_DetectionFrame& frame) {
      for (const auto& r : frame.robots_yellow()) {
        if (r.robot_id() == 0 && std::abs(r.x() + 1500) < 5 && std::abs(r.y() - 1250) < 5 &&
            std::abs(r.orientation() - M_PI / 2) < 0.01) {
          return true;
        }
      }
      return false;
    }, seconds(1));
  }
  EXPECT_TRUE(seen) << "the simulator printed: " << printed(simulator);

  // A grSim client gets its robots' status on port 30012 (yellow) of its own address.
  auto status_socket = net::UdpSocket::open("127.0.0.1", 30012);
  ASSERT_TRUE(status_socket) << status_socket.error().message;
  grSim_Packet commands;
  commands.mutable_commands()->set_timestamp(0);
  commands.mutable_commands()->set_isteamyellow(true);
  auto* command = commands.mutable_commands()->add_robot_commands();
  command->set_id(0);
  command->set_kickspeedx(0);
  command->set_kickspeedz(0);
  command->set_veltangent(0);
  command->set_velnormal(0);
  command->set_velangular(0);
  command->set_spinner(false);
  command->set_wheelsspeed(false);
  ASSERT_TRUE(client->send_to(local(ports.grsim), league::byte_span(commands.SerializeAsString())).ok());
  std::array<std::uint8_t, 65536> buffer;
  const auto received = status_socket->receive(buffer, seconds(10));
  ASSERT_TRUE(received.ok()) << "the simulator printed: " << printed(simulator);
  auto status = league::decode_grsim_robots_status(std::span(buffer).first(received.size));
  ASSERT_TRUE(status) << status.error().message;
  EXPECT_EQ(status->robots_status_size(), 2);  // both yellow robots on the field

  simulator.signal(SIGTERM);
  EXPECT_EQ(simulator.wait(seconds(10)), 0);
}

TEST(SimulatorProtocolTest, LockstepAdvancesExactlyTheRequestedStep) {
  const Ports ports(22400);
  auto simulator = start_simulator(ports, "lockstep");
  auto client = net::UdpSocket::open("127.0.0.1", 0);
  ASSERT_TRUE(client);

  SimulationSyncRequest step;
  step.set_sim_step(0.1f);
  const auto first = request<SimulationSyncResponse>(*client, ports.control, step.SerializeAsString());
  ASSERT_TRUE(first) << simulator.drain_stderr();
  // 0.1 s of 4 cameras at 75 Hz: 30 frames (give or take the camera stagger).
  EXPECT_GE(first->detection_size(), 28);
  EXPECT_LE(first->detection_size(), 32);
  double first_capture = 1e300;
  double last_capture = 0;
  for (const auto& frame : first->detection()) {
    first_capture = std::min(first_capture, frame.t_capture());
    last_capture = std::max(last_capture, frame.t_capture());
  }
  const auto second = request<SimulationSyncResponse>(*client, ports.control, step.SerializeAsString());
  ASSERT_TRUE(second);
  ASSERT_GT(second->detection_size(), 0);
  double second_last = 0;
  for (const auto& frame : second->detection()) second_last = std::max(second_last, frame.t_capture());
  // The second request moved simulated time on by one more step.
  EXPECT_NEAR(second_last - last_capture, 0.1, 0.02);
  EXPECT_LT(last_capture - first_capture, 0.1 + 1e-6);
  simulator.signal(SIGTERM);
  EXPECT_EQ(simulator.wait(seconds(10)), 0);
}

}  // namespace
}  // namespace ssl::testing
