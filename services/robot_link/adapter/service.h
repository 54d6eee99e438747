// robot_link as a running service: wires the DDS topics (robot.commands of the team, referee.state,
// system.estop for the team in; robot.sent and robot.feedback of the team, system.health out, and
// system.estop for the team out when a local e-stop input is configured) to the LinkRunner send loop and
// the configured backend, until shutdown.
// Every topic of the process is created here (one place). On shutdown every robot is sent a stop.
//
//   ssl::Status ran = run_robot_link({.config = config, .team = team, .domain_id = 3}, shutdown, logger);
#pragma once

#include <spdlog/logger.h>

#include <memory>

#include "libs/common/result.h"
#include "libs/common/shutdown.h"
#include "libs/dds/discovery.h"
#include "libs/dds/security.h"
#include "libs/common/team.h"
#include "services/robot_link/robot_link_config.h"

namespace ssl::robot_link {

struct ServiceOptions {
  RobotLinkConfig config;
  TeamColor team = TeamColor::kBlue;
  int domain_id = 0;
  dds::DiscoveryConfig discovery;
  dds::SecurityConfig security;  // with it on, the process is its team's identity (libs/dds/security.h)
  std::string saved_parameters;  // where run-time parameters are saved ("" none)
};

/// Runs until `shutdown` is requested; an error when setup fails (backend, DDS).
Status run_robot_link(const ServiceOptions& options, ShutdownSignal& shutdown,
                      const std::shared_ptr<spdlog::logger>& logger);

}  // namespace ssl::robot_link
