// vision_gateway: receives SSL-Vision (224.5.23.2:10006; simulators :10020) and publishes vision.detection
// (per camera, metres, capture/sent/receive times) and vision.geometry (transient local) over DDS, plus
// system.health. Config: deploy/config/vision_gateway.yaml, the site's layer (--site sim: port 10020),
// --config, then the flags.
#include <spdlog/spdlog.h>

#include <CLI/CLI.hpp>
#include <iostream>

#include "libs/service/setup.h"
#include "libs/common/shutdown.h"
#include "libs/dds/participant.h"
#include "services/vision_gateway/adapter/service.h"
#include "services/vision_gateway/vision_gateway_config.h"

namespace {

struct Flags {
  std::string config_file;
  std::string site;
  int domain = 0;
  std::string log_level = "info";
  bool print_config = false;
  bool help_config = false;
  std::vector<std::string> overrides;      // from the named flags (--interface, --vision-port)
  std::vector<std::string> set_overrides;  // from --set (CLI11 assigns this vector whole, so it is separate)
};

void add_override(CLI::App& app, const std::string& flag, const std::string& key, const std::string& help,
                  std::vector<std::string>& overrides) {
  app.add_option_function<std::string>(
      flag, [&overrides, key](const std::string& value) { overrides.push_back(key + "=" + value); }, help);
}

}  // namespace

int main(int argc, char** argv) {
  ssl::ShutdownSignal shutdown;  // before any thread exists
  Flags flags;
  CLI::App app{"vision_gateway: SSL-Vision multicast -> vision.detection and vision.geometry (DDS, metres)",
               "vision_gateway"};
  app.add_option("--config", flags.config_file, "YAML file laid over the defaults and the site (only the keys it changes)");
  app.add_option("--site", flags.site, ssl::service::kSiteHelp);
  app.add_option("--domain", flags.domain, "DDS domain id")->check(CLI::Range(0, 232));
  app.add_option("--log-level", flags.log_level, "trace, debug, info, warn, error, critical or off")
      ->check(CLI::IsMember({"trace", "debug", "info", "warn", "error", "critical", "off"}));
  add_override(app, "--interface", "network.interface",
               "multicast interface address (the NIC on the vision network; default 127.0.0.1)",
               flags.overrides);
  add_override(app, "--vision-port", "network.vision_port",
               "vision multicast port (group 224.5.23.2, default 10006)", flags.overrides);
  app.add_option("--set", flags.set_overrides, "override any config key: --set source=10.0.0.5")->take_all();
  app.add_flag("--print-config", flags.print_config, "print the effective config and exit");
  app.add_flag("--help-config", flags.help_config, "describe every config key and exit");
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& error) {
    return app.exit(error);
  }

  flags.overrides.insert(flags.overrides.end(), flags.set_overrides.begin(), flags.set_overrides.end());

  auto logger = spdlog::default_logger()->clone("vision_gateway");
  logger->set_level(spdlog::level::from_str(flags.log_level));

  if (flags.help_config) {
    std::cout << ssl::vision_gateway::vision_gateway_config_help();
    return 0;
  }
  auto setup = ssl::service::prepare("vision_gateway", flags.site, flags.config_file);
  if (!setup) {
    logger->critical("{}", setup.error().message);
    return 1;
  }
  auto config = ssl::vision_gateway::load_vision_gateway_config(setup->config_files, flags.overrides);
  if (!config) {
    logger->critical("{}", config.error().message);
    return 1;
  }
  if (flags.print_config) {
    std::cout << ssl::vision_gateway::vision_gateway_config_yaml(*config);
    return 0;
  }

  logger->info("{}", ssl::service::describe(*setup));
  auto participant = ssl::dds::Participant::create({.domain_id = flags.domain, .name = "vision_gateway", .discovery = setup->discovery});
  if (!participant) {
    logger->critical("{}", participant.error().message);
    return 1;
  }
  auto service = ssl::vision_gateway::VisionGatewayService::create(
      ssl::vision_gateway::service_options(*config), *participant, logger);
  if (!service) {
    logger->critical("{}", service.error().message);
    return 1;
  }
  logger->info("domain {}, source {}", flags.domain, config->source);
  (*service)->run(shutdown);
  logger->info("stopping");
  return 0;
}
