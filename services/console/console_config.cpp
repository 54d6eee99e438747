#include "services/console/console_config.h"

#include "libs/config/config.h"
#include "libs/net/endpoint.h"

namespace ssl::console {
namespace {

using config::field;
using config::Fields;
using config::nested;

Fields<HttpConfig> http_fields() {
  return Fields<HttpConfig>{
      field("port", &HttpConfig::port).range(1, 65535).doc("HTTP port of the page (--http-port)"),
      field("bind", &HttpConfig::bind)
          .doc("address to listen on (--bind): 127.0.0.1 for this host only; another address needs a token for "
               "operator actions"),
      field("token", &HttpConfig::token)
          .doc("\"\" or the token operator actions must carry (--token; the page takes it from ?token=...)"),
      field("max_streams", &HttpConfig::max_streams).range(1, 256).doc("viewers at most (open event streams)"),
  }
      .check([](const HttpConfig& http) -> Status {
        if (http.bind == "localhost") return {};
        if (auto address = net::parse_ipv4(http.bind); !address) return Error{"bind: " + address.error().message};
        return {};
      });
}

Fields<ConsoleConfig> console_fields() {
  return Fields<ConsoleConfig>{
      nested("http", &ConsoleConfig::http, http_fields()),
      field("frame_rate", &ConsoleConfig::frame_rate).unit("Hz").range(1.0, 60.0).doc("field frames per second to each viewer"),
      field("simulator_control", &ConsoleConfig::simulator_control)
          .doc("\"\" or the simulator's control host:port: dragging the ball or a robot places it there"),
      field("referee_profile", &ConsoleConfig::referee_profile)
          .doc("\"\": the profile of referee_gateway's config for this site; or a profile name or YAML file"),
      field("battery_low_volts", &ConsoleConfig::battery_low_volts).unit("V").range(0.0, 60.0).doc("a battery below this is flagged"),
      field("link_low_quality", &ConsoleConfig::link_low_quality).range(0.0, 1.0).doc("a radio link below this share is flagged"),
  }
      .check([](const ConsoleConfig& config) -> Status {
        if (config.simulator_control.empty()) return {};
        if (auto endpoint = net::Endpoint::parse(config.simulator_control); !endpoint) {
          return Error{"key 'simulator_control': " + endpoint.error().message};
        }
        return {};
      });
}

}  // namespace

Result<ConsoleConfig> load_console_config(std::span<const std::string> files, const std::vector<std::string>& overrides) {
  return config::load_files(files, console_fields(), overrides);
}

std::string console_config_yaml(const ConsoleConfig& config) { return config::to_yaml(config, console_fields()); }

std::string console_config_help() { return config::describe(console_fields()); }

}  // namespace ssl::console
