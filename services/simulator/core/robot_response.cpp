#include "services/simulator/core/robot_response.h"

#include <cmath>

namespace ssl::sim {

RobotResponse RobotResponse::ideal() { return {}; }

RobotResponse RobotResponse::realistic() {
  return {.command_delay = 0.025, .command_loss = 0.01, .velocity_time_constant = 0.05, .limit_spread = 0.1};
}

RobotResponse RobotResponse::harsh() {
  return {.command_delay = 0.05, .command_loss = 0.05, .velocity_time_constant = 0.1, .limit_spread = 0.2};
}

std::optional<RobotResponse> RobotResponse::profile(std::string_view name) {
  if (name == "ideal") return ideal();
  if (name == "realistic") return realistic();
  if (name == "harsh") return harsh();
  return std::nullopt;
}

std::optional<std::string> RobotResponse::invalid_reason() const {
  auto non_negative = [](double value) { return std::isfinite(value) && value >= 0; };
  if (!non_negative(command_delay)) return "command_delay must be a finite number of seconds >= 0";
  if (!non_negative(command_loss) || command_loss > 1) return "command_loss must be in [0, 1]";
  if (!non_negative(velocity_time_constant)) return "velocity_time_constant must be a finite number of seconds >= 0";
  if (!non_negative(limit_spread) || limit_spread >= 1) return "limit_spread must be in [0, 1)";
  return std::nullopt;
}

}  // namespace ssl::sim
