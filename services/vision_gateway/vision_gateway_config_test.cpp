// The deployed configs load and map onto the gateway's options; bad values are rejected with the key.
#include "services/vision_gateway/vision_gateway_config.h"

#include <gtest/gtest.h>

#include "libs/common/deploy_files.h"
#include "libs/net/endpoint.h"

namespace ssl::vision_gateway {
namespace {

using namespace std::chrono_literals;

std::string deployed(const std::string& name) {
  auto path = find_deploy_file("config/" + name);
  EXPECT_TRUE(path) << path.error().message;
  return path ? *path : std::string();
}

TEST(VisionGatewayConfig, DeployedDefaultListensToSslVisionOnLoopback) {
  auto config = load_vision_gateway_config(deployed("vision_gateway.yaml"), {});
  ASSERT_TRUE(config) << config.error().message;
  EXPECT_EQ(config->network.interface_address, "127.0.0.1");
  EXPECT_EQ(config->network.vision_group, "224.5.23.2");
  EXPECT_EQ(config->network.vision_port, 10006);
  EXPECT_EQ(config->source, "auto");
  EXPECT_FALSE(config->tracker.enabled);
  EXPECT_EQ(config->tracker.port, 10010);

  const ServiceOptions service = service_options(*config);
  EXPECT_EQ(service.vision_port, 10006);
  EXPECT_EQ(service.vision_timeout, 1s);
  EXPECT_FALSE(service.gateway.source_address);
  EXPECT_EQ(service.gateway.source_timeout, 1s);
  EXPECT_EQ(service.gateway.camera_restart_silence, 500ms);
  EXPECT_EQ(service.gateway.camera_restart_min_jump, 10u);
  EXPECT_EQ(service.gateway.camera_resync_after, 30u);
  EXPECT_EQ(service.gateway.defaults_division, DivisionChoice::kAuto);
}

TEST(VisionGatewayConfig, TheSitesChangeOnlyThePortAndTheInterface) {
  auto sim_layers = config_layers("vision_gateway", "sim", "");
  ASSERT_TRUE(sim_layers) << sim_layers.error().message;
  auto sim = load_vision_gateway_config(*sim_layers, {});
  ASSERT_TRUE(sim) << sim.error().message;
  EXPECT_EQ(sim->network.vision_port, 10020);
  EXPECT_EQ(sim->network.interface_address, "127.0.0.1");

  auto field_layers = config_layers("vision_gateway", "field", "");
  ASSERT_TRUE(field_layers) << field_layers.error().message;
  auto field = load_vision_gateway_config(*field_layers, {});
  ASSERT_TRUE(field) << field.error().message;
  EXPECT_EQ(field->network.vision_port, 10006);
  EXPECT_EQ(field->network.interface_address, "0.0.0.0");

  field->network.vision_port = 10020;
  field->network.interface_address = "127.0.0.1";
  EXPECT_EQ(vision_gateway_config_yaml(*field), vision_gateway_config_yaml(*sim));
}

TEST(VisionGatewayConfig, FlagsOverrideKeysAndAFixedSourceBecomesAnAddress) {
  auto config = load_vision_gateway_config(
      deployed("vision_gateway.yaml"),
      {"network.vision_port=23123", "network.interface=10.1.2.3", "source=192.168.1.50",
       "geometry.defaults_division=b", "tracker.enabled=true"});
  ASSERT_TRUE(config) << config.error().message;
  const ServiceOptions options = service_options(*config);
  EXPECT_EQ(options.vision_port, 23123);
  EXPECT_EQ(options.interface_address, "10.1.2.3");
  EXPECT_EQ(options.gateway.source_address, *net::parse_ipv4("192.168.1.50"));
  EXPECT_EQ(options.gateway.defaults_division, DivisionChoice::kB);
  EXPECT_TRUE(options.tracker_enabled);
}

TEST(VisionGatewayConfig, BadValuesAreRejectedNamingTheKey) {
  const std::string file = deployed("vision_gateway.yaml");
  struct Case {
    std::string override_text;
    std::string expected;
  };
  const Case cases[] = {
      {"source=vision-pc", "'source'"},
      {"network.vision_port=70000", "network.vision_port"},
      {"network.vision_group=10.0.0.1", "not a multicast group"},
      {"network.interface=localhost", "interface"},
      {"tracker.group=224.5.23", "group"},
      {"geometry.defaults_division=c", "defaults_division"},
      {"source_timeout=0", "source_timeout"},
      {"cameras.resync_after=0", "cameras.resync_after"},
      {"cameras.restart_min_jmp=4", "did you mean"},
  };
  for (const Case& c : cases) {
    auto config = load_vision_gateway_config(file, {c.override_text});
    ASSERT_FALSE(config) << c.override_text;
    EXPECT_NE(config.error().message.find(c.expected), std::string::npos)
        << c.override_text << ": " << config.error().message;
  }
}

}  // namespace
}  // namespace ssl::vision_gateway
