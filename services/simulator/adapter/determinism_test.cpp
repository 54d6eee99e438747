// Same seed and same commands give byte-identical vision output; another seed gives different noise.
#include <gtest/gtest.h>

#include <cmath>

#include "services/simulator/adapter/convert.h"

namespace ssl::sim {
namespace {

/// Runs two simulated seconds of a scripted scene with competition-grade vision noise and returns every
/// vision packet as the bytes the simulator would send.
std::vector<std::string> run_scripted(std::uint64_t seed) {
  SimulatorOptions options;
  options.robots_per_team = 6;
  options.field = FieldGeometry::division_b();
  options.vision.realism = RealismConfig::competition();
  options.seed = seed;
  Simulator sim(options);
  ControlRequest kick_off;
  kick_off.ball = BallTeleport{.x = 0.0, .y = 0.0, .vx = 2.0, .vy = 0.5};
  (void)sim.apply(kick_off);
  std::vector<std::string> packets;
  for (int step = 0; step < 1000; ++step) {
    if (step % 8 == 0) {
      std::vector<RobotCommandFor> commands;
      for (std::uint32_t id = 0; id < 6; ++id) {
        RobotCommand command;
        command.move = RobotCommand::Move::kLocalVelocity;
        command.velocity = {std::sin(step * 0.01 + id), std::cos(step * 0.013 + id), 1.0};
        command.kick_speed = 3.0;
        commands.push_back({id, command});
      }
      (void)sim.set_commands(TeamColor::kBlue, commands);
      (void)sim.set_commands(TeamColor::kYellow, commands);
    }
    const StepOutput output = sim.step(std::chrono::milliseconds(2));
    for (const auto& frame : output.frames) {
      SSL_WrapperPacket packet;
      *packet.mutable_detection() = detection_to_proto(frame, std::chrono::seconds(0));
      packets.push_back(packet.SerializeAsString());
    }
  }
  return packets;
}

TEST(SimDeterminismTest, SameSeedAndCommandsGiveIdenticalVisionBytes) {
  const auto first = run_scripted(1234);
  const auto second = run_scripted(1234);
  ASSERT_GT(first.size(), 500u);  // 2 s of 4 cameras at 75 Hz
  ASSERT_EQ(first.size(), second.size());
  for (std::size_t i = 0; i < first.size(); ++i) ASSERT_EQ(first[i], second[i]) << "packet " << i << " differs";
}

TEST(SimDeterminismTest, AnotherSeedGivesOtherNoise) {
  EXPECT_NE(run_scripted(1234), run_scripted(4321));
}

}  // namespace
}  // namespace ssl::sim
