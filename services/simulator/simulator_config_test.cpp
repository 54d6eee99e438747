// The deployed simulator config loads, flags override it with validation, and mistakes name the key.
#include "services/simulator/simulator_config.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "libs/common/deploy_files.h"

namespace ssl::sim {
namespace {

std::string deployed_config() {
  auto path = find_deploy_file("config/simulator.yaml");
  EXPECT_TRUE(path) << path.error().message;
  return *path;
}

TEST(SimulatorConfigTest, DeployedFileLoadsWithTheLeaguePorts) {
  auto config = load_simulator_config(deployed_config(), {});
  ASSERT_TRUE(config) << config.error().message;
  EXPECT_EQ(config->network.vision_port, 10020);
  EXPECT_EQ(config->network.control_port, 10300);
  EXPECT_EQ(config->network.blue_port, 10301);
  EXPECT_EQ(config->network.yellow_port, 10302);
  EXPECT_EQ(config->network.grsim_port, 20011);
  EXPECT_EQ(config->robots_per_team, 11);
  const SimulatorOptions options = simulator_options(*config);
  EXPECT_DOUBLE_EQ(options.field.field_length, 12.0);
  EXPECT_DOUBLE_EQ(options.blue_spec.limits.vel_absolute_max, 3.0);
  EXPECT_EQ(options.yellow_spec.height, options.blue_spec.height);
}

TEST(SimulatorConfigTest, FlagOverridesApplyAndAreValidated) {
  auto config = load_simulator_config(deployed_config(), {"division=b", "robots_per_team=6", "realism=none"});
  ASSERT_TRUE(config) << config.error().message;
  EXPECT_DOUBLE_EQ(simulator_options(*config).field.field_length, 9.0);
  EXPECT_EQ(simulator_options(*config).robots_per_team, 6u);

  auto bad = load_simulator_config(deployed_config(), {"robots_per_team=17"});
  ASSERT_FALSE(bad);
  EXPECT_NE(bad.error().message.find("robots_per_team"), std::string::npos);
  auto bad_mode = load_simulator_config(deployed_config(), {"mode=slow"});
  ASSERT_FALSE(bad_mode);
  EXPECT_NE(bad_mode.error().message.find("lockstep"), std::string::npos);  // lists the allowed values
  auto bad_cameras = load_simulator_config(deployed_config(), {"cameras.count=3"});
  ASSERT_FALSE(bad_cameras);
  EXPECT_NE(bad_cameras.error().message.find("cameras.count"), std::string::npos);
}

TEST(SimulatorConfigTest, PrintedConfigLoadsBackUnchanged) {
  auto config = load_simulator_config(deployed_config(), {"seed=99"});
  ASSERT_TRUE(config);
  const std::string yaml = simulator_config_yaml(*config);
  const auto path = std::filesystem::temp_directory_path() / "simulator_config_test.yaml";
  {
    std::ofstream(path) << yaml;
  }
  auto reloaded = load_simulator_config(path.string(), {});
  ASSERT_TRUE(reloaded) << reloaded.error().message;
  EXPECT_EQ(reloaded->seed, 99u);
  EXPECT_EQ(simulator_config_yaml(*reloaded), yaml);
  std::filesystem::remove(path);
}

}  // namespace
}  // namespace ssl::sim
