// The console's configuration (deploy/config/console.yaml, the site's layer, --config, then the flags), a
// typed struct validated once at start by libs/config. Units per key: Hz, V, or none.
#pragma once

#include <span>
#include <string>
#include <vector>

#include "libs/common/result.h"

namespace ssl::console {

struct HttpConfig {
  int port = 0;
  std::string bind;       // address the page is served on (127.0.0.1: this host only)
  std::string token;      // "" or the token every operator action must carry
  int max_streams = 0;    // open event streams at most (viewers)
};

struct ConsoleConfig {
  HttpConfig http;
  double frame_rate = 0;            // Hz of field frames to each viewer
  std::string simulator_control;    // "" (no simulator: no placing by dragging) or host:port
  std::string referee_profile;      // "" (the referee_gateway config's) or a profile name or file
  double battery_low_volts = 0;     // V
  double link_low_quality = 0;      // 0..1
};

/// `files`: the config's layers, lowest first (defaults, site, --config); `overrides` "key=value" (flags).
Result<ConsoleConfig> load_console_config(std::span<const std::string> files, const std::vector<std::string>& overrides);

/// The effective config as YAML (--print-config) and every key with its doc (--help-config).
std::string console_config_yaml(const ConsoleConfig& config);
std::string console_config_help();

}  // namespace ssl::console
