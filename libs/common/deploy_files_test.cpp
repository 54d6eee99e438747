#include "libs/common/deploy_files.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include <unistd.h>

namespace ssl {
namespace {

namespace fs = std::filesystem;
using ::testing::ElementsAre;
using ::testing::HasSubstr;

// A deploy directory of its own, found first through $SSL_DEPLOY_DIR.
class DeployFilesTest : public ::testing::Test {
 protected:
  void SetUp() override {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    root_ = fs::temp_directory_path() / ("ssl_deploy_files_" + std::string(info->name()) + "_" + std::to_string(::getpid()));
    write("config/vision_gateway.yaml", "network: {vision_port: 10006}\n");
    write("config/planner.yaml", "team: blue\n");
    write("sites/sim/vision_gateway.yaml", "network: {vision_port: 10020}\n");
    write("sites/field/vision_gateway.yaml", "network: {vision_port: 10006}\n");
    ::setenv("SSL_DEPLOY_DIR", root_.c_str(), 1);
    ::unsetenv("SSL_SITE");
  }
  void TearDown() override {
    ::unsetenv("SSL_DEPLOY_DIR");
    ::unsetenv("SSL_SITE");
    fs::remove_all(root_);
  }
  void write(const std::string& relative, const std::string& text) {
    fs::create_directories((root_ / relative).parent_path());
    std::ofstream(root_ / relative) << text;
  }
  std::string path(const std::string& relative) const { return fs::weakly_canonical(root_ / relative).string(); }

  fs::path root_;
};

TEST_F(DeployFilesTest, WithoutASiteOnlyTheDefaults) {
  auto layers = config_layers("vision_gateway", "", "");
  ASSERT_TRUE(layers) << layers.error().message;
  EXPECT_THAT(*layers, ElementsAre(path("config/vision_gateway.yaml")));
}

TEST_F(DeployFilesTest, TheSitesFileAndTheUsersFileComeOnTopInThatOrder) {
  auto layers = config_layers("vision_gateway", "sim", "/somewhere/mine.yaml");
  ASSERT_TRUE(layers) << layers.error().message;
  EXPECT_THAT(*layers, ElementsAre(path("config/vision_gateway.yaml"), path("sites/sim/vision_gateway.yaml"),
                                   "/somewhere/mine.yaml"));
}

TEST_F(DeployFilesTest, ASiteThatChangesNothingOfAServiceAddsNoLayer) {
  auto layers = config_layers("planner", "field", "");
  ASSERT_TRUE(layers) << layers.error().message;
  EXPECT_THAT(*layers, ElementsAre(path("config/planner.yaml")));
}

TEST_F(DeployFilesTest, AnUnknownSiteIsAnErrorNamingTheKnownOnes) {
  auto layers = config_layers("vision_gateway", "feild", "");
  ASSERT_FALSE(layers);
  EXPECT_THAT(layers.error().message, HasSubstr("unknown site 'feild' (known: field, sim; or give a directory)"));
}

TEST_F(DeployFilesTest, ASiteMayBeADirectory) {
  write("elsewhere/lab/vision_gateway.yaml", "network: {vision_port: 10555}\n");
  const std::string lab = (root_ / "elsewhere/lab").string();
  auto layers = config_layers("vision_gateway", lab, "");
  ASSERT_TRUE(layers) << layers.error().message;
  EXPECT_THAT(*layers, ElementsAre(path("config/vision_gateway.yaml"), path("elsewhere/lab/vision_gateway.yaml")));
  EXPECT_THAT(config_layers("vision_gateway", lab + "/missing", "").error().message, HasSubstr("does not exist"));
}

TEST_F(DeployFilesTest, TheFlagWinsOverTheEnvironment) {
  EXPECT_EQ(chosen_site(""), "");
  ::setenv("SSL_SITE", "field", 1);
  EXPECT_EQ(chosen_site(""), "field");
  EXPECT_EQ(chosen_site("sim"), "sim");
}

}  // namespace
}  // namespace ssl
