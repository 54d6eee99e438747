// vision_gateway: receives SSL-Vision (224.5.23.2:10006; simulators :10020) and publishes vision.detection
// (per camera, metres, capture/sent/receive times) and vision.geometry (transient local) over DDS, plus
// system.health. Config: deploy/config/vision_gateway.yaml, the site's layer (--site sim: port 10020),
// --config, then the flags.
#include <spdlog/spdlog.h>

#include <CLI/CLI.hpp>
#include <iostream>

#include "libs/service/flags.h"
#include "libs/service/setup.h"
#include "libs/common/shutdown.h"
#include "libs/dds/participant.h"
#include "services/vision_gateway/adapter/service.h"
#include "services/vision_gateway/vision_gateway_config.h"

int main(int argc, char** argv) {
  ssl::ShutdownSignal shutdown;  // before any thread exists
  ssl::service::CommonFlags flags;
  CLI::App app{"vision_gateway: SSL-Vision multicast -> vision.detection and vision.geometry (DDS, metres)",
               "vision_gateway"};
  ssl::service::add_common_flags(app, flags, {.help_config = true, .set_example = "source=10.0.0.5"});
  ssl::service::add_key_flag(app, flags, "--interface", "network.interface",
                             "multicast interface address (the NIC on the vision network; default 127.0.0.1)");
  ssl::service::add_key_flag(app, flags, "--vision-port", "network.vision_port",
                             "vision multicast port (group 224.5.23.2, default 10006)");
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& error) {
    return app.exit(error);
  }

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
  auto config = ssl::vision_gateway::load_vision_gateway_config(setup->config_files, flags.overrides());
  if (!config) {
    logger->critical("{}", config.error().message);
    return 1;
  }
  if (flags.print_config) {
    std::cout << ssl::vision_gateway::vision_gateway_config_yaml(*config);
    return 0;
  }

  logger->info("{}", ssl::service::describe(*setup, ssl::dds::identity::kSharedServices));
  auto participant = ssl::dds::Participant::create({.domain_id = flags.domain, .name = "vision_gateway",
                                                    .discovery = setup->discovery, .security = setup->security,
                                                    .identity = std::string(ssl::dds::identity::kSharedServices)});
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
