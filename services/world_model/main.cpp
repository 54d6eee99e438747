// world_model: fuses vision.detection, vision.geometry, referee.state, robot.feedback and robot.commands
// into world.state for one team (team frame, our goal at -x), published after every camera frame.
// Flags override keys of deploy/config/world_model.yaml.
#include <spdlog/spdlog.h>

#include <CLI/CLI.hpp>
#include <iostream>

#include "libs/service/flags.h"
#include "libs/service/setup.h"
#include "libs/common/shutdown.h"
#include "libs/dds/participant.h"
#include "libs/time/clock.h"
#include "services/world_model/adapter/world_model_node.h"
#include "services/world_model/world_model_config.h"

int main(int argc, char** argv) {
  ssl::ShutdownSignal shutdown;  // before any thread exists
  ssl::service::CommonFlags flags;
  std::string interface_address;
  CLI::App app{"world_model: filtered ball and robots in the team frame (world.state)", "world_model"};
  ssl::service::add_common_flags(app, flags, {.set_example = "filter.ball.position_stddev=0.005"});
  app.add_option("--interface", interface_address, "multicast interface address (accepted for uniformity)");
  ssl::service::add_key_flag(app, flags, "--team", "team", "our colour: blue or yellow", {"blue", "yellow"});
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& error) {
    return app.exit(error);
  }

  auto logger = spdlog::default_logger()->clone("world_model");
  logger->set_level(spdlog::level::from_str(flags.log_level));

  auto prepared = ssl::service::prepare_instance<ssl::wm::WorldModelServiceConfig>(
      "world_model", flags.site, flags.config_file,
      [&](const std::vector<std::string>& files) { return ssl::wm::load_world_model_config(files, flags.overrides()); },
      [](const ssl::wm::WorldModelServiceConfig& c) { return "world_model/" + std::string(ssl::to_string(c.team)); });
  if (!prepared) {
    logger->critical("{}", prepared.error().message);
    return 1;
  }
  const ssl::service::Setup* setup = &prepared->first;
  const ssl::wm::WorldModelServiceConfig* config = &prepared->second;
  if (flags.print_config) {
    std::cout << ssl::wm::world_model_config_yaml(*config);
    return 0;
  }

  const std::string team(ssl::to_string(config->team));
  const std::string identity = ssl::dds::identity::team_stack(config->team);
  logger->info("{}", ssl::service::describe(*setup, identity));
  auto participant = ssl::dds::Participant::create({.domain_id = flags.domain, .name = "world_model/" + team,
                                                    .discovery = setup->discovery, .security = setup->security,
                                                    .identity = identity});
  if (!participant) {
    logger->critical("{}", participant.error().message);
    return 1;
  }
  ssl::time::RealClock wall_clock;
  auto node = ssl::wm::WorldModelNode::create(*participant, *config, wall_clock, setup->saved_parameters);
  if (!node) {
    logger->critical("{}", node.error().message);
    return 1;
  }
  logger->info("team {}, domain {}, publishing world.state {}", team, flags.domain,
               config->publish_mode == ssl::wm::PublishMode::kOnFrame ? "after every camera frame"
                                                                      : "at a fixed rate");
  node->run(shutdown);
  logger->info("stopping");
  return 0;
}
