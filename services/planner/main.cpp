// planner: one team's behaviour tree. Reads world.state (our partition), referee.state and vision.geometry;
// writes robot.commands and planner.debug (our partition) on every tick. Flags override keys of
// deploy/config/planner.yaml; --print-tree shows the tree (ASCII, or DOT with --dot) and exits.
#include <spdlog/spdlog.h>

#include <CLI/CLI.hpp>
#include <iostream>

#include "libs/service/flags.h"
#include "libs/service/setup.h"
#include "libs/common/shutdown.h"
#include "libs/dds/participant.h"
#include "libs/time/clock.h"
#include "services/planner/adapter/planner_node.h"
#include "services/planner/planner_config.h"

int main(int argc, char** argv) {
  ssl::ShutdownSignal shutdown;  // before any thread exists
  ssl::service::CommonFlags flags;
  std::string interface_address;
  bool print_tree = false;
  bool dot = false;
  CLI::App app{"planner: one team's behaviour tree, world.state + referee.state -> robot.commands", "planner"};
  ssl::service::add_common_flags(app, flags, {.help_config = true, .set_example = "planner.limits.max_speed=2.5"});
  app.add_option("--interface", interface_address,
                 "multicast interface address (accepted for uniformity; the planner uses DDS only)");
  ssl::service::add_key_flag(app, flags, "--team", "team", "our colour: blue or yellow", {"blue", "yellow"});
  app.add_flag("--print-tree", print_tree, "print the behaviour tree (ASCII) and exit");
  app.add_flag("--dot", dot, "with --print-tree: print the tree as Graphviz DOT")->needs("--print-tree");
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& error) {
    return app.exit(error);
  }

  spdlog::set_default_logger(spdlog::default_logger()->clone("planner"));
  spdlog::set_level(spdlog::level::from_str(flags.log_level));
  auto logger = spdlog::default_logger();

  if (flags.help_config) {
    std::cout << ssl::planner::planner_config_help();
    return 0;
  }
  auto prepared = ssl::service::prepare_instance<ssl::planner::PlannerServiceConfig>(
      "planner", flags.site, flags.config_file,
      [&](const std::vector<std::string>& files) { return ssl::planner::load_planner_config(files, flags.overrides()); },
      [](const ssl::planner::PlannerServiceConfig& c) { return "planner/" + std::string(ssl::to_string(c.team)); });
  if (!prepared) {
    logger->critical("{}", prepared.error().message);
    return 1;
  }
  const ssl::service::Setup* setup = &prepared->first;
  const ssl::planner::PlannerServiceConfig* config = &prepared->second;
  if (flags.print_config) {
    std::cout << ssl::planner::planner_config_yaml(*config);
    return 0;
  }
  if (print_tree) {
    const ssl::planner::Planner planner(config->core);
    std::cout << (dot ? planner.tree_dot() : planner.tree_ascii());
    return 0;
  }

  const std::string team(ssl::to_string(config->team));
  const std::string identity = ssl::dds::identity::team_stack(config->team);
  logger->info("{}", ssl::service::describe(*setup, identity));
  auto participant = ssl::dds::Participant::create({.domain_id = flags.domain, .name = "planner/" + team,
                                                    .discovery = setup->discovery, .security = setup->security,
                                                    .identity = identity});
  if (!participant) {
    logger->critical("{}", participant.error().message);
    return 1;
  }
  ssl::time::RealClock wall_clock;
  auto node = ssl::planner::PlannerNode::create(*participant, *config, wall_clock, setup->saved_parameters);
  if (!node) {
    logger->critical("{}", node.error().message);
    return 1;
  }
  logger->info("team {}, domain {}, ticking {}", team, flags.domain,
               config->tick_mode == ssl::planner::TickMode::kOnWorldState
                   ? std::string("on every world.state as it arrives")
                   : fmt::format("at {} Hz", config->tick_rate));
  node->run(shutdown);
  logger->info("stopping");
  return 0;
}
