// The referee gateway's configuration (deploy/config/referee_gateway.yaml), a typed struct validated once
// at start. Command-line flags override single keys after loading (--source, --referee-port,
// --interface; --set key=value for any key). Durations are in seconds in the file.
//
//   auto config = ssl::referee::load_referee_gateway_config("deploy/config/referee_gateway.yaml",
//                                                            {"network.referee_port=24001"});
//   if (!config) fail(config.error().message);
//   RefereeIngest ingest(gateway_options(*config));
#pragma once

#include <span>
#include <string>
#include <vector>

#include "libs/domain/division.h"
#include "libs/common/result.h"
#include "libs/common/team.h"
#include "services/referee_gateway/core/gateway.h"

namespace ssl::referee {

/// gc: listen to a Game Controller on the referee group; builtin: run our own referee, which multicasts
/// league Referee packets on that group, and listen to it like to a Game Controller.
enum class SourceKind { kGameController, kBuiltin };

/// The built-in referee (source builtin).
struct BuiltinConfig {
  std::string profile;            // arcade, strict_ai or a YAML file (--profile)
  Division division = Division::kB;  // the field's rule numbers and max_allowed_bots (11 / 6)
  bool blue_on_positive_half = kBlueOnPositiveHalfAtStart;  // in the first half; swapped at half time
  std::string yellow_team;        // team names in the Referee packets
  std::string blue_team;
  int yellow_goalkeeper = 0;
  int blue_goalkeeper = 0;
  double step_period = 0;         // s between referee steps
  double send_period = 0;         // s between Referee packets without a new command
  double vision_max_age = 0;      // s: older camera frames are not observed
  std::string teleport_placement;  // "" (robots place the ball) or the simulator's control "host:port"
  // Where the referee keeps the match (its last Referee packet) to resume it after a restart: "" nowhere,
  // "auto" the run directory (state_file_path), else a file.
  std::string state_file;
  double resume_within = 0;  // s: an older state file is a finished session; the match starts afresh
};

/// The built-in referee's state file for DDS domain `domain`: "" for none; "auto" gives
/// <run directory>/domain-<domain>/referee.state, the run directory being $RUNTIME_DIRECTORY (systemd's),
/// else $XDG_RUNTIME_DIR/ssl-stack, else /tmp/ssl-stack (as ./ssl up's); any other value as it is.
std::string state_file_path(const std::string& state_file, int domain);

struct NetworkConfig {
  std::string interface_address;  // multicast interface the group is joined on
  std::string referee_group;      // 224.5.23.1
  int referee_port = 0;           // 10003
};

struct RefereeGatewayConfig {
  SourceKind source = SourceKind::kGameController;
  NetworkConfig network;
  std::string source_identifier;   // "auto" or the UUID of the Game Controller to follow
  double source_switch_after = 0;  // s
  double heartbeat_period = 0;     // s
  double stale_after = 0;          // s
  int remembered_events = 0;
  double log_interval = 0;  // s between repeated warnings of one kind (malformed, jumps, foreign)
  BuiltinConfig builtin;
};

/// Loads and validates a config file; `overrides` are "key.path=value" strings (from flags).
/// `files`: the config's layers, lowest first (ssl::config_layers: defaults, site, --config).
Result<RefereeGatewayConfig> load_referee_gateway_config(std::span<const std::string> files, const std::vector<std::string>& overrides);
/// One complete file.
Result<RefereeGatewayConfig> load_referee_gateway_config(const std::string& path, const std::vector<std::string>& overrides);

/// The effective config as YAML (for --print-config).
std::string referee_gateway_config_yaml(const RefereeGatewayConfig& config);

/// The core's options from the config.
GatewayOptions gateway_options(const RefereeGatewayConfig& config);

}  // namespace ssl::referee
