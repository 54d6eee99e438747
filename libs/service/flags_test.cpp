#include "libs/service/flags.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <CLI/CLI.hpp>
#include <algorithm>

namespace ssl::service {
namespace {

using ::testing::ElementsAre;

// Parses `args` (without the program name) with the common flags and a --team key flag.
CommonFlags parse(std::vector<std::string> args) {
  CommonFlags flags;
  CLI::App app{"test", "test"};
  add_common_flags(app, flags, {.help_config = true});
  add_key_flag(app, flags, "--team", "team", "our colour", {"blue", "yellow"});
  std::reverse(args.begin(), args.end());  // CLI11 takes the arguments last first
  app.parse(args);
  return flags;
}

TEST(CommonFlags, ADedicatedFlagWinsOverASetOfTheSameKeyWhateverTheOrder) {
  // Before the shared flags, world_model's --set replaced the vector --team had written into: the team
  // was lost whenever --set came too.
  EXPECT_THAT(parse({"--team", "yellow", "--set", "team=blue", "publish_rate=50"}).overrides(),
              ElementsAre("team=blue", "publish_rate=50", "team=yellow"));
  EXPECT_THAT(parse({"--set", "team=blue", "--team", "yellow"}).overrides(), ElementsAre("team=blue", "team=yellow"));
}

TEST(CommonFlags, EveryServiceHasTheSameCommonFlags) {
  const CommonFlags flags =
      parse({"--config", "mine.yaml", "--site", "field", "--domain", "7", "--log-level", "debug", "--print-config"});
  EXPECT_EQ(flags.config_file, "mine.yaml");
  EXPECT_EQ(flags.site, "field");
  EXPECT_EQ(flags.domain, 7);
  EXPECT_EQ(flags.log_level, "debug");
  EXPECT_TRUE(flags.print_config);
  EXPECT_THROW(parse({"--domain", "233"}), CLI::ValidationError);
  EXPECT_THROW(parse({"--team", "green"}), CLI::ValidationError);
  EXPECT_THROW(parse({"--log-level", "loud"}), CLI::ValidationError);
}

}  // namespace
}  // namespace ssl::service
