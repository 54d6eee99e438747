// The world_model's configuration (deploy/config/world_model.yaml), a typed struct validated once at
// start; flags (--team) override single keys. Units per key in the schema (world_model_config.cpp).
#pragma once

#include "libs/config/runtime_parameters.h"

#include <span>
#include <string>
#include <vector>

#include "libs/common/result.h"
#include "services/world_model/core/world_model.h"

namespace ssl::wm {

enum class PublishMode { kOnFrame, kFixedRate };

struct WorldModelServiceConfig {
  TeamColor team = TeamColor::kBlue;
  PublishMode publish_mode = PublishMode::kOnFrame;
  double publish_rate = 100;          // Hz, kFixedRate only
  double stale_vision_timeout = 0.2;  // s without a frame: health WARN
  WorldModelConfig core;
};

/// `files`: the config's layers, lowest first (ssl::config_layers: defaults, site, --config).
Result<WorldModelServiceConfig> load_world_model_config(std::span<const std::string> files, const std::vector<std::string>& overrides);
/// One complete file.
Result<WorldModelServiceConfig> load_world_model_config(const std::string& path, const std::vector<std::string>& overrides);
std::string world_model_config_yaml(const WorldModelServiceConfig& config);

/// The keys that may change while world_model runs (the console, `sslctl param`): its thresholds.
Result<config::RuntimeParameters<WorldModelServiceConfig>> world_model_runtime_parameters(
    const WorldModelServiceConfig& config);

}  // namespace ssl::wm
