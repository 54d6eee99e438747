// The deployed configs load, flags override them with validation, and the backend is swapped by config
// alone: the same commands leave as RobotControl (sim), grSim_Packet (grsim) or radio frames (radio).
#include "services/robot_link/robot_link_config.h"

#include <gtest/gtest.h>

#include <array>
#include <filesystem>
#include <fstream>

#include "libs/common/deploy_files.h"
#include "libs/league/decode.h"
#include "libs/net/udp.h"
#include "services/robot_link/radio/radio_frame.h"

namespace ssl::robot_link {
namespace {

std::string deployed(const std::string& name) {
  auto path = find_deploy_file("config/" + name);
  EXPECT_TRUE(path) << path.error().message;
  return *path;
}

TEST(RobotLinkConfigTest, DeployedFilesLoad) {
  auto config = load_robot_link_config(deployed("robot_link.yaml"), {});
  ASSERT_TRUE(config) << config.error().message;
  EXPECT_EQ(config->backend, BackendKind::kSim);
  EXPECT_DOUBLE_EQ(config->send_rate, 100);
  EXPECT_DOUBLE_EQ(config->command_timeout, 0.1);
  EXPECT_FALSE(config_team(*config)) << "the deployed file leaves the team to --team";
  const CoreConfig core = core_config(*config);
  EXPECT_EQ(core.command_timeout, std::chrono::milliseconds(100));
  EXPECT_EQ(core.send_period, std::chrono::milliseconds(10));
  EXPECT_DOUBLE_EQ(core.limits.vel_absolute_max, 3.0);

  // The sites: the simulator's, and the real field's radio on USB serial with our slower robots' limits.
  auto sim = config_layers("robot_link", "sim", "");
  ASSERT_TRUE(sim) << sim.error().message;
  auto simulated = load_robot_link_config(*sim, {});
  ASSERT_TRUE(simulated) << simulated.error().message;
  EXPECT_EQ(simulated->backend, BackendKind::kSim);

  auto field = config_layers("robot_link", "field", "");
  ASSERT_TRUE(field) << field.error().message;
  auto radio = load_robot_link_config(*field, {});
  ASSERT_TRUE(radio) << radio.error().message;
  EXPECT_EQ(radio->backend, BackendKind::kRadio);
  EXPECT_EQ(radio->radio.transport, RadioTransport::kSerial);
  EXPECT_DOUBLE_EQ(core_config(*radio).limits.vel_absolute_max, 2.5);
  EXPECT_DOUBLE_EQ(radio->command_timeout, 0.1) << "the field site changes only what differs";
}

TEST(RobotLinkConfigTest, FlagOverridesApplyAndAreValidated) {
  auto config = load_robot_link_config(
      deployed("robot_link.yaml"), {"team=yellow", "backend=grsim", "sim.host=10.0.0.7", "sim.port=20099"});
  ASSERT_TRUE(config) << config.error().message;
  ASSERT_TRUE(config_team(*config));
  EXPECT_EQ(*config_team(*config), TeamColor::kYellow);
  const BackendOptions options = backend_options(*config, TeamColor::kYellow);
  EXPECT_EQ(options.kind, BackendKind::kGrsim);
  EXPECT_EQ(options.host, "10.0.0.7");
  EXPECT_EQ(options.port, 20099);

  auto bad_team = load_robot_link_config(deployed("robot_link.yaml"), {"team=green"});
  ASSERT_FALSE(bad_team);
  EXPECT_NE(bad_team.error().message.find("team"), std::string::npos);
  auto bad_backend = load_robot_link_config(deployed("robot_link.yaml"), {"backend=carrier_pigeon"});
  ASSERT_FALSE(bad_backend);
  EXPECT_NE(bad_backend.error().message.find("radio"), std::string::npos) << "lists the allowed values";
  auto bad_rate = load_robot_link_config(deployed("robot_link.yaml"), {"send_rate=5"});
  ASSERT_FALSE(bad_rate) << "100 ms watchdog at 5 Hz cannot work";
  auto bad_baud = load_robot_link_config(deployed("robot_link.yaml"), {"radio.baud=12345"});
  ASSERT_FALSE(bad_baud);
  EXPECT_NE(bad_baud.error().message.find("baud"), std::string::npos);
}

TEST(RobotLinkConfigTest, PrintedConfigLoadsBackUnchanged) {
  auto config = load_robot_link_config(deployed("robot_link.yaml"), {"team=blue", "send_rate=50"});
  ASSERT_TRUE(config);
  const auto path = std::filesystem::temp_directory_path() / "robot_link_config_test.yaml";
  std::ofstream(path) << robot_link_config_yaml(*config);
  auto reloaded = load_robot_link_config(path.string(), {});
  std::filesystem::remove(path);
  ASSERT_TRUE(reloaded) << reloaded.error().message;
  EXPECT_EQ(reloaded->team, "blue");
  EXPECT_DOUBLE_EQ(reloaded->send_rate, 50);
}

TEST(RobotLinkConfigTest, BackendIsSwappedByConfigAlone) {
  auto receiver = net::UdpSocket::open("127.0.0.1", 0);
  ASSERT_TRUE(receiver);
  const std::string port = std::to_string(receiver->local_endpoint().port());
  const std::vector<OutgoingCommand> commands = {
      {.command = {.id = 1, .forward = 0.75, .kick = KickType::kFlat, .kick_speed = 5}}};
  std::array<std::uint8_t, 65536> buffer{};
  const auto send_with = [&](const std::vector<std::string>& overrides) -> std::vector<std::uint8_t> {
    auto config = load_robot_link_config(deployed("robot_link.yaml"), overrides);
    EXPECT_TRUE(config) << config.error().message;
    if (!config) return {};
    auto backend = make_backend(backend_options(*config, TeamColor::kBlue));
    EXPECT_TRUE(backend) << backend.error().message;
    if (!backend) return {};
    EXPECT_TRUE((*backend)->send(commands));
    const auto received = receiver->receive(buffer, std::chrono::seconds(2));
    EXPECT_TRUE(received.ok());
    return {buffer.begin(), buffer.begin() + static_cast<std::ptrdiff_t>(received.size)};
  };

  const auto sim = send_with({"backend=sim", "sim.port=" + port, "interface=127.0.0.1"});
  auto control = league::decode_robot_control(sim);
  ASSERT_TRUE(control) << control.error().message;
  ASSERT_EQ(control->robot_commands_size(), 1);
  EXPECT_FLOAT_EQ(control->robot_commands(0).move_command().local_velocity().forward(), 0.75f);

  const auto grsim = send_with({"backend=grsim", "sim.port=" + port, "sim.grsim_feedback=false"});
  auto packet = league::decode_grsim_packet(grsim);
  ASSERT_TRUE(packet) << packet.error().message;
  ASSERT_EQ(packet->commands().robot_commands_size(), 1);
  EXPECT_FLOAT_EQ(packet->commands().robot_commands(0).kickspeedx(), 5.0f);
  EXPECT_FALSE(packet->commands().isteamyellow());

  const auto radio = send_with({"backend=radio", "radio.transport=udp", "radio.port=" + port});
  auto frame = radio::decode_frame(radio);
  ASSERT_TRUE(frame) << frame.error().message;
  const auto& robots = std::get<radio::CommandFrame>(*frame).robots;
  ASSERT_EQ(robots.size(), 1u);
  EXPECT_NEAR(robots[0].command.forward, 0.75, 1e-3);
  EXPECT_EQ(robots[0].command.kick, KickType::kFlat);
}

}  // namespace
}  // namespace ssl::robot_link
