// The planner service's configuration (deploy/config/planner.yaml): a typed struct validated once at
// start; flags (--team) and --set override single keys. Units per key in the schema (planner_config.cpp).
#pragma once

#include "libs/config/runtime_parameters.h"

#include "libs/domain/division.h"
#include <span>
#include <string>
#include <vector>

#include "libs/common/result.h"
#include "services/planner/core/planner.h"

namespace ssl::planner {

/// When the planner ticks.
///  kOnWorldState: on every new world.state sample (the vision rate) as soon as it arrives, once the
///                 previous tick is done (samples that arrive during a tick are folded into the next: the
///                 newest wins). No rate cap: a tick's own duration bounds the rate, and robot_link's
///                 token bucket bounds what reaches the radio;
///  kFixedRate:    at tick_rate Hz with the newest world.state (none while it is stale).
enum class TickMode { kOnWorldState, kFixedRate };

struct PlannerServiceConfig {
  TeamColor team = TeamColor::kBlue;
  TickMode tick_mode = TickMode::kOnWorldState;
  double tick_rate = 100;                 // Hz, kFixedRate
  double stale_world_timeout = 0.1;       // s without world.state: no ticks, health WARN "no world state"
  Division default_division = Division::kA;  // field until vision.geometry arrives
  PlannerConfig core;                     // team, default_field (and tick_period with kFixedRate) are filled from the above
};

/// The rulebook's field of a division (metres).
wm::FieldSize division_field(Division division);

/// `files`: the config's layers, lowest first (ssl::config_layers: defaults, site, --config).
Result<PlannerServiceConfig> load_planner_config(std::span<const std::string> files, const std::vector<std::string>& overrides);
/// One complete file.
Result<PlannerServiceConfig> load_planner_config(const std::string& path, const std::vector<std::string>& overrides);
std::string planner_config_yaml(const PlannerServiceConfig& config);
/// Every key with its type, unit, limits and documentation (for --help-config).
std::string planner_config_help();

/// The keys that may change while the planner runs (the console, `sslctl param`), starting from `config`.
Result<config::RuntimeParameters<PlannerServiceConfig>> planner_runtime_parameters(const PlannerServiceConfig& config);

}  // namespace ssl::planner
