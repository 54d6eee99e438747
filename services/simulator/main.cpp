// simulator: a headless Bullet simulation of an SSL match, served over the league's simulation protocol
// (UDP 10300/10301/10302), grSim's legacy commands (UDP 20011) and SSL-Vision multicast
// (224.5.23.2:10020). Flags override keys of deploy/config/simulator.yaml.
#include <spdlog/spdlog.h>

#include <CLI/CLI.hpp>
#include <iostream>

#include "libs/service/flags.h"
#include "libs/service/setup.h"
#include "libs/common/shutdown.h"
#include "libs/dds/health.h"
#include "services/simulator/run_loop.h"

int main(int argc, char** argv) {
  ssl::ShutdownSignal shutdown;  // before any thread exists
  ssl::service::CommonFlags flags;
  bool no_dds = false;
  CLI::App app{"simulator: Bullet physics of an SSL match over the league's simulation protocol and SSL-Vision",
               "simulator"};
  ssl::service::add_common_flags(app, flags, {.set_example = "cameras.count=8"});
  using ssl::service::add_key_flag;
  add_key_flag(app, flags, "--interface", "network.interface", "multicast interface address for vision");
  add_key_flag(app, flags, "--division", "division", "field: a or b");
  add_key_flag(app, flags, "--robots", "robots_per_team", "robots per team at start (0..16)");
  add_key_flag(app, flags, "--realism", "realism", "none, realistic or competition");
  add_key_flag(app, flags, "--robot-response", "robot_response",
               "ideal, realistic or harsh: command delay, loss, velocity lag, per-robot limits");
  add_key_flag(app, flags, "--seed", "seed", "random seed of the vision noise");
  add_key_flag(app, flags, "--mode", "mode", "realtime, fast or lockstep");
  add_key_flag(app, flags, "--vision-port", "network.vision_port", "vision multicast port (group 224.5.23.2)");
  add_key_flag(app, flags, "--control-port", "network.control_port", "simulation control port");
  add_key_flag(app, flags, "--blue-port", "network.blue_port", "blue robot control port");
  add_key_flag(app, flags, "--yellow-port", "network.yellow_port", "yellow robot control port");
  add_key_flag(app, flags, "--grsim-port", "network.grsim_port", "grSim legacy command port");
  app.add_flag("--no-dds", no_dds, "do not publish system.health over DDS");
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& error) {
    return app.exit(error);
  }

  auto logger = spdlog::default_logger()->clone("simulator");
  logger->set_level(spdlog::level::from_str(flags.log_level));

  auto setup = ssl::service::prepare("simulator", flags.site, flags.config_file);
  if (!setup) {
    logger->critical("{}", setup.error().message);
    return 1;
  }
  auto config = ssl::sim::load_simulator_config(setup->config_files, flags.overrides());
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
  if (!no_dds) {
    logger->info("{}", ssl::service::describe(*setup, ssl::dds::identity::kSharedServices));
    auto created = ssl::dds::Participant::create({.domain_id = flags.domain, .name = "simulator",
                                                  .discovery = setup->discovery, .security = setup->security,
                                                  .identity = std::string(ssl::dds::identity::kSharedServices)});
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
    // In lockstep the loop waits for its client's steps as long as the client likes.
    if (config->mode != ssl::sim::Mode::kLockstep) reporter->exit_when_stalled();
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
