// Backends over real sockets and a pseudo-terminal: the same commands leave as RobotControl (sim),
// grSim_Packet (grsim) or radio frames (radio over UDP or serial), and feedback comes back from each.
// A UdpSocket in the test plays the simulator / base station; a pty plays the serial device.
#include "services/robot_link/backend/backend.h"

#include <fcntl.h>
#include <gtest/gtest.h>
#include <poll.h>
#include <stdlib.h>
#include <unistd.h>

#include <array>
#include <chrono>
#include <cmath>
#include <numbers>
#include <thread>

#include "libs/league/decode.h"
#include "libs/net/udp.h"
#include "services/robot_link/backend/serial_port.h"
#include "services/robot_link/radio/radio_frame.h"

namespace ssl::robot_link {
namespace {

using std::chrono::milliseconds;

std::vector<OutgoingCommand> sample_commands() {
  return {
      {.command = {.id = 0, .forward = 1.5, .left = -0.25, .angular = 2.0, .dribbler_rpm = 8000}},
      {.command = {.id = 3, .kick = KickType::kChip, .kick_speed = 4.0, .chip_angle = std::numbers::pi / 6}},
      {.command = {.id = 5, .kick = KickType::kFlat, .kick_speed = 6.0}},
      {.command = stop_command(9), .stop = StopReason::kStale},
  };
}

/// The simulator / base station: a socket on an ephemeral loopback port.
struct Peer {
  net::UdpSocket socket = net::UdpSocket::open("127.0.0.1", 0).value();
  std::array<std::uint8_t, 65536> buffer{};
  net::Endpoint last_sender;

  int port() const { return socket.local_endpoint().port(); }

