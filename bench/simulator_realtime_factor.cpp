// Real-time factor of the simulator on one core: 11 v 11 on a Division A field, every robot driving a
// changing velocity command, the ball rolling and being kicked around, four cameras at 75 Hz with the
// realistic vision profile, and every vision frame converted and serialized to SSL_WrapperPacket bytes as
// the simulator process sends them (only the socket send is left out). Steps of 2 ms simulated time, as
// the `fast` mode does.
//
//   build/bench/simulator_realtime_factor [--seconds S] [--step-ms M]
#include <chrono>
#include <cmath>
#include <cstdio>
#include <string>

#include "services/simulator/adapter/convert.h"

namespace {

using Clock = std::chrono::steady_clock;

/// A deterministic, varied command per robot: drive a slow circle whose radius and direction depend on
/// the robot, turn, and kick when the ball is at the dribbler.
ssl::sim::RobotCommand command_for(std::uint32_t id, double t) {
  ssl::sim::RobotCommand command;
  command.move = ssl::sim::RobotCommand::Move::kGlobalVelocity;
  const double phase = t * (0.5 + 0.1 * id) + id;
  command.velocity = {1.5 * std::cos(phase), 1.5 * std::sin(phase), id % 2 == 0 ? 2.0 : -2.0};
  command.kick_speed = 4.0;
  command.dribbler_rpm = id % 3 == 0 ? 1000 : 0;
  return command;
}

}  // namespace

int main(int argc, char** argv) {
  double simulated_seconds = 20;
  double step_ms = 2;
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    if (arg == "--seconds" && i + 1 < argc) {
      simulated_seconds = std::stod(argv[++i]);
    } else if (arg == "--step-ms" && i + 1 < argc) {
      step_ms = std::stod(argv[++i]);
    } else {
      std::printf("usage: simulator_realtime_factor [--seconds S] [--step-ms M]\n");
      return arg == "--help" ? 0 : 2;
    }
  }
  ssl::sim::SimulatorOptions options;
  options.robots_per_team = 11;
  options.vision.realism = ssl::sim::RealismConfig::realistic();
  options.seed = 42;
  ssl::sim::Simulator sim(options);
  ssl::sim::BallTeleport ball;
  ball.x = 0.0;
  ball.y = 0.0;
  ball.vx = 2.0;
  ball.vy = 1.0;
  ssl::sim::ControlRequest request;
  request.ball = ball;
  (void)sim.apply(request);

  const auto step = std::chrono::duration_cast<ssl::time::Duration>(std::chrono::duration<double, std::milli>(step_ms));
  const auto steps = static_cast<long>(simulated_seconds * 1000.0 / step_ms);
  const auto unix_offset = std::chrono::seconds(1'700'000'000);
  std::size_t frames = 0;
  std::size_t bytes = 0;
  std::vector<ssl::sim::RobotCommandFor> commands(11);
  const auto start = Clock::now();
  for (long i = 0; i < steps; ++i) {
    const double t = static_cast<double>(i) * step_ms * 1e-3;
    if (i % 8 == 0) {  // commands arrive at about the planner's rate (every 16 ms)
      for (ssl::TeamColor team : {ssl::TeamColor::kBlue, ssl::TeamColor::kYellow}) {
        for (std::uint32_t id = 0; id < 11; ++id) commands[id] = {id, command_for(id + (team == ssl::TeamColor::kBlue ? 0 : 11), t)};
        (void)sim.set_commands(team, commands);
      }
    }
    const ssl::sim::StepOutput output = sim.step(step);
    for (const auto& frame : output.frames) {
      SSL_WrapperPacket packet;
      *packet.mutable_detection() = ssl::sim::detection_to_proto(frame, unix_offset);
      bytes += packet.SerializeAsString().size();
      ++frames;
    }
  }
  const double wall = std::chrono::duration<double>(Clock::now() - start).count();
  std::printf("simulator, 11 v 11, division A, 4 cameras at 75 Hz, realistic vision, %.1f ms steps\n", step_ms);
  std::printf("  %.0f s simulated in %.2f s wall: real-time factor %.1fx\n", simulated_seconds, wall,
              simulated_seconds / wall);
  std::printf("  %zu vision frames (%.0f per simulated s), %.0f bytes per frame\n", frames,
              static_cast<double>(frames) / simulated_seconds, frames ? static_cast<double>(bytes) / static_cast<double>(frames) : 0.0);
  std::printf("BUDGET simulator_realtime_factor %.1f\n", simulated_seconds / wall);
  return 0;
}
