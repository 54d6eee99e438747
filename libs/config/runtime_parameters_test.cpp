#include "libs/config/runtime_parameters.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

namespace ssl::config {
namespace {

using ::testing::HasSubstr;

enum class Mode { kCalm, kWild };

struct Limits {
  double max_speed = 0;
  int retries = 0;
};

struct Settings {
  Limits limits;
  Mode mode = Mode::kCalm;
  std::string name;
  bool enabled = false;
  double derived = 0;  // not in the schema: filled from max_speed
};

Fields<Settings> settings_fields() {
  return Fields<Settings>{
      nested("limits", &Settings::limits,
             Fields<Limits>{field("max_speed", &Limits::max_speed).unit("m/s").range(0.5, 4.0).doc("top speed"),
                            field("retries", &Limits::retries).range(0, 5)}),
      field("mode", &Settings::mode).values({{"calm", Mode::kCalm}, {"wild", Mode::kWild}}),
      field("name", &Settings::name),
      field("enabled", &Settings::enabled),
  }
      .check([](const Settings& s) -> Status {
        if (s.mode == Mode::kWild && s.limits.max_speed < 1.0) return Error{"wild needs max_speed >= 1"};
        return {};
      });
}

Settings initial() {
  return {.limits = {.max_speed = 2.0, .retries = 1}, .mode = Mode::kCalm, .name = "a b", .enabled = true, .derived = 4.0};
}

RuntimeParameters<Settings> make() {
  auto params = RuntimeParameters<Settings>::create(initial(), settings_fields(),
                                                    {"limits.max_speed", "mode", "name", "enabled"},
                                                    [](Settings& s) { s.derived = 2 * s.limits.max_speed; });
  EXPECT_TRUE(params) << params.error().message;
  return std::move(*params);
}

TEST(RuntimeParameters, DescribesTheRunTimeKeysWithTheirSchema) {
  const std::vector<KeyInfo> keys = make().describe();
  ASSERT_EQ(keys.size(), 4u);
  EXPECT_EQ(keys[0].key, "limits.max_speed");
  EXPECT_EQ(keys[0].type, "number");
  EXPECT_EQ(keys[0].value, "2");
  EXPECT_EQ(keys[0].min, 0.5);
  EXPECT_EQ(keys[0].max, 4.0);
  EXPECT_EQ(keys[0].unit, "m/s");
  EXPECT_EQ(keys[0].doc, "top speed");
  EXPECT_EQ(keys[1].allowed, (std::vector<std::string>{"calm", "wild"}));
  EXPECT_EQ(keys[1].value, "calm");
  EXPECT_EQ(keys[2].value, "a b");  // strings unquoted
  EXPECT_EQ(keys[3].type, "boolean");
}

TEST(RuntimeParameters, AChangeIsCheckedLikeTheConfigFileAndDerivedValuesFollow) {
  auto params = make();
  auto next = params.apply(std::vector<std::pair<std::string, std::string>>{{"limits.max_speed", "3.5"}});
  ASSERT_TRUE(next) << next.error().message;
  EXPECT_EQ(next->limits.max_speed, 3.5);
  EXPECT_EQ(next->derived, 7.0);
  EXPECT_EQ(params.current().limits.max_speed, 3.5);

  auto range = params.apply(std::vector<std::pair<std::string, std::string>>{{"limits.max_speed", "9"}});
  ASSERT_FALSE(range);
  EXPECT_THAT(range.error().message, HasSubstr("limits.max_speed"));
  EXPECT_THAT(range.error().message, HasSubstr("range"));
  auto type = params.apply(std::vector<std::pair<std::string, std::string>>{{"enabled", "maybe"}});
  ASSERT_FALSE(type);
  EXPECT_THAT(type.error().message, HasSubstr("enabled"));
  auto one_of = params.apply(std::vector<std::pair<std::string, std::string>>{{"mode", "fast"}});
  ASSERT_FALSE(one_of);
  EXPECT_THAT(one_of.error().message, HasSubstr("calm"));
  EXPECT_EQ(params.current().limits.max_speed, 3.5);  // refused changes leave it as it was
}

TEST(RuntimeParameters, KeysThatAreNotRunTimeAreRefused) {
  auto params = make();
  auto refused = params.apply(std::vector<std::pair<std::string, std::string>>{{"limits.retries", "2"}});
  ASSERT_FALSE(refused);
  EXPECT_THAT(refused.error().message, HasSubstr("cannot change at run time"));
  EXPECT_FALSE(RuntimeParameters<Settings>::create(initial(), settings_fields(), {"limits"}));
  EXPECT_FALSE(RuntimeParameters<Settings>::create(initial(), settings_fields(), {"no.such"}));
}

TEST(RuntimeParameters, AllChangesOfARequestOrNone) {
  auto params = make();
  // Each change alone is fine; together they break the whole-struct check.
  auto refused = params.apply(
      std::vector<std::pair<std::string, std::string>>{{"limits.max_speed", "0.6"}, {"mode", "wild"}});
  ASSERT_FALSE(refused);
  EXPECT_THAT(refused.error().message, HasSubstr("wild needs"));
  EXPECT_EQ(params.current().limits.max_speed, 2.0);
  EXPECT_EQ(params.current().mode, Mode::kCalm);
}

TEST(RuntimeParameters, ChangedKeysSaveAsALayerThatLoadsBack) {
  auto params = make();
  ASSERT_TRUE(params.apply(std::vector<std::pair<std::string, std::string>>{
      {"limits.max_speed", "1.25"}, {"name", "it's"}, {"enabled", "false"}}));
  const std::vector<KeyInfo> changed = params.changed();
  ASSERT_EQ(changed.size(), 3u);
  const std::string layer = layer_yaml(changed);
  EXPECT_EQ(layer, "limits:\n  max_speed: 1.25\nname: 'it''s'\nenabled: false\n");

  const auto dir = std::filesystem::temp_directory_path();
  const std::string defaults = (dir / "runtime_parameters_defaults.yaml").string();
  const std::string saved = (dir / "runtime_parameters_saved.yaml").string();
  std::ofstream(defaults) << to_yaml(initial(), settings_fields());
  std::ofstream(saved) << layer;
  const std::vector<std::string> files{defaults, saved};
  auto loaded = load_files(std::span<const std::string>(files), settings_fields());
  ASSERT_TRUE(loaded) << loaded.error().message;
  EXPECT_EQ(loaded->limits.max_speed, 1.25);
  EXPECT_EQ(loaded->name, "it's");
  EXPECT_FALSE(loaded->enabled);
  EXPECT_EQ(loaded->limits.retries, 1);
}

}  // namespace
}  // namespace ssl::config