  /// One datagram's bytes (empty on timeout).
  std::vector<std::uint8_t> receive(milliseconds timeout = milliseconds(2000)) {
    const auto received = socket.receive(buffer, timeout);
    if (!received.ok()) return {};
    last_sender = received.sender;
    return {buffer.begin(), buffer.begin() + static_cast<std::ptrdiff_t>(received.size)};
  }
};

/// Polls the backend until feedback arrives (bounded).
std::vector<FeedbackReport> wait_for_feedback(Backend& backend) {
  for (int i = 0; i < 200; ++i) {
    auto reports = backend.poll_feedback();
    if (!reports.empty()) return reports;
    std::this_thread::sleep_for(milliseconds(10));
  }
  return {};
}

/// A port that was free a moment ago (for sockets a backend binds itself).
int free_port() { return net::UdpSocket::open("127.0.0.1", 0)->local_endpoint().port(); }

TEST(RobotLinkBackendTest, SimBackendSendsRobotControlWithKickAngleInDegrees) {
  Peer sim;
  auto backend = make_backend({.kind = BackendKind::kSim,
                               .team = TeamColor::kBlue,
                               .bind_address = "127.0.0.1",
                               .host = "127.0.0.1",
                               .port = sim.port()});
  ASSERT_TRUE(backend) << backend.error().message;
  EXPECT_EQ((*backend)->description(), "sim 127.0.0.1:" + std::to_string(sim.port()));
  ASSERT_TRUE((*backend)->send(sample_commands()));

  const auto bytes = sim.receive();
  ASSERT_FALSE(bytes.empty());
  auto control = league::decode_robot_control(bytes);
  ASSERT_TRUE(control) << control.error().message;
  ASSERT_EQ(control->robot_commands_size(), 4);
  const ::RobotCommand& drive = control->robot_commands(0);
  EXPECT_EQ(drive.id(), 0u);
  ASSERT_TRUE(drive.move_command().has_local_velocity());
  EXPECT_FLOAT_EQ(drive.move_command().local_velocity().forward(), 1.5f);
  EXPECT_FLOAT_EQ(drive.move_command().local_velocity().left(), -0.25f);
  EXPECT_FLOAT_EQ(drive.move_command().local_velocity().angular(), 2.0f);
  EXPECT_FLOAT_EQ(drive.dribbler_speed(), 8000.0f);
  EXPECT_TRUE(drive.has_kick_speed()) << "unset would mean 'unchanged' to the simulator";
  EXPECT_FLOAT_EQ(drive.kick_speed(), 0.0f);
  const ::RobotCommand& chip = control->robot_commands(1);
  EXPECT_FLOAT_EQ(chip.kick_speed(), 4.0f);
  EXPECT_NEAR(chip.kick_angle(), 30.0f, 1e-4) << "kick_angle is in DEGREES on the wire";
  const ::RobotCommand& flat = control->robot_commands(2);
  EXPECT_FLOAT_EQ(flat.kick_speed(), 6.0f);
  EXPECT_FLOAT_EQ(flat.kick_angle(), 0.0f);
  const ::RobotCommand& stopped = control->robot_commands(3);
  EXPECT_EQ(stopped.id(), 9u);
  EXPECT_FLOAT_EQ(stopped.move_command().local_velocity().forward(), 0.0f);
  EXPECT_TRUE(stopped.has_dribbler_speed());
  EXPECT_FLOAT_EQ(stopped.dribbler_speed(), 0.0f);

  // The simulator answers the sender with RobotControlResponse: feedback and errors.
  RobotControlResponse response;
  auto* feedback = response.add_feedback();
  feedback->set_id(3);
  feedback->set_dribbler_ball_contact(true);
  auto* error = response.add_errors();
  error->set_code("UNKNOWN_ROBOT");
  error->set_message("blue 9 is not on the field");
  const std::string reply = *league::encode_datagram(response);
  ASSERT_TRUE(sim.socket.send_to(sim.last_sender, league::byte_span(reply)));
  const auto reports = wait_for_feedback(**backend);
  ASSERT_EQ(reports.size(), 1u);
  EXPECT_EQ(reports[0].robot_id, 3u);
  EXPECT_EQ(reports[0].ball_in_dribbler, true);
  EXPECT_FALSE(reports[0].battery_voltage);
  const BackendCounters counters = (*backend)->counters();
  EXPECT_EQ(counters.packets_sent, 1u);
  EXPECT_EQ(counters.feedback_received, 1u);
  EXPECT_EQ(counters.remote_errors, 1u);
  EXPECT_NE((*backend)->last_error().find("UNKNOWN_ROBOT"), std::string::npos);

  // Garbage from the simulator's port is counted, not fatal.
  const std::uint8_t junk[] = {0xFF, 0xFF, 0xFF};
  ASSERT_TRUE(sim.socket.send_to(sim.last_sender, junk));
  for (int i = 0; i < 200 && (*backend)->counters().feedback_errors == 0; ++i) {
    (void)(*backend)->poll_feedback();
    std::this_thread::sleep_for(milliseconds(5));
  }
  EXPECT_EQ((*backend)->counters().feedback_errors, 1u);
}

TEST(RobotLinkBackendTest, GrsimBackendSendsGrsimPacketAndReadsRobotsStatus) {
  Peer grsim;
  const int status_port = free_port();
  auto backend = make_backend({.kind = BackendKind::kGrsim,
                               .team = TeamColor::kYellow,
                               .bind_address = "127.0.0.1",
                               .host = "127.0.0.1",
                               .port = grsim.port(),
                               .grsim_feedback = true,
                               .grsim_status_port = status_port});
  ASSERT_TRUE(backend) << backend.error().message;
  ASSERT_TRUE((*backend)->send(sample_commands()));
  const auto bytes = grsim.receive();
  auto packet = league::decode_grsim_packet(bytes);
  ASSERT_TRUE(packet) << packet.error().message;
  ASSERT_TRUE(packet->has_commands());
  EXPECT_TRUE(packet->commands().isteamyellow());
  ASSERT_EQ(packet->commands().robot_commands_size(), 4);
  const grSim_Robot_Command& drive = packet->commands().robot_commands(0);
  EXPECT_FLOAT_EQ(drive.veltangent(), 1.5f);
  EXPECT_FLOAT_EQ(drive.velnormal(), -0.25f);
  EXPECT_FLOAT_EQ(drive.velangular(), 2.0f);
  EXPECT_TRUE(drive.spinner());
  EXPECT_FALSE(drive.wheelsspeed());
  const grSim_Robot_Command& chip = packet->commands().robot_commands(1);
  EXPECT_NEAR(chip.kickspeedx(), 4.0 * std::cos(std::numbers::pi / 6), 1e-5);
  EXPECT_NEAR(chip.kickspeedz(), 2.0, 1e-5);
  EXPECT_FALSE(chip.spinner());
  const grSim_Robot_Command& flat = packet->commands().robot_commands(2);
  EXPECT_FLOAT_EQ(flat.kickspeedx(), 6.0f);
  EXPECT_FLOAT_EQ(flat.kickspeedz(), 0.0f);

  Robots_Status status;
  auto* robot = status.add_robots_status();
  robot->set_robot_id(5);
  robot->set_infrared(true);
  robot->set_flat_kick(false);
  robot->set_chip_kick(false);
  const std::string reply = *league::encode_datagram(status);
  ASSERT_TRUE(
      grsim.socket.send_to(*net::Endpoint::from_parts("127.0.0.1", status_port), league::byte_span(reply)));
  const auto reports = wait_for_feedback(**backend);
  ASSERT_EQ(reports.size(), 1u);
  EXPECT_EQ(reports[0].robot_id, 5u);
  EXPECT_EQ(reports[0].ball_in_dribbler, true);
}

TEST(RobotLinkBackendTest, RadioOverUdpSendsFramesTheCodecDecodesWithIncreasingSequence) {
  Peer base_station;
  auto backend = make_backend({.kind = BackendKind::kRadio,
                               .bind_address = "127.0.0.1",
                               .host = "127.0.0.1",
                               .port = base_station.port(),
                               .radio_transport = RadioTransport::kUdp});
  ASSERT_TRUE(backend) << backend.error().message;
  for (int i = 0; i < 3; ++i) ASSERT_TRUE((*backend)->send(sample_commands()));
  for (std::uint16_t expected_sequence = 0; expected_sequence < 3; ++expected_sequence) {
    const auto bytes = base_station.receive();
    auto frame = radio::decode_frame(bytes);
    ASSERT_TRUE(frame) << frame.error().message;
    const auto* command = std::get_if<radio::CommandFrame>(&*frame);
    ASSERT_NE(command, nullptr);
    EXPECT_EQ(command->sequence, expected_sequence);
    ASSERT_EQ(command->robots.size(), 4u);
    EXPECT_NEAR(command->robots[0].command.forward, 1.5, 1e-3);
    EXPECT_EQ(command->robots[1].command.kick, KickType::kChip);
    EXPECT_NEAR(command->robots[1].command.chip_angle, std::numbers::pi / 6, 1e-3);
    EXPECT_FALSE(command->robots[0].stop);
    EXPECT_TRUE(command->robots[3].stop);
  }

  // Status frames back (to the sender), one lost in between.
  for (const std::uint16_t sequence : {10, 12}) {
    radio::StatusFrame status{.sequence = sequence,
                              .robots = {{.robot_id = 3,
                                          .ball_in_dribbler = true,
                                          .battery_voltage = 16.2,
                                          .kicker_charge = 0.5,
                                          .link_quality = 0.97,
                                          .last_command_sequence = 2}}};
    const auto bytes = *radio::encode_status_frame(status);
    ASSERT_TRUE(base_station.socket.send_to(base_station.last_sender, bytes));
  }
  std::vector<FeedbackReport> reports;
  for (int i = 0; i < 200 && reports.size() < 2; ++i) {
    for (auto& report : (*backend)->poll_feedback()) reports.push_back(report);
    std::this_thread::sleep_for(milliseconds(5));
  }
  ASSERT_EQ(reports.size(), 2u);
  EXPECT_EQ(reports[0].robot_id, 3u);
  EXPECT_EQ(reports[0].ball_in_dribbler, true);
  EXPECT_NEAR(*reports[0].battery_voltage, 16.2, 1e-9);
  EXPECT_NEAR(*reports[0].kicker_charge, 0.5, 1e-9);
  EXPECT_NEAR(*reports[0].link_quality, 0.97, 1e-9);
  EXPECT_EQ((*backend)->counters().frames_lost, 1u);
  EXPECT_EQ((*backend)->counters().packets_sent, 3u);
}

/// A pseudo-terminal standing in for a serial device: robot_link opens `slave_path`, the test uses `master`.
struct Pty {
  int master = -1;
  std::string slave_path;
  Pty() {
    master = ::posix_openpt(O_RDWR | O_NOCTTY);
    if (master < 0 || ::grantpt(master) != 0 || ::unlockpt(master) != 0) return;
    slave_path = ::ptsname(master);
  }
  ~Pty() {
    if (master >= 0) ::close(master);
  }
  std::vector<std::uint8_t> read_some(milliseconds timeout) {
    pollfd entry{.fd = master, .events = POLLIN, .revents = 0};
    if (::poll(&entry, 1, static_cast<int>(timeout.count())) <= 0) return {};
    std::array<std::uint8_t, 1024> buffer{};
    const ssize_t got = ::read(master, buffer.data(), buffer.size());
    if (got <= 0) return {};
    return {buffer.begin(), buffer.begin() + got};
  }
};

TEST(RobotLinkBackendTest, RadioOverSerialWritesFramesToTheDeviceAndReadsStatusFrames) {
  Pty pty;
  ASSERT_FALSE(pty.slave_path.empty()) << "no pseudo-terminal available";
  auto backend = make_backend({.kind = BackendKind::kRadio,
                               .radio_transport = RadioTransport::kSerial,
                               .serial_device = pty.slave_path,
                               .serial_baud = 921600});
  ASSERT_TRUE(backend) << backend.error().message;
  EXPECT_NE((*backend)->description().find(pty.slave_path), std::string::npos);
  ASSERT_TRUE((*backend)->send(sample_commands()));
  ASSERT_TRUE((*backend)->send(sample_commands()));

  radio::FrameAssembler assembler;
  std::vector<radio::RadioFrame> frames;
  for (int i = 0; i < 100 && frames.size() < 2; ++i) {
    for (auto& frame : assembler.push(pty.read_some(milliseconds(20)))) frames.push_back(std::move(frame));
  }
  ASSERT_EQ(frames.size(), 2u) << "raw mode: every byte arrives unchanged (no CR/LF translation)";
  EXPECT_EQ(std::get<radio::CommandFrame>(frames[0]).sequence, 0);
  EXPECT_EQ(std::get<radio::CommandFrame>(frames[1]).sequence, 1);
  EXPECT_EQ(std::get<radio::CommandFrame>(frames[1]).robots.size(), 4u);
  EXPECT_EQ(assembler.bad_frames(), 0u);

  // A status frame written in two pieces, with noise before it.
  const auto status = *radio::encode_status_frame(
      {.sequence = 1, .robots = {{.robot_id = 7, .ball_in_dribbler = false, .battery_voltage = 15.0}}});
  const std::uint8_t noise[] = {0x0A, 0x0D, 0x11, 0x13};  // LF, CR, XON, XOFF: raw mode passes them
  ASSERT_EQ(::write(pty.master, noise, sizeof noise), static_cast<ssize_t>(sizeof noise));
  ASSERT_EQ(::write(pty.master, status.data(), 5), 5);
  std::vector<FeedbackReport> reports = (*backend)->poll_feedback();
  ASSERT_EQ(::write(pty.master, status.data() + 5, status.size() - 5),
            static_cast<ssize_t>(status.size() - 5));
  for (int i = 0; i < 200 && reports.empty(); ++i) {
    reports = (*backend)->poll_feedback();
    std::this_thread::sleep_for(milliseconds(5));
  }
  ASSERT_EQ(reports.size(), 1u);
  EXPECT_EQ(reports[0].robot_id, 7u);
  EXPECT_NEAR(*reports[0].battery_voltage, 15.0, 1e-9);
  EXPECT_FALSE(reports[0].kicker_charge);
}

TEST(RobotLinkBackendTest, OpeningFailuresAreClearErrors) {
  auto missing = make_backend({.kind = BackendKind::kRadio,
                               .radio_transport = RadioTransport::kSerial,
                               .serial_device = "/dev/does-not-exist-robot-link"});
  ASSERT_FALSE(missing);
  EXPECT_NE(missing.error().message.find("/dev/does-not-exist-robot-link"), std::string::npos);
  auto bad_host = make_backend({.kind = BackendKind::kSim, .host = "simulator.local", .port = 10301});
  ASSERT_FALSE(bad_host);
  EXPECT_NE(bad_host.error().message.find("simulator.local"), std::string::npos);
  EXPECT_FALSE(SerialPort::open("/dev/null", 115200)) << "not a terminal";
  EXPECT_FALSE(SerialPort::open("/dev/ptmx", 12345)) << "unsupported baud";
  EXPECT_EQ(default_port(BackendKind::kSim, TeamColor::kBlue), 10301);
  EXPECT_EQ(default_port(BackendKind::kSim, TeamColor::kYellow), 10302);
  EXPECT_EQ(default_port(BackendKind::kGrsim, TeamColor::kYellow), 20011);
}

}  // namespace
}  // namespace ssl::robot_link
