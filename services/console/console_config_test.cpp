#include "services/console/console_config.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "libs/common/deploy_files.h"

namespace ssl::console {
namespace {

std::string deployed_defaults() { return find_deploy_file("config/console.yaml").value(); }

std::string write_layer(const std::string& name, const std::string& text) {
  const std::string path = (std::filesystem::temp_directory_path() / name).string();
  std::ofstream(path) << text;
  return path;
}

TEST(ConsoleConfig, TheDeployedDefaultsLoad) {
  const std::vector<std::string> files{deployed_defaults()};
  auto config = load_console_config(files, {});
  ASSERT_TRUE(config) << config.error().message;
  EXPECT_EQ(config->http.port, 8080);
  EXPECT_EQ(config->http.bind, "127.0.0.1");
  EXPECT_TRUE(config->http.token.empty());
  EXPECT_TRUE(config->simulator_control.empty());
}

TEST(ConsoleConfig, FlagsOverrideKeys) {
  const std::vector<std::string> files{deployed_defaults()};
  auto config = load_console_config(files, {"http.port=9090", "http.bind=0.0.0.0", "http.token=abc"});
  ASSERT_TRUE(config) << config.error().message;
  EXPECT_EQ(config->http.port, 9090);
  EXPECT_EQ(config->http.bind, "0.0.0.0");
  EXPECT_EQ(config->http.token, "abc");
}

TEST(ConsoleConfig, BadValuesNameTheirKey) {
  const std::vector<std::string> files{deployed_defaults()};
  auto port = load_console_config(files, {"http.port=70000"});
  ASSERT_FALSE(port);
  EXPECT_NE(port.error().message.find("port"), std::string::npos);
  auto bind = load_console_config(files, {"http.bind=everywhere"});
  ASSERT_FALSE(bind);
  EXPECT_NE(bind.error().message.find("bind"), std::string::npos);
  auto control = load_console_config(files, {"simulator_control=nohost"});
  ASSERT_FALSE(control);
  EXPECT_NE(control.error().message.find("simulator_control"), std::string::npos);
  const std::vector<std::string> layered{deployed_defaults(), write_layer("console_bad_layer.yaml", "frame_rate: 0\n")};
  auto rate = load_console_config(layered, {});
  ASSERT_FALSE(rate);
  EXPECT_NE(rate.error().message.find("frame_rate"), std::string::npos);
}

TEST(ConsoleConfig, TheSimSiteAddsTheSimulatorsControlPort) {
  const std::vector<std::string> files{deployed_defaults(), find_deploy_file("sites/sim/console.yaml").value()};
  auto config = load_console_config(files, {});
  ASSERT_TRUE(config) << config.error().message;
  EXPECT_EQ(config->simulator_control, "127.0.0.1:10300");
}

}  // namespace
}  // namespace ssl::console
