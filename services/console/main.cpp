// console: serves the match console on http://127.0.0.1:8080 (PROTOCOL.md): the live field, the referee
// operator panel, behaviour trees, health and the e-stop, streamed from the bus. Config:
// deploy/config/console.yaml, the site's layer (--site sim: the simulator's control port), --config, flags.
#include <spdlog/spdlog.h>

#include <CLI/CLI.hpp>
#include <iostream>

#include "libs/common/shutdown.h"
#include "libs/dds/participant.h"
#include "libs/service/flags.h"
#include "libs/service/setup.h"
#include "services/console/adapter/service.h"
#include "services/console/console_config.h"
#include "services/referee_gateway/builtin/profile.h"
#include "services/referee_gateway/referee_gateway_config.h"

namespace {

/// The built-in referee's profile for the profile panel: the configured one, else the one referee_gateway's
/// config names for this site; nullopt when the site's referee is the Game Controller.
ssl::Result<std::optional<ssl::referee::RefereeProfile>> referee_profile(const std::string& configured,
                                                                         const std::string& site) {
  std::string name = configured;
  if (name.empty()) {
    auto setup = ssl::service::prepare("referee_gateway", site, "");
    if (!setup) return setup.error();
    auto referee = ssl::referee::load_referee_gateway_config(setup->config_files, {});
    if (!referee) return referee.error();
    if (referee->source != ssl::referee::SourceKind::kBuiltin) return std::optional<ssl::referee::RefereeProfile>{};
    name = referee->builtin.profile;
  }
  auto profile = ssl::referee::load_referee_profile(name);
  if (!profile) return profile.error();
  return std::optional<ssl::referee::RefereeProfile>(std::move(*profile));
}

}  // namespace

int main(int argc, char** argv) {
  ssl::ShutdownSignal shutdown;  // before any thread exists
  ssl::service::CommonFlags flags;
  CLI::App app{"console: the match in a browser (field, referee operator panel, trees, health, e-stop)", "console"};
  ssl::service::add_common_flags(app, flags, {.help_config = true, .set_example = "frame_rate=20"});
  ssl::service::add_key_flag(app, flags, "--http-port", "http.port", "HTTP port of the page (default 8080)");
  ssl::service::add_key_flag(app, flags, "--bind", "http.bind",
                             "address to listen on (default 127.0.0.1; another address needs --token for operator actions)");
  ssl::service::add_key_flag(app, flags, "--token", "http.token",
                             "token that operator actions must carry (open the page with ?token=...)");
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& error) {
    return app.exit(error);
  }

  auto logger = spdlog::default_logger()->clone("console");
  logger->set_level(spdlog::level::from_str(flags.log_level));
  if (flags.help_config) {
    std::cout << ssl::console::console_config_help();
    return 0;
  }
  auto setup = ssl::service::prepare("console", flags.site, flags.config_file);
  if (!setup) {
    logger->critical("{}", setup.error().message);
    return 1;
  }
  auto config = ssl::console::load_console_config(setup->config_files, flags.overrides());
  if (!config) {
    logger->critical("{}", config.error().message);
    return 1;
  }
  if (flags.print_config) {
    std::cout << ssl::console::console_config_yaml(*config);
    return 0;
  }
  auto profile = referee_profile(config->referee_profile, setup->site);
  if (!profile) {
    logger->critical("referee profile: {}", profile.error().message);
    return 1;
  }

  // The console serves both teams: it is the operator of every team of the trust domain.
  const std::string identity = ssl::dds::identity::operator_of(std::nullopt);
  logger->info("{}", ssl::service::describe(*setup, identity));
  auto participant = ssl::dds::Participant::create({.domain_id = flags.domain, .name = "console",
                                                    .discovery = setup->discovery, .security = setup->security,
                                                    .identity = identity});
  if (!participant) {
    logger->critical("{}", participant.error().message);
    return 1;
  }
  ssl::console::ServiceOptions options{
      .http_port = config->http.port,
      .bind = config->http.bind,
      .token = config->http.token,
      .max_streams = static_cast<std::size_t>(config->http.max_streams),
      .frame_rate = config->frame_rate,
      .simulator_control = config->simulator_control,
      .profile = *profile,
      .state = {.battery_low_volts = config->battery_low_volts, .link_low_quality = config->link_low_quality},
      .estop_participant = {.domain_id = flags.domain, .name = "console/estop", .discovery = setup->discovery,
                            .security = setup->security, .identity = identity}};
  auto service = ssl::console::ConsoleService::create(options, *participant, logger);
  if (!service) {
    logger->critical("{}", service.error().message);
    return 1;
  }
  logger->info("domain {}: the console is on http://{}:{}/{}", flags.domain, config->http.bind, (*service)->port(),
               config->http.token.empty() ? "" : "?token=...");
  (*service)->run(shutdown);
  logger->info("stopping");
  return 0;
}
