// RobotResponse: what a real robot adds between a command leaving the team's software and the wheels
// following it, beyond the physics' acceleration limits: the radio and firmware's delay, commands lost on
// the air, motors whose velocity lags the set point, and robots of one team that are not alike. The
// simulator (Simulator) applies it to every command, so a match against it meets what a field (or grSim)
// shows: a robot answers its command some tens of milliseconds late and gets there gradually.
//
// The profiles share their names with the harness's conditions profiles (ideal, realistic, harsh):
//   ideal      commands act at once, exactly (the lab's lockstep figures before 2026-11-28)
//   realistic  25 ms radio + firmware, 1 % lost, 50 ms velocity lag, limits of each robot within +-10 %:
//              with realistic vision (12 ms + jitter) and the pipeline about 40 ms from camera to wheels
//   harsh      50 ms, 5 % lost, 100 ms lag, +-20 %: with competition vision (20 ms + jitter) about 80 ms
#pragma once

#include <optional>
#include <string>
#include <string_view>

namespace ssl::sim {

struct RobotResponse {
  double command_delay = 0;           // s from a command reaching the simulator until it acts
  double command_loss = 0;            // 0..1, chance that one command is lost (the robot keeps its last)
  double velocity_time_constant = 0;  // s, first-order lag of the velocity aimed for behind the command
  double limit_spread = 0;            // 0..<1, each robot's speed and acceleration limits scaled by factors
                                      // drawn uniformly from [1 - this, 1 + this] (seed, team and id)

  static RobotResponse ideal();
  static RobotResponse realistic();
  static RobotResponse harsh();
  /// The profile of that name (ideal, realistic, harsh), or nullopt.
  static std::optional<RobotResponse> profile(std::string_view name);

  /// nullopt when usable, otherwise a one-line reason (finite, non-negative, probabilities <= 1, spread < 1).
  std::optional<std::string> invalid_reason() const;

  friend bool operator==(const RobotResponse&, const RobotResponse&) = default;
};

}  // namespace ssl::sim
