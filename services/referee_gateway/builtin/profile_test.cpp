// Referee profiles: both built-ins load with the settings their documentation promises, a file path
// works, mistakes are reported with the key named, and unknown names list the built-in ones.
#include "services/referee_gateway/builtin/profile.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>

namespace ssl::referee {
namespace {

std::string write_temp_file(const std::string& file_name, const std::string& text) {
  const std::filesystem::path path = std::filesystem::path(::testing::TempDir()) / file_name;
  std::ofstream(path) << text;
  return path.string();
}

TEST(RefereeProfile, ArcadeDetectsGoalsOnlyAndForceStartsAfterTwoSeconds) {
  auto profile = load_referee_profile("arcade");
  ASSERT_TRUE(profile) << profile.error().message;
  EXPECT_EQ(profile->name, "arcade");
  EXPECT_TRUE(profile->rules.goal_detection.enabled);
  EXPECT_FALSE(profile->rules.out_of_bounds.enabled);
  EXPECT_FALSE(profile->rules.defense_area.enabled);
  EXPECT_FALSE(profile->rules.keep_out.enabled);
  EXPECT_TRUE(profile->game.force_start_after_goal);
  EXPECT_TRUE(profile->game.auto_continue);
  EXPECT_DOUBLE_EQ(profile->game.stop_duration, 2.0);
}

TEST(RefereeProfile, StrictAiEnablesAllFourRulesAndWaitsForTheOperatorAfterAGoal) {
  auto profile = load_referee_profile("strict_ai");
  ASSERT_TRUE(profile) << profile.error().message;
  EXPECT_EQ(profile->name, "strict_ai");
  EXPECT_TRUE(profile->rules.goal_detection.enabled);
  EXPECT_TRUE(profile->rules.out_of_bounds.enabled);
  EXPECT_TRUE(profile->rules.out_of_bounds.ball_placement);
  EXPECT_DOUBLE_EQ(profile->rules.out_of_bounds.line_distance, 0.2);
  EXPECT_DOUBLE_EQ(profile->rules.out_of_bounds.goal_kick_distance, 1.0);
  EXPECT_TRUE(profile->rules.defense_area.enabled);
  EXPECT_EQ(profile->rules.defense_area.max_defenders, 1u);
  EXPECT_TRUE(profile->rules.defense_area.attacker_infringement);
  EXPECT_TRUE(profile->rules.keep_out.enabled);
  EXPECT_DOUBLE_EQ(profile->rules.keep_out.radius, 0.5);
  EXPECT_DOUBLE_EQ(profile->rules.keep_out.violation_persistence, 2.0);
  EXPECT_FALSE(profile->game.force_start_after_goal);
  EXPECT_FALSE(profile->game.auto_continue);
  EXPECT_DOUBLE_EQ(profile->game.placement_timeout, 30.0);
  EXPECT_DOUBLE_EQ(profile->game.placement_tolerance, 0.15);
  EXPECT_DOUBLE_EQ(profile->game.half_duration, 300.0);
  EXPECT_EQ(profile->game.kickoff_team, TeamColor::kYellow);
}

TEST(RefereeProfile, SimulationRefereesGoalsAndOutOfBoundsAndContinuesWithoutAnOperator) {
  auto profile = load_referee_profile("simulation");
  ASSERT_TRUE(profile) << profile.error().message;
  EXPECT_EQ(profile->name, "simulation");
  EXPECT_TRUE(profile->rules.goal_detection.enabled);
  EXPECT_TRUE(profile->rules.out_of_bounds.enabled);
  EXPECT_TRUE(profile->rules.out_of_bounds.ball_placement);
  EXPECT_FALSE(profile->rules.defense_area.enabled);
  EXPECT_TRUE(profile->rules.keep_out.enabled);
  EXPECT_FALSE(profile->game.force_start_after_goal);  // the conceding team kicks off ...
  EXPECT_TRUE(profile->game.auto_continue);           // ... without an operator
}

TEST(RefereeProfile, APathLoadsAndThePrintedYamlLoadsBackEqual) {
  auto strict = load_referee_profile("strict_ai");
  ASSERT_TRUE(strict) << strict.error().message;
  std::string yaml = referee_profile_yaml(*strict);
  const std::string path = write_temp_file("referee_profile_roundtrip.yaml", yaml);
  auto reloaded = load_referee_profile(path);
  ASSERT_TRUE(reloaded) << reloaded.error().message;
  EXPECT_EQ(referee_profile_yaml(*reloaded), yaml);
  EXPECT_EQ(reloaded->game.kickoff_team, TeamColor::kYellow);
}

TEST(RefereeProfile, AnOutOfRangeValueNamesItsKey) {
  auto strict = load_referee_profile("strict_ai");
  ASSERT_TRUE(strict) << strict.error().message;
  std::string yaml = referee_profile_yaml(*strict);
  const std::string original = "radius: 0.5";
  const std::size_t at = yaml.find(original);
  ASSERT_NE(at, std::string::npos) << yaml;
  yaml.replace(at, original.size(), "radius: -4");
  auto loaded = load_referee_profile(write_temp_file("referee_profile_bad_radius.yaml", yaml));
  ASSERT_FALSE(loaded);
  EXPECT_NE(loaded.error().message.find("rules.keep_out.radius"), std::string::npos)
      << loaded.error().message;
  EXPECT_NE(loaded.error().message.find("referee_profile_bad_radius.yaml"), std::string::npos)
      << loaded.error().message;
}

TEST(RefereeProfile, AMissingKeyAndABadKickoffTeamAreBothNamed) {
  // strict_ai as YAML, with one key taken out and one value made invalid.
  auto strict = load_referee_profile("strict_ai");
  ASSERT_TRUE(strict) << strict.error().message;
  std::string yaml = referee_profile_yaml(*strict);
  const auto remove_line_with = [&](const std::string& text) {
    const std::size_t at = yaml.find(text);
    ASSERT_NE(at, std::string::npos) << text;
    const std::size_t begin = yaml.rfind('\n', at) + 1;
    yaml.erase(begin, yaml.find('\n', at) + 1 - begin);
  };
  const std::size_t keep_out = yaml.find("keep_out:");
  ASSERT_NE(keep_out, std::string::npos);
  const std::size_t persistence = yaml.find("violation_persistence:", keep_out);
  ASSERT_NE(persistence, std::string::npos);
  remove_line_with(yaml.substr(persistence, yaml.find('\n', persistence) - persistence));
  const std::size_t kickoff = yaml.find("kickoff_team: yellow");
  ASSERT_NE(kickoff, std::string::npos);
  yaml.replace(kickoff, std::string("kickoff_team: yellow").size(), "kickoff_team: green");
  auto loaded = load_referee_profile_from_string(yaml, "mine.yaml");
  ASSERT_FALSE(loaded);
  const std::string& message = loaded.error().message;
  EXPECT_NE(message.find("rules.keep_out.violation_persistence"), std::string::npos) << message;
  EXPECT_NE(message.find("game.kickoff_team"), std::string::npos) << message;
}

TEST(RefereeProfile, AnUnknownNameListsTheBuiltInProfiles) {
  auto loaded = load_referee_profile("no_such_profile");
  ASSERT_FALSE(loaded);
  EXPECT_NE(loaded.error().message.find("unknown referee profile 'no_such_profile'"), std::string::npos)
      << loaded.error().message;
  EXPECT_NE(loaded.error().message.find("arcade, strict_ai, simulation"), std::string::npos) << loaded.error().message;
  EXPECT_FALSE(load_referee_profile("../secrets"));
  EXPECT_FALSE(load_referee_profile("/no/such/file.yaml"));
}

}  // namespace
}  // namespace ssl::referee
