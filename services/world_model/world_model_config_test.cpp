#include "services/world_model/world_model_config.h"

#include <gtest/gtest.h>

#include "libs/common/deploy_files.h"

namespace ssl::wm {
namespace {

TEST(WorldModelConfig, DeployedFileLoadsAndTeamOverrideApplies) {
  auto path = find_deploy_file("config/world_model.yaml");
  ASSERT_TRUE(path) << path.error().message;
  auto config = load_world_model_config(*path, {"team=yellow"});
  ASSERT_TRUE(config) << config.error().message;
  EXPECT_EQ(config->team, TeamColor::kYellow);
  EXPECT_EQ(config->core.team, TeamColor::kYellow);
  EXPECT_EQ(config->publish_mode, PublishMode::kOnFrame);
  EXPECT_FALSE(load_world_model_config(*path, {"team=green"}));
}

}  // namespace
}  // namespace ssl::wm
