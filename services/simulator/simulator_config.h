// The simulator's configuration (deploy/config/simulator.yaml), a typed struct validated once at start.
// Command-line flags override single keys after loading. Units are stated per key in the schema.
#pragma once

#include "libs/domain/division.h"
#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "libs/common/result.h"
#include "services/simulator/adapter/server.h"
#include "services/simulator/core/simulator.h"

namespace ssl::sim {

enum class Mode { kRealtime, kFast, kLockstep };
enum class RealismProfile { kNone, kRealistic, kCompetition };
enum class ResponseProfile { kIdeal, kRealistic, kHarsh };  // RobotResponse's profiles

struct NetworkConfig {
  std::string bind_address;        // where the protocol ports listen
  std::string interface_address;   // multicast interface for vision output
  std::string vision_group;
  int vision_port = 0;
  int control_port = 0;
  int blue_port = 0;
  int yellow_port = 0;
  int grsim_port = 0;
};

struct CameraConfig {
  int count = 0;
  double frame_rate = 0;           // Hz per camera
  double overlap = 0;              // m
  double height = 0;               // m above the carpet
  int geometry_every_frames = 0;
};

struct SimulatorConfig {
  Division division = Division::kA;
  int robots_per_team = 0;
  std::uint64_t seed = 0;
  Mode mode = Mode::kRealtime;
  RealismProfile realism = RealismProfile::kRealistic;
  ResponseProfile robot_response = ResponseProfile::kRealistic;
  double loop_rate = 0;            // Hz, iterations of the real-time loop
  double fast_step = 0;            // s of simulated time per iteration in fast mode
  double command_timeout = 0;      // s (simulated) without a command after which a robot stops; 0: never
  NetworkConfig network;
  CameraConfig cameras;
  RobotSpec blue;                  // robot specs per team (wheel angles keep their defaults)
  RobotSpec yellow;
};

/// Loads and validates a config file; `overrides` are "key.path=value" strings (from flags).
/// `files`: the config's layers, lowest first (ssl::config_layers: defaults, site, --config).
Result<SimulatorConfig> load_simulator_config(std::span<const std::string> files, const std::vector<std::string>& overrides);
/// One complete file.
Result<SimulatorConfig> load_simulator_config(const std::string& path, const std::vector<std::string>& overrides);

/// The effective config as YAML (for --print-config).
std::string simulator_config_yaml(const SimulatorConfig& config);

SimulatorOptions simulator_options(const SimulatorConfig& config);
ServerOptions server_options(const SimulatorConfig& config);

}  // namespace ssl::sim
