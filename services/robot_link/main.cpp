// robot_link: one team's robot.commands -> the simulator (simulation protocol or grSim) or the robots'
// radio, at a fixed rate, behind the safety layer (watchdog, referee HALT, latched e-stop, limits); robot
// feedback -> robot.feedback. Flags override keys of deploy/config/robot_link.yaml.
#include <spdlog/spdlog.h>

#include <CLI/CLI.hpp>
#include <iostream>

#include "libs/service/setup.h"
#include "libs/common/shutdown.h"
#include "services/robot_link/adapter/service.h"

namespace {

struct Flags {
  std::string config_file;
  std::string site;
  int domain = 0;
  std::string log_level = "info";
  bool print_config = false;
  std::vector<std::string> overrides;      // from the dedicated flags (--team, --sim-port, ...)
  std::vector<std::string> set_overrides;  // from --set (kept apart: CLI11 assigns this vector whole)
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
  CLI::App app{
      "robot_link: one team's robot commands to the simulator or the radio, with watchdog, HALT, "
      "latched e-stop and limits",
      "robot_link"};
  app.add_option("--config", flags.config_file, "YAML file laid over the defaults and the site (only the keys it changes)");
  app.add_option("--site", flags.site, ssl::service::kSiteHelp);
  app.add_option("--domain", flags.domain, "DDS domain id")->check(CLI::Range(0, 232));
  app.add_option("--log-level", flags.log_level, "trace, debug, info, warn, error, critical or off")
      ->check(CLI::IsMember({"trace", "debug", "info", "warn", "error", "critical", "off"}));
  add_override(app, "--interface", "interface", "local address of the UDP sockets (default 0.0.0.0)",
               flags.overrides);
  add_override(app, "--team", "team", "blue or yellow (required unless set in the config)", flags.overrides);
  add_override(app, "--backend", "backend", "sim, grsim or radio", flags.overrides);
  add_override(app, "--sim-host", "sim.host", "simulator address (default 127.0.0.1)", flags.overrides);
  add_override(app, "--sim-port", "sim.port",
               "simulator port (default 10301 blue, 10302 yellow; 20011 grsim)", flags.overrides);
  app.add_flag_callback(
      "--keyboard-estop", [&flags] { flags.overrides.push_back("keyboard_estop=true"); },
      "space toggles the e-stop (when stdin is a terminal)");
  app.add_option("--set", flags.set_overrides, "override any config key: --set send_rate=50")->take_all();
  app.add_flag("--print-config", flags.print_config, "print the effective config and exit");
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& error) {
    return app.exit(error);
  }

  // --set first, so that the dedicated flags win over a --set of the same key.
  flags.set_overrides.insert(flags.set_overrides.end(), flags.overrides.begin(), flags.overrides.end());
  flags.overrides = std::move(flags.set_overrides);

  auto logger = spdlog::default_logger()->clone("robot_link");
  logger->set_level(spdlog::level::from_str(flags.log_level));

  auto setup = ssl::service::prepare("robot_link", flags.site, flags.config_file);
  if (!setup) {
    logger->critical("{}", setup.error().message);
    return 1;
  }
  auto config = ssl::robot_link::load_robot_link_config(setup->config_files, flags.overrides);
  if (!config) {
    logger->critical("{}", config.error().message);
    return 1;
  }
  if (flags.print_config) {
    std::cout << ssl::robot_link::robot_link_config_yaml(*config);
    return 0;
  }
  auto team = ssl::robot_link::config_team(*config);
  if (!team) {
    logger->critical("{}", team.error().message);
    return 1;
  }

  logger->info("{}", ssl::service::describe(*setup));
  ssl::Status ran = ssl::robot_link::run_robot_link(
      {.config = *config, .team = *team, .domain_id = flags.domain, .discovery = setup->discovery}, shutdown, logger);
  if (!ran) {
    logger->critical("{}", ran.error().message);
    return 1;
  }
  return 0;
}
