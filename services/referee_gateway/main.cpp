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

#include "libs/service/flags.h"
#include "libs/service/setup.h"
#include "libs/common/shutdown.h"
#include "libs/dds/participant.h"
#include "libs/time/clock.h"
#include "services/referee_gateway/adapter/builtin_service.h"
#include "services/referee_gateway/adapter/service.h"
#include "services/referee_gateway/builtin/profile.h"
#include "services/referee_gateway/referee_gateway_config.h"

int main(int argc, char** argv) {
  ssl::ShutdownSignal shutdown;  // before any thread exists
  ssl::service::CommonFlags flags;
  std::string profile_flag;
  CLI::App app{
      "referee_gateway: SSL Game Controller (or our built-in referee's) packets -> referee.state and "
      "referee.event (DDS)",
      "referee_gateway"};
  ssl::service::add_common_flags(app, flags, {.set_example = "heartbeat_period=0.5"});
  ssl::service::add_key_flag(app, flags, "--interface", "network.interface",
                             "multicast interface address of the referee network");
  ssl::service::add_key_flag(app, flags, "--source", "source", "gc (a Game Controller) or builtin (our own referee)");
  ssl::service::add_key_flag(app, flags, "--referee-port", "network.referee_port",
                             "referee multicast port (group 224.5.23.1, default 10003)");
  app.add_option("--profile", profile_flag, "built-in referee profile: arcade, strict_ai or a file (builtin only)");
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& error) {
    return app.exit(error);
  }

  auto logger = spdlog::default_logger()->clone("referee_gateway");
  logger->set_level(spdlog::level::from_str(flags.log_level));
  logger->flush_on(spdlog::level::trace);  // every line at once, also into a pipe or the journal (low rate)

  auto setup = ssl::service::prepare("referee_gateway", flags.site, flags.config_file);
  if (!setup) {
    logger->critical("{}", setup.error().message);
    return 1;
  }
  auto config = ssl::referee::load_referee_gateway_config(setup->config_files, flags.overrides());
  if (!config) {
    logger->critical("{}", config.error().message);
    return 1;
  }
  const bool builtin = config->source == ssl::referee::SourceKind::kBuiltin;
  if (!profile_flag.empty() && !builtin) {
    logger->critical("--profile selects a built-in referee profile and needs --source builtin");
    return 2;
  }
  if (!profile_flag.empty()) config->builtin.profile = profile_flag;
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

  logger->info("{}", ssl::service::describe(*setup, ssl::dds::identity::kSharedServices));
  auto participant = ssl::dds::Participant::create({.domain_id = flags.domain, .name = "referee_gateway",
                                                    .discovery = setup->discovery, .security = setup->security,
                                                    .identity = std::string(ssl::dds::identity::kSharedServices)});
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
                                                               : std::optional<std::string>(b.teleport_placement),
         .state_file = ssl::referee::state_file_path(b.state_file, flags.domain),
         .resume_within = ssl::time::duration_from_seconds(b.resume_within)},
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
