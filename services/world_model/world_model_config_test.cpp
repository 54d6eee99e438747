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

TEST(WorldModelConfig, ImmModesNeedOneToFourJerkDensitiesEachWithItsAngularAccelerationAndTimeConstant) {
  auto path = find_deploy_file("config/world_model.yaml");
  ASSERT_TRUE(path) << path.error().message;
  auto deployed = load_world_model_config(*path, {});
  ASSERT_TRUE(deployed) << deployed.error().message;
  EXPECT_EQ(deployed->core.robot.mode_jerk_stddev, RobotFilterParams{}.mode_jerk_stddev);
  EXPECT_EQ(deployed->core.robot.mode_angular_acceleration_stddev,
            RobotFilterParams{}.mode_angular_acceleration_stddev);
  EXPECT_EQ(deployed->core.robot.mode_acceleration_time_constant, RobotFilterParams{}.mode_acceleration_time_constant);
  auto two = load_world_model_config(*path, {"filter.robot.mode_jerk_stddev=[0.05, 5]",
                                             "filter.robot.mode_angular_acceleration_stddev=[5, 20]",
                                             "filter.robot.mode_acceleration_time_constant=[1, 0.3]"});
  ASSERT_TRUE(two) << two.error().message;
  EXPECT_EQ(two->core.robot.mode_jerk_stddev.size(), 2u);
  auto unpaired = load_world_model_config(*path, {"filter.robot.mode_jerk_stddev=[0.05, 5]"});
  ASSERT_FALSE(unpaired);
  EXPECT_NE(unpaired.error().message.find("mode_angular_acceleration_stddev needs one value per mode_jerk_stddev "
                                          "(2), has 3"),
            std::string::npos)
      << unpaired.error().message;
  auto time_constants = load_world_model_config(*path, {"filter.robot.mode_acceleration_time_constant=[1]"});
  ASSERT_FALSE(time_constants);
  EXPECT_NE(time_constants.error().message.find("mode_acceleration_time_constant needs one value"), std::string::npos)
      << time_constants.error().message;
  auto none = load_world_model_config(*path, {"filter.robot.mode_jerk_stddev=[]"});
  ASSERT_FALSE(none);
  EXPECT_NE(none.error().message.find("mode_jerk_stddev"), std::string::npos) << none.error().message;
  EXPECT_FALSE(load_world_model_config(*path, {"filter.robot.mode_jerk_stddev=[1, 2, 3, 4, 5]"}));
  EXPECT_FALSE(load_world_model_config(*path, {"filter.robot.mode_jerk_stddev=[1, -2]"}));
}

}  // namespace
}  // namespace ssl::wm
