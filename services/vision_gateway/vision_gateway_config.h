// The vision gateway's configuration (deploy/config/vision_gateway.yaml; the `sim` profile
// deploy/config/vision_gateway.sim.yaml listens on the simulators' port 10020), a typed struct validated
// once at start by libs/config: unknown or missing keys, out-of-range numbers, a `source` that is neither
// "auto" nor an IPv4 literal and non-multicast groups are errors naming the file, line and key. Flags
// (--interface, --vision-port, --set key=value) override single keys after loading. Units per key: s, or
// frames, or none.
#pragma once

#include <span>
#include <string>
#include <vector>

#include "libs/common/result.h"
#include "services/vision_gateway/adapter/service.h"
#include "services/vision_gateway/core/gateway.h"

namespace ssl::vision_gateway {

struct NetworkConfig {
  std::string interface_address;  // multicast interface (vision and tracker)
  std::string vision_group;       // SSL-Vision multicast group
  int vision_port = 0;
};

struct CameraTrackingConfig {
  double restart_silence = 0;  // s
  int restart_min_jump = 0;    // frames
  int resync_after = 0;        // backwards frames in a row
};

struct GeometryConfig {
  DivisionChoice defaults_division = DivisionChoice::kAuto;
};

struct TrackerConfig {
  bool enabled = false;
  std::string group;
  int port = 0;
};

struct HealthConfig {
  double vision_timeout = 0;          // s without a published frame -> WARN
  double malformed_log_interval = 0;  // s between two log lines about malformed packets
};

struct VisionGatewayConfig {
  NetworkConfig network;
  std::string source;         // "auto" or the IPv4 address of the vision host
  double source_timeout = 0;  // s of silence before auto switches source
  CameraTrackingConfig cameras;
  GeometryConfig geometry;
  TrackerConfig tracker;
  HealthConfig health;
};

/// Loads and validates a config file; `overrides` are "key.path=value" strings (from flags).
/// `files`: the config's layers, lowest first (ssl::config_layers: defaults, site, --config).
Result<VisionGatewayConfig> load_vision_gateway_config(std::span<const std::string> files, const std::vector<std::string>& overrides);
/// One complete file.
Result<VisionGatewayConfig> load_vision_gateway_config(const std::string& path, const std::vector<std::string>& overrides);

/// The effective config as YAML (for --print-config).
std::string vision_gateway_config_yaml(const VisionGatewayConfig& config);

/// Every key with its type, limits and doc (for --help-config).
std::string vision_gateway_config_help();

GatewayOptions gateway_options(const VisionGatewayConfig& config);
ServiceOptions service_options(const VisionGatewayConfig& config);

}  // namespace ssl::vision_gateway
