#include "services/planner/planner_config.h"

#include <gtest/gtest.h>

#include <cstdio>
#include <fstream>

#include "libs/common/deploy_files.h"

namespace ssl::planner {
namespace {

std::string deployed() {
  auto path = find_deploy_file("config/planner.yaml");
  EXPECT_TRUE(path) << path.error().message;
  return path ? *path : std::string();
}

TEST(PlannerConfig, DeployedFileLoadsWithTheDocumentedDefaults) {
  auto config = load_planner_config(deployed(), {});
  ASSERT_TRUE(config) << config.error().message;
  EXPECT_EQ(config->team, TeamColor::kBlue);
  EXPECT_EQ(config->core.team, TeamColor::kBlue);
  EXPECT_EQ(config->tick_mode, TickMode::kOnWorldState);
  EXPECT_DOUBLE_EQ(config->core.tick_period, 0.01) << "the core's nominal first dt";
  EXPECT_DOUBLE_EQ(config->core.stop_speed, 1.5);
  EXPECT_DOUBLE_EQ(config->core.limits.max_speed, 3.0);
  EXPECT_EQ(config->default_division, Division::kA);
  EXPECT_DOUBLE_EQ(config->core.default_field.field_length, 12.0);
  EXPECT_EQ(config->core.free_kick, FreeKickPlay::kShot);
  EXPECT_EQ(config->core.kickoff, KickoffPlay::kPass);
  EXPECT_EQ(config->core.penalty, PenaltyPlay::kAdvance);
}

TEST(PlannerConfig, OverridesApplyAndDerivedValuesFollow) {
  auto config = load_planner_config(
      deployed(), {"team=yellow", "tick_mode=fixed_rate", "tick_rate=50", "default_division=b",
                   "planner.limits.max_speed=2.5", "planner.free_kick=redirect", "planner.kickoff=shot",
                   "planner.penalty=shot"});
  ASSERT_TRUE(config) << config.error().message;
  EXPECT_EQ(config->core.team, TeamColor::kYellow);
  EXPECT_EQ(config->tick_mode, TickMode::kFixedRate);
  EXPECT_DOUBLE_EQ(config->core.tick_period, 0.02);
  EXPECT_DOUBLE_EQ(config->core.limits.max_speed, 2.5);
  EXPECT_EQ(config->core.free_kick, FreeKickPlay::kRedirect);
  EXPECT_EQ(config->core.kickoff, KickoffPlay::kShot);
  EXPECT_EQ(config->core.penalty, PenaltyPlay::kShot);
  EXPECT_DOUBLE_EQ(config->core.default_field.field_length, 9.0);
  EXPECT_DOUBLE_EQ(config->core.default_field.goal_width, 1.0);
  EXPECT_DOUBLE_EQ(config->core.default_field.goal_center_to_penalty_mark, 6.0);
}

TEST(PlannerConfig, BadValuesAreRejectedWithTheKeyNamed) {
  auto team = load_planner_config(deployed(), {"team=green"});
  ASSERT_FALSE(team);
  EXPECT_NE(team.error().message.find("team"), std::string::npos) << team.error().message;

  auto too_fast = load_planner_config(deployed(), {"planner.stop_speed=2.0"});
  ASSERT_FALSE(too_fast);
  EXPECT_NE(too_fast.error().message.find("stop_speed"), std::string::npos) << too_fast.error().message;

  auto margin = load_planner_config(deployed(), {"planner.stop_speed=0.2", "planner.stop_speed_margin=0.3"});
  ASSERT_FALSE(margin);
  EXPECT_NE(margin.error().message.find("stop_speed_margin"), std::string::npos) << margin.error().message;

  auto free_kick = load_planner_config(deployed(), {"planner.free_kick=chip"});
  ASSERT_FALSE(free_kick);
  EXPECT_NE(free_kick.error().message.find("free_kick"), std::string::npos) << free_kick.error().message;

  auto kickoff = load_planner_config(deployed(), {"planner.kickoff=chip"});
  ASSERT_FALSE(kickoff);
  EXPECT_NE(kickoff.error().message.find("kickoff"), std::string::npos) << kickoff.error().message;

  auto penalty = load_planner_config(deployed(), {"planner.penalty=chip"});
  ASSERT_FALSE(penalty);
  EXPECT_NE(penalty.error().message.find("penalty"), std::string::npos) << penalty.error().message;

  auto unknown = load_planner_config(deployed(), {"tick_mod=fixed_rate"});
  EXPECT_FALSE(unknown);
  EXPECT_FALSE(load_planner_config(deployed(), {"tick_rate=nan"}));
  // The on_world_state rate cap is gone: a config still setting it is told so, not silently obeyed.
  auto old_cap = load_planner_config(deployed(), {"max_rate=100"});
  ASSERT_FALSE(old_cap);
  EXPECT_NE(old_cap.error().message.find("max_rate"), std::string::npos) << old_cap.error().message;
  EXPECT_FALSE(load_planner_config("/nonexistent/planner.yaml", {}));
}

TEST(PlannerConfig, PrintedConfigLoadsBackEqual) {
  auto config = load_planner_config(deployed(), {"team=yellow", "planner.keep_away_margin=0.25"});
  ASSERT_TRUE(config) << config.error().message;
  const std::string yaml = planner_config_yaml(*config);
  const std::string path = ::testing::TempDir() + "planner_config_roundtrip.yaml";
  std::ofstream(path) << yaml;
  auto again = load_planner_config(path, {});
  std::remove(path.c_str());
  ASSERT_TRUE(again) << again.error().message << "\n" << yaml;
  EXPECT_EQ(again->team, TeamColor::kYellow);
  EXPECT_DOUBLE_EQ(again->core.keep_away_margin, 0.25);
  EXPECT_EQ(planner_config_yaml(*again), yaml);
  EXPECT_NE(planner_config_help().find("stale_world_timeout"), std::string::npos);
}

}  // namespace
}  // namespace ssl::planner
