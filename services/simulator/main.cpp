// simulator: a headless Bullet simulation of an SSL match, served over the league's simulation protocol
// (UDP 10300/10301/10302), grSim's legacy commands (UDP 20011) and SSL-Vision multicast
// (224.5.23.2:10020). Flags override keys of deploy/config/simulator.yaml.
#include <spdlog/spdlog.h>

#include <CLI/CLI.hpp>
#include <iostream>

#include "libs/service/setup.h"
#include "libs/common/shutdown.h"
#include "libs/dds/health.h"
#include "services/simulator/run_loop.h"

namespace {

struct Flags {
  std::string config_file;
  std::string site;
  int domain = 0;
  std::string log_level = "info";
  bool print_config = false;
  bool no_dds = false;
  std::vector<std::string> overrides;      // from the named flags, in order
  std::vector<std::string> set_overrides;  // from --set (CLI11 assigns this vector as a whole)
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
  CLI::App app{"simulator: Bullet physics of an SSL match over the league's simulation protocol and SSL-Vision",
               "simulator"};
  app.add_option("--config", flags.config_file, "YAML file laid over the defaults and the site (only the keys it changes)");
  app.add_option("--site", flags.site, ssl::service::kSiteHelp);
  app.add_option("--domain", flags.domain, "DDS domain id for system.health")->check(CLI::Range(0, 232));
  app.add_option("--log-level", flags.log_level, "trace, debug, info, warn, error, critical or off")
      ->check(CLI::IsMember({"trace", "debug", "info", "warn", "error", "critical", "off"}));
  add_override(app, "--interface", "network.interface", "multicast interface address for vision", flags.overrides);
  add_override(app, "--division", "division", "field: a or b", flags.overrides);
  add_override(app, "--robots", "robots_per_team", "robots per team at start (0..16)", flags.overrides);
  add_override(app, "--realism", "realism", "none, realistic or competition", flags.overrides);
  add_override(app, "--seed", "seed", "random seed of the vision noise", flags.overrides);
  add_override(app, "--mode", "mode", "realtime, fast or lockstep", flags.overrides);
  add_override(app, "--vision-port", "network.vision_port", "vision multicast port (group 224.5.23.2)",
               flags.overrides);
  add_override(app, "--control-port", "network.control_port", "simulation control port", flags.overrides);
  add_override(app, "--blue-port", "network.blue_port", "blue robot control port", flags.overrides);
  add_override(app, "--yellow-port", "network.yellow_port", "yellow robot control port", flags.overrides);
  add_override(app, "--grsim-port", "network.grsim_port", "grSim legacy command port", flags.overrides);
  app.add_option("--set", flags.set_overrides, "override any config key: --set cameras.count=8")->take_all();
  app.add_flag("--print-config", flags.print_config, "print the effective config and exit");
  app.add_flag("--no-dds", flags.no_dds, "do not publish system.health over DDS");
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& error) {
    return app.exit(error);
  }

  auto logger = spdlog::default_logger()->clone("simulator");
  logger->set_level(spdlog::level::from_str(flags.log_level));

  flags.overrides.insert(flags.overrides.end(), flags.set_overrides.begin(), flags.set_overrides.end());
  auto setup = ssl::service::prepare("simulator", flags.site, flags.config_file);
  if (!setup) {
    logger->critical("{}", setup.error().message);
    return 1;
  }
  auto config = ssl::sim::load_simulator_config(setup->config_files, flags.overrides);
  if (!config) {
    logger->critical("{}", config.error().message);
    return 1;
  }
  if (flags.print_config) {
    std::cout << ssl::sim::simulator_config_yaml(*config);
    return 0;
  }

  auto server = ssl::sim::SimulatorServer::open(ssl::sim::server_options(*config));
  if (!server) {
    logger->critical("{}", server.error().message);
    return 1;
  }
  ssl::sim::Simulator sim(ssl::sim::simulator_options(*config));

  std::optional<ssl::dds::Participant> participant;
  std::optional<ssl::dds::HealthReporter> health;
  if (!flags.no_dds) {
    logger->info("{}", ssl::service::describe(*setup));
    auto created = ssl::dds::Participant::create({.domain_id = flags.domain, .name = "simulator", .discovery = setup->discovery});
    if (!created) {
      logger->critical("{}", created.error().message);
      return 1;
    }
    participant.emplace(std::move(*created));
    auto reporter = ssl::dds::HealthReporter::create(*participant, "simulator");
    if (!reporter) {
      logger->critical("{}", reporter.error().message);
      return 1;
    }
    health.emplace(std::move(*reporter));
  }

  const auto& network = config->network;
  logger->info("control :{}, blue :{}, yellow :{}, grSim :{}, vision {}:{} via {}; {} robots per team, seed {}",
               network.control_port, network.blue_port, network.yellow_port, network.grsim_port,
               network.vision_group, network.vision_port, network.interface_address, config->robots_per_team,
               config->seed);
  ssl::sim::run_loop(sim, **server,
                     {.mode = config->mode, .loop_rate = config->loop_rate, .fast_step = config->fast_step},
                     shutdown, health ? &*health : nullptr,
                     [&](const std::string& line) { logger->debug("{}", line); });
  logger->info("stopping");
  return 0;
}
