// referee_gateway: listens to the SSL Game Controller's Referee multicast (224.5.23.1:10003) and
// publishes referee.state (the whole state, transient local) and referee.event (each game event once)
// on DDS, with system.health once per second. With --source builtin it also runs our own referee
// (--profile arcade|strict_ai|FILE), which watches vision.detection, takes operator commands from
// referee.command and multicasts league Referee packets on the same group and port; the gateway then
// listens to those like to a Game Controller's (so other teams' software can use our referee too).
// Flags override keys of deploy/config/referee_gateway.yaml.
//
// Exit codes: 0 after SIGINT/SIGTERM; 1 when the config, the profile, the socket or DDS cannot be set up;
// 2 for --profile without --source builtin.
#include <spdlog/spdlog.h>

#include <CLI/CLI.hpp>
#include <iostream>
#include <memory>
#include <optional>

#include "libs/service/setup.h"
#include "libs/common/shutdown.h"
#include "libs/dds/participant.h"
#include "libs/time/clock.h"
#include "services/referee_gateway/adapter/builtin_service.h"
#include "services/referee_gateway/adapter/service.h"
#include "services/referee_gateway/builtin/profile.h"
#include "services/referee_gateway/referee_gateway_config.h"

namespace {

struct Flags {
  std::string config_file;
  std::string site;
  int domain = 0;
  std::string log_level = "info";
  std::string profile;
  bool print_config = false;
  std::vector<std::string> overrides;  // from the named flags, in command-line order
  std::vector<std::string> set;        // from --set; CLI11 assigns this vector whole, so it is kept apart
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
      "referee_gateway: SSL Game Controller (or our built-in referee's) packets -> referee.state and "
      "referee.event (DDS)",
      "referee_gateway"};
  app.add_option("--config", flags.config_file, "YAML file laid over the defaults and the site (only the keys it changes)");
  app.add_option("--site", flags.site, ssl::service::kSiteHelp);
  app.add_option("--domain", flags.domain, "DDS domain id")->check(CLI::Range(0, 232));
  app.add_option("--log-level", flags.log_level, "trace, debug, info, warn, error, critical or off")
      ->check(CLI::IsMember({"trace", "debug", "info", "warn", "error", "critical", "off"}));
  add_override(app, "--interface", "network.interface", "multicast interface address of the referee network",
               flags.overrides);
  add_override(app, "--source", "source", "gc (a Game Controller) or builtin (our own referee)",
               flags.overrides);
  add_override(app, "--referee-port", "network.referee_port",
               "referee multicast port (group 224.5.23.1, default 10003)", flags.overrides);
  app.add_option("--profile", flags.profile,
                 "built-in referee profile: arcade, strict_ai or a file (builtin only)");
  app.add_option("--set", flags.set, "override any config key: --set heartbeat_period=0.5")->take_all();
  app.add_flag("--print-config", flags.print_config, "print the effective config and exit");
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& error) {
    return app.exit(error);
  }

  flags.overrides.insert(flags.overrides.end(), flags.set.begin(), flags.set.end());

  auto logger = spdlog::default_logger()->clone("referee_gateway");
  logger->set_level(spdlog::level::from_str(flags.log_level));
  logger->flush_on(spdlog::level::trace);  // every line at once, also into a pipe or the journal (low rate)

  auto setup = ssl::service::prepare("referee_gateway", flags.site, flags.config_file);
  if (!setup) {
    logger->critical("{}", setup.error().message);
    return 1;
  }
  auto config = ssl::referee::load_referee_gateway_config(setup->config_files, flags.overrides);
  if (!config) {
    logger->critical("{}", config.error().message);
    return 1;
  }
  const bool builtin = config->source == ssl::referee::SourceKind::kBuiltin;
  if (!flags.profile.empty() && !builtin) {
    logger->critical("--profile selects a built-in referee profile and needs --source builtin");
    return 2;
  }
  if (!flags.profile.empty()) config->builtin.profile = flags.profile;
  std::optional<ssl::referee::RefereeProfile> profile;
  if (builtin) {
    auto loaded = ssl::referee::load_referee_profile(config->builtin.profile);
    if (!loaded) {
      logger->critical("{}", loaded.error().message);
      return 1;
    }
    profile = std::move(*loaded);
  }
  if (flags.print_config) {
    std::cout << ssl::referee::referee_gateway_config_yaml(*config);
    return 0;
  }

  logger->info("{}", ssl::service::describe(*setup));
  auto participant = ssl::dds::Participant::create({.domain_id = flags.domain, .name = "referee_gateway", .discovery = setup->discovery});
  if (!participant) {
    logger->critical("{}", participant.error().message);
    return 1;
  }
  ssl::time::RealClock wall;
  ssl::time::MonotonicClock monotonic;
  const auto& network = config->network;
  std::unique_ptr<ssl::referee::BuiltinRefereeService> referee;
  if (builtin) {
    const auto& b = config->builtin;
    auto opened = ssl::referee::BuiltinRefereeService::open(
        {.group = network.referee_group,
         .port = network.referee_port,
         .interface_address = network.interface_address,
         .profile = *profile,
         .field = ssl::FieldGeometry::of(b.division),
         .setup = {.yellow = {b.yellow_team, static_cast<std::uint32_t>(b.yellow_goalkeeper)},
                   .blue = {b.blue_team, static_cast<std::uint32_t>(b.blue_goalkeeper)},
                   .division = b.division,
                   .max_allowed_bots = ssl::max_robots_per_team(b.division),
                   .blue_on_positive_half = b.blue_on_positive_half},
         .step_period = ssl::time::duration_from_seconds(b.step_period),
         .send_period = ssl::time::duration_from_seconds(b.send_period),
         .vision_max_age = ssl::time::duration_from_seconds(b.vision_max_age),
         .teleport_placement_to = b.teleport_placement.empty() ? std::nullopt
                                                               : std::optional<std::string>(b.teleport_placement)},
        *participant, logger, wall);
    if (!opened) {
      logger->critical("built-in referee: {}", opened.error().message);
      return 1;
    }
    referee = std::move(*opened);
  }
  auto service = ssl::referee::RefereeGatewayService::open(
      {.group = network.referee_group,
       .port = network.referee_port,
       .interface_address = network.interface_address,
       .gateway = ssl::referee::gateway_options(*config),
       .source = builtin ? ssl::referee::RefereeSource::kBuiltin : ssl::referee::RefereeSource::kGameController,
       .log_interval = ssl::time::duration_from_seconds(config->log_interval)},
      *participant, logger, wall, monotonic);
  if (!service) {
    logger->critical("{}", service.error().message);
    return 1;
  }
  if (referee) {
    logger->info("built-in referee, profile {}, division {}: Referee packets to {}:{} via {}, operator "
                 "commands on referee.command",
                 profile->name, config->builtin.division == ssl::Division::kA ? "A" : "B",
                 network.referee_group, network.referee_port, network.interface_address);
    referee->start();
  }
  logger->info("listening for referee packets on {}:{} via {}, source {}, DDS domain {}",
               network.referee_group, network.referee_port, network.interface_address,
               config->source_identifier, flags.domain);
  (*service)->start();
  shutdown.wait();
  logger->info("stopping");
  if (referee) referee->stop();
  (*service)->stop();
  return 0;
}
