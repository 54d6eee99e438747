// robot_link: one team's robot.commands -> the simulator (simulation protocol or grSim) or the robots'
// radio (new commands at once within the radio's rate, a heartbeat otherwise), behind the safety layer
// (watchdog, referee HALT, latched e-stop, limits); robot feedback -> robot.feedback. Flags override keys
// of deploy/config/robot_link.yaml.
#include <spdlog/spdlog.h>

#include <CLI/CLI.hpp>
#include <iostream>

#include "libs/service/flags.h"
#include "libs/service/setup.h"
#include "libs/common/shutdown.h"
#include "services/robot_link/adapter/service.h"

int main(int argc, char** argv) {
  ssl::ShutdownSignal shutdown;  // before any thread exists
  ssl::service::CommonFlags flags;
  CLI::App app{
      "robot_link: one team's robot commands to the simulator or the radio, with watchdog, HALT, "
      "latched e-stop and limits",
      "robot_link"};
  ssl::service::add_common_flags(app, flags, {.set_example = "send_rate=50"});
  ssl::service::add_key_flag(app, flags, "--interface", "interface",
                             "local address of the UDP sockets (default 0.0.0.0)");
  ssl::service::add_key_flag(app, flags, "--team", "team", "blue or yellow (required unless set in the config)");
  ssl::service::add_key_flag(app, flags, "--backend", "backend", "sim, grsim or radio");
  ssl::service::add_key_flag(app, flags, "--sim-host", "sim.host", "simulator address (default 127.0.0.1)");
  ssl::service::add_key_flag(app, flags, "--sim-port", "sim.port",
                             "simulator port (default 10301 blue, 10302 yellow; 20011 grsim)");
  app.add_flag_callback(
      "--keyboard-estop", [&flags] { flags.named.push_back("keyboard_estop=true"); },
      "space toggles the e-stop (when stdin is a terminal)");
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& error) {
    return app.exit(error);
  }

  auto logger = spdlog::default_logger()->clone("robot_link");
  logger->set_level(spdlog::level::from_str(flags.log_level));

  auto prepared = ssl::service::prepare_instance<ssl::robot_link::RobotLinkConfig>(
      "robot_link", flags.site, flags.config_file,
      [&](const std::vector<std::string>& files) { return ssl::robot_link::load_robot_link_config(files, flags.overrides()); },
      [](const ssl::robot_link::RobotLinkConfig& c) { return c.team.empty() ? std::string() : "robot_link/" + c.team; });
  if (!prepared) {
    logger->critical("{}", prepared.error().message);
    return 1;
  }
  const ssl::service::Setup* setup = &prepared->first;
  const ssl::robot_link::RobotLinkConfig* config = &prepared->second;
  if (flags.print_config) {
    std::cout << ssl::robot_link::robot_link_config_yaml(*config);
    return 0;
  }
  auto team = ssl::robot_link::config_team(*config);
  if (!team) {
    logger->critical("{}", team.error().message);
    return 1;
  }

  logger->info("{}", ssl::service::describe(*setup, ssl::dds::identity::team_stack(*team)));
  ssl::Status ran = ssl::robot_link::run_robot_link(
      {.config = *config, .team = *team, .domain_id = flags.domain, .discovery = setup->discovery,
       .security = setup->security, .saved_parameters = setup->saved_parameters},
      shutdown, logger);
  if (!ran) {
    logger->critical("{}", ran.error().message);
    return 1;
  }
  return 0;
}
