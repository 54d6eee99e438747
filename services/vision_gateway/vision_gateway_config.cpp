#include "services/vision_gateway/vision_gateway_config.h"

#include "libs/config/config.h"
#include "libs/net/endpoint.h"

namespace ssl::vision_gateway {
namespace {

using config::field;
using config::Fields;
using config::nested;

/// For checks of nested structs: the loader prefixes "key '<struct>': ".
Status check_group(const std::string& group, const std::string& key) {
  auto endpoint = net::Endpoint::from_parts(group, 0);
  if (!endpoint) return Error{key + ": " + endpoint.error().message};
  if (!endpoint->is_multicast())
    return Error{key + ": '" + group + "' is not a multicast group (224.0.0.0/4)"};
  return {};
}

Fields<NetworkConfig> network_fields() {
  return Fields<NetworkConfig>{
      field("interface", &NetworkConfig::interface_address)
          .doc("address of the local interface that faces the vision network (127.0.0.1: this host only)"),
      field("vision_group", &NetworkConfig::vision_group).doc("SSL-Vision multicast group"),
      field("vision_port", &NetworkConfig::vision_port)
          .range(1, 65535)
          .doc("10006: ssl-vision; 10020: simulators (grSim, ER-Force, ours)"),
  }
      .check([](const NetworkConfig& network) -> Status {
        if (auto address = net::parse_ipv4(network.interface_address); !address) {
          return Error{"interface: " + address.error().message};
        }
        return check_group(network.vision_group, "vision_group");
      });
}

Fields<CameraTrackingConfig> camera_fields() {
  return {
      field("restart_silence", &CameraTrackingConfig::restart_silence)
          .unit("s")
          .range(0.0, 60.0)
          .doc("a camera silent this long whose frame numbers then jump back has restarted"),
      field("restart_min_jump", &CameraTrackingConfig::restart_min_jump)
          .unit("frames")
          .range(1, 1000000)
          .doc("... if they jump back at least this many frames"),
      field("resync_after", &CameraTrackingConfig::resync_after)
          .unit("frames")
          .range(1, 100000)
          .doc("this many backwards frames in a row also count as a restart"),
  };
}

Fields<GeometryConfig> geometry_fields() {
  return {
      field("defaults_division", &GeometryConfig::defaults_division)
          .values({{"auto", DivisionChoice::kAuto}, {"a", DivisionChoice::kA}, {"b", DivisionChoice::kB}})
          .doc("rulebook defaults for geometry fields the source leaves out: auto = from the field length"),
  };
}

Fields<TrackerConfig> tracker_fields() {
  return Fields<TrackerConfig>{
      field("enabled", &TrackerConfig::enabled)
          .doc("also receive TrackerWrapperPacket (counted on system.health)"),
      field("group", &TrackerConfig::group).doc("tracked vision multicast group"),
      field("port", &TrackerConfig::port).range(1, 65535).doc("tracked vision port (league default 10010)"),
  }
      .check([](const TrackerConfig& tracker) { return check_group(tracker.group, "group"); });
}

Fields<HealthConfig> health_fields() {
  return {
      field("vision_timeout", &HealthConfig::vision_timeout)
          .unit("s")
          .range(0.05, 60.0)
          .doc("health is WARN when no frame was published for this long"),
      field("malformed_log_interval", &HealthConfig::malformed_log_interval)
          .unit("s")
          .range(0.0, 3600.0)
          .doc("at most one log line about malformed packets per interval (with their count)"),
  };
}

Fields<VisionGatewayConfig> gateway_fields() {
  return Fields<VisionGatewayConfig>{
      nested("network", &VisionGatewayConfig::network, network_fields()),
      field("source", &VisionGatewayConfig::source)
          .doc("auto (lock onto the first sender) or the IPv4 address of the one vision host to use"),
      field("source_timeout", &VisionGatewayConfig::source_timeout)
          .unit("s")
          .range(0.01, 3600.0)
          .doc("auto: silence of the current source before another sender may take over"),
      nested("cameras", &VisionGatewayConfig::cameras, camera_fields()),
      nested("geometry", &VisionGatewayConfig::geometry, geometry_fields()),
      nested("tracker", &VisionGatewayConfig::tracker, tracker_fields()),
      nested("health", &VisionGatewayConfig::health, health_fields()),
  }
      .check([](const VisionGatewayConfig& config) -> Status {
        if (config.source == "auto") return {};
        if (auto address = net::parse_ipv4(config.source); !address) {
          return Error{"key 'source': '" + config.source + "' is neither 'auto' nor an IPv4 address (" +
                       address.error().message + ")"};
        }
        return {};
      });
}

time::Duration seconds(double s) { return time::duration_from_seconds(s); }

}  // namespace

Result<VisionGatewayConfig> load_vision_gateway_config(std::span<const std::string> files, const std::vector<std::string>& overrides) {
  return config::load_files(files, gateway_fields(), overrides);
}

Result<VisionGatewayConfig> load_vision_gateway_config(const std::string& path, const std::vector<std::string>& overrides) {
  return load_vision_gateway_config(std::span<const std::string>(&path, 1), overrides);
}

std::string vision_gateway_config_yaml(const VisionGatewayConfig& config) {
  return config::to_yaml(config, gateway_fields());
}

std::string vision_gateway_config_help() { return config::describe(gateway_fields()); }

GatewayOptions gateway_options(const VisionGatewayConfig& config) {
  GatewayOptions options;
  if (config.source != "auto") {
    if (auto address = net::parse_ipv4(config.source)) options.source_address = *address;
  }
  options.source_timeout = seconds(config.source_timeout);
  options.camera_restart_silence = seconds(config.cameras.restart_silence);
  options.camera_restart_min_jump = static_cast<std::uint32_t>(config.cameras.restart_min_jump);
  options.camera_resync_after = static_cast<std::uint32_t>(config.cameras.resync_after);
  options.defaults_division = config.geometry.defaults_division;
  return options;
}

ServiceOptions service_options(const VisionGatewayConfig& config) {
  ServiceOptions options;
  options.gateway = gateway_options(config);
  options.interface_address = config.network.interface_address;
  options.vision_group = config.network.vision_group;
  options.vision_port = config.network.vision_port;
  options.tracker_enabled = config.tracker.enabled;
  options.tracker_group = config.tracker.group;
  options.tracker_port = config.tracker.port;
  options.vision_timeout = seconds(config.health.vision_timeout);
  options.malformed_log_interval = seconds(config.health.malformed_log_interval);
  return options;
}

}  // namespace ssl::vision_gateway
