// The deployed config file loads, flags override single keys, bad values are rejected with the key named.
#include "services/referee_gateway/referee_gateway_config.h"

#include <gtest/gtest.h>

#include "libs/common/deploy_files.h"

namespace ssl::referee {
namespace {

using namespace std::chrono_literals;

std::string deployed_file() {
  auto found = find_deploy_file("config/referee_gateway.yaml");
  EXPECT_TRUE(found) << found.error().message;
  return found ? *found : std::string();
}

TEST(RefereeGatewayConfig, TheDeployedFileLoadsWithTheLeagueDefaults) {
  auto config = load_referee_gateway_config(deployed_file(), {});
  ASSERT_TRUE(config) << config.error().message;
  EXPECT_EQ(config->source, SourceKind::kGameController);
  EXPECT_EQ(config->network.referee_group, "224.5.23.1");
  EXPECT_EQ(config->network.referee_port, 10003);
  EXPECT_EQ(config->source_identifier, "auto");
  const GatewayOptions options = gateway_options(*config);
  EXPECT_FALSE(options.source_identifier);
  EXPECT_EQ(options.heartbeat_period, 1s);
  EXPECT_EQ(options.stale_after, 1s);
  EXPECT_EQ(options.source_switch_after, 2s);
  // --print-config output loads back to the same values.
  const std::string yaml = referee_gateway_config_yaml(*config);
  EXPECT_NE(yaml.find("referee_port: 10003"), std::string::npos) << yaml;
}

TEST(RefereeGatewayConfig, FlagsOverrideKeys) {
  auto config = load_referee_gateway_config(
      deployed_file(), {"network.referee_port=24123", "source=builtin", "network.interface=10.0.0.5",
                        "source_identifier=6f1c2a4e-1b2d-4c3e-9f00-0123456789ab", "heartbeat_period=0.25"});
  ASSERT_TRUE(config) << config.error().message;
  EXPECT_EQ(config->network.referee_port, 24123);
  EXPECT_EQ(config->source, SourceKind::kBuiltin);
  EXPECT_EQ(config->network.interface_address, "10.0.0.5");
  const GatewayOptions options = gateway_options(*config);
  EXPECT_EQ(options.source_identifier, "6f1c2a4e-1b2d-4c3e-9f00-0123456789ab");
  EXPECT_EQ(options.heartbeat_period, 250ms);
}

TEST(RefereeGatewayConfig, BadValuesAreRejectedNamingTheKey) {
  for (const auto& [override_text, key] : std::vector<std::pair<std::string, std::string>>{
           {"source=tv", "source"},
           {"network.referee_port=70000", "network.referee_port"},
           {"stale_after=0", "stale_after"},
           {"source_identifier=", "source_identifier"}}) {
    auto config = load_referee_gateway_config(deployed_file(), {override_text});
    ASSERT_FALSE(config) << override_text;
    EXPECT_NE(config.error().message.find(key), std::string::npos) << config.error().message;
  }
}

}  // namespace
}  // namespace ssl::referee
