// robot_link's configuration (deploy/config/robot_link.yaml), a typed struct validated once at start.
// Command-line flags override single keys after loading (--team -> team, --backend -> backend, --sim-host ->
// sim.host, --sim-port -> sim.port, --interface -> network.interface, --keyboard-estop -> keyboard_estop).
// Units: seconds, Hz, m/s, rad/s, m/s^2, rad/s^2, rpm, as stated per key in the schema.
#pragma once

#include <span>
#include <string>
#include <vector>

#include "libs/common/result.h"
#include "libs/config/runtime_parameters.h"
#include "libs/common/team.h"
#include "services/robot_link/backend/backend.h"
#include "services/robot_link/core/robot_link_core.h"

namespace ssl::robot_link {

struct SimTargetConfig {
  std::string host;            // simulator (sim, grsim backends)
  int port = 0;                // 0: 10301 blue / 10302 yellow for sim, 20011 for grsim
  bool grsim_feedback = true;  // grsim: listen for Robots_Status
  int grsim_status_port = 0;   // 0: 30011 blue / 30012 yellow
};

struct RadioConfig {
  RadioTransport transport = RadioTransport::kUdp;
  std::string host;    // base station (udp)
  int port = 0;        // 0: 10400
  int local_port = 0;  // status frames arrive here; 0: ephemeral (the base station replies)
  std::string device;  // serial device (serial)
  int baud = 115200;
};

struct RobotLinkConfig {
  std::string team;  // "blue", "yellow" or "" (then --team is required)
  BackendKind backend = BackendKind::kSim;
  double send_rate = 100;         // Hz, the radio's rate (SendSchedule): token bucket rate and heartbeat
  double command_timeout = 0.1;   // s, watchdog
  double startup_stop = 0.5;      // s, uncommanded ids get stops this long after start
  std::string interface_address;  // local address of the UDP sockets
  SimTargetConfig sim;
  RadioConfig radio;
  RobotLimits robot;
  std::string estop_device;  // serial e-stop device ("" = none)
  int estop_device_baud = 9600;
  bool keyboard_estop = false;      // space toggles the e-stop when stdin is a terminal
  double feedback_heartbeat = 0.1;  // s, republish unchanged feedback this often
};

/// Loads and validates a config file; `overrides` are "key.path=value" strings (from flags).
/// `files`: the config's layers, lowest first (ssl::config_layers: defaults, site, --config).
Result<RobotLinkConfig> load_robot_link_config(std::span<const std::string> files, const std::vector<std::string>& overrides);
/// One complete file.
Result<RobotLinkConfig> load_robot_link_config(const std::string& path, const std::vector<std::string>& overrides);

/// The effective config as YAML (for --print-config).
std::string robot_link_config_yaml(const RobotLinkConfig& config);

/// The team of a loaded config; an error when it is empty (neither --team nor the file gave one).
Result<TeamColor> config_team(const RobotLinkConfig& config);

CoreConfig core_config(const RobotLinkConfig& config);

/// The keys that may change while robot_link runs (the console, `sslctl param`): the robots' limits.
Result<config::RuntimeParameters<RobotLinkConfig>> robot_link_runtime_parameters(const RobotLinkConfig& config);
BackendOptions backend_options(const RobotLinkConfig& config, TeamColor team);

}  // namespace ssl::robot_link
