#include "services/referee_gateway/referee_gateway_config.h"

#include "libs/config/config.h"

#include <cstdlib>
#include <string>

namespace ssl::referee {
namespace {

using config::field;
using config::Fields;
using config::nested;

Fields<NetworkConfig> network_fields() {
  return {
      field("interface", &NetworkConfig::interface_address)
          .doc("multicast interface address the referee group is joined on"),
      field("referee_group", &NetworkConfig::referee_group).doc("the Game Controller's multicast group"),
      field("referee_port", &NetworkConfig::referee_port).range(1, 65535),
  };
}

Fields<BuiltinConfig> builtin_fields() {
  return {
      field("profile", &BuiltinConfig::profile).doc("arcade, strict_ai or a YAML profile file (--profile)"),
      field("division", &BuiltinConfig::division)
          .values({{"a", Division::kA}, {"b", Division::kB}})
          .doc("the field's rule numbers and robots per team (11 / 6)"),
      field("blue_on_positive_half", &BuiltinConfig::blue_on_positive_half),
      field("yellow_team", &BuiltinConfig::yellow_team).doc("team name sent in the Referee packets"),
      field("blue_team", &BuiltinConfig::blue_team).doc("team name sent in the Referee packets"),
      field("yellow_goalkeeper", &BuiltinConfig::yellow_goalkeeper).range(0, 15),
      field("blue_goalkeeper", &BuiltinConfig::blue_goalkeeper).range(0, 15),
      field("step_period", &BuiltinConfig::step_period).unit("s").range(0.001, 1)
          .doc("between referee steps (vision in, rules, commands)"),
      field("send_period", &BuiltinConfig::send_period).unit("s").range(0.01, 5)
          .doc("between Referee packets without a new command"),
      field("vision_max_age", &BuiltinConfig::vision_max_age).unit("s").range(0.01, 10)
          .doc("camera frames older than this are not observed"),
      field("teleport_placement", &BuiltinConfig::teleport_placement)
          .doc("'' (the robots place the ball) or the simulator's control host:port: it places the ball"),
      field("state_file", &BuiltinConfig::state_file)
          .doc("'' (none), auto (the run directory) or a file: the match, resumed after a restart"),
      field("resume_within", &BuiltinConfig::resume_within).unit("s").range(0, 86400)
          .doc("an older state file is not resumed: the match starts afresh"),
  };
}

Fields<RefereeGatewayConfig> gateway_fields() {
  return Fields<RefereeGatewayConfig>{
      field("source", &RefereeGatewayConfig::source)
          .values({{"gc", SourceKind::kGameController}, {"builtin", SourceKind::kBuiltin}})
          .doc("gc: a Game Controller on the referee group; builtin: our own referee"),
      nested("network", &RefereeGatewayConfig::network, network_fields()),
      field("source_identifier", &RefereeGatewayConfig::source_identifier)
          .doc("auto (the first Game Controller seen) or the UUID of the one to follow"),
      field("source_switch_after", &RefereeGatewayConfig::source_switch_after)
          .unit("s")
          .range(0.05, 600)
          .doc("auto: another Game Controller is followed once the chosen one was silent this long"),
      field("heartbeat_period", &RefereeGatewayConfig::heartbeat_period)
          .unit("s")
          .range(0.01, 60)
          .doc("referee.state is republished at least this often while packets arrive"),
      field("stale_after", &RefereeGatewayConfig::stale_after)
          .unit("s")
          .range(0.05, 600)
          .doc("health turns WARN when no packet arrived for this long"),
      field("remembered_events", &RefereeGatewayConfig::remembered_events)
          .range(16, 1000000)
          .doc("identities of published game events kept to publish each one once"),
      field("log_interval", &RefereeGatewayConfig::log_interval)
          .unit("s")
          .range(0, 3600)
          .doc("repeated warnings of one kind (malformed packets, counter jumps) at most this often"),
      nested("builtin", &RefereeGatewayConfig::builtin, builtin_fields()),
  }
      .check([](const RefereeGatewayConfig& config) -> Status {
        if (config.source_identifier.empty())
          return Error{"key 'source_identifier': empty (use auto or a UUID)"};
        return {};
      });
}

}  // namespace

std::string state_file_path(const std::string& state_file, int domain) {
  if (state_file != "auto") return state_file;
  std::string run_directory;
  if (const char* systemd = std::getenv("RUNTIME_DIRECTORY"); systemd != nullptr && *systemd != '\0') {
    run_directory = systemd;
  } else if (const char* user = std::getenv("XDG_RUNTIME_DIR"); user != nullptr && *user != '\0') {
    run_directory = std::string(user) + "/ssl-stack";
  } else {
    run_directory = "/tmp/ssl-stack";
  }
  return run_directory + "/domain-" + std::to_string(domain) + "/referee.state";
}

Result<RefereeGatewayConfig> load_referee_gateway_config(std::span<const std::string> files, const std::vector<std::string>& overrides) {
  return config::load_files(files, gateway_fields(), overrides);
}

Result<RefereeGatewayConfig> load_referee_gateway_config(const std::string& path, const std::vector<std::string>& overrides) {
  return load_referee_gateway_config(std::span<const std::string>(&path, 1), overrides);
}

std::string referee_gateway_config_yaml(const RefereeGatewayConfig& config) {
  return config::to_yaml(config, gateway_fields());
}

GatewayOptions gateway_options(const RefereeGatewayConfig& config) {
  GatewayOptions options;
  if (config.source_identifier != "auto") options.source_identifier = config.source_identifier;
  options.source_switch_after = time::duration_from_seconds(config.source_switch_after);
  options.heartbeat_period = time::duration_from_seconds(config.heartbeat_period);
  options.stale_after = time::duration_from_seconds(config.stale_after);
  options.remembered_events = static_cast<std::size_t>(config.remembered_events);
  return options;
}

}  // namespace ssl::referee
