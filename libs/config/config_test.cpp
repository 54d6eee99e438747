#include "libs/config/config.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include <unistd.h>

namespace ssl::config {
namespace {

using ::testing::HasSubstr;
using ::testing::Not;

enum class Division { kA, kB };

struct Physics {
  double ball_radius_m = 0;
  double friction = 0;
  bool operator==(const Physics&) const = default;
};

struct Robot {
  int id = 0;
  std::string name;
  bool operator==(const Robot&) const = default;
};

struct SimConfig {
  Physics physics;
  int robots_per_team = 0;
  Division division = Division::kA;
  std::string team;
  std::vector<double> gains;
  bool realism = false;
  std::uint16_t port = 0;
  std::vector<Robot> robots;
  std::vector<std::string> tags;
  bool operator==(const SimConfig&) const = default;
};

Fields<Physics> physics_fields() {
  return {
      field("ball_radius", &Physics::ball_radius_m).unit("m").range(0.01, 0.05).doc("ball radius"),
      optional_field("friction", &Physics::friction, 0.3).range(0.0, 1.0),
  };
}

Fields<Robot> robot_fields() {
  return {
      field("id", &Robot::id).range(0, 15).doc("robot id on its shirt"),
      optional_field("name", &Robot::name, ""),
  };
}

Fields<SimConfig> sim_fields() {
  return Fields<SimConfig>{
      nested("physics", &SimConfig::physics, physics_fields()),
      field("robots_per_team", &SimConfig::robots_per_team).range(0, 16),
      field("division", &SimConfig::division).values({{"a", Division::kA}, {"b", Division::kB}}),
      field("team", &SimConfig::team).one_of({"blue", "yellow"}),
      optional_field("gains", &SimConfig::gains, {1.0, 2.0}).range(0.0, 10.0).length(1, 3),
      optional_field("realism", &SimConfig::realism, false).doc("add vision noise"),
      field("port", &SimConfig::port),
      optional_nested_list("robots", &SimConfig::robots, robot_fields()),
      optional_field("tags", &SimConfig::tags, {}),
  }
      .check([](const SimConfig& c) -> Status {
        if (static_cast<int>(c.robots.size()) > c.robots_per_team) {
          return Error{"lists " + std::to_string(c.robots.size()) + " robots but robots_per_team is " +
                       std::to_string(c.robots_per_team)};
        }
        return Status::success();
      });
}

const char* const kValidYaml = R"(# simulator config
physics:
  ball_radius: 0.0215  # [m]
robots_per_team: 11
division: b
team: "blue"
gains: [1.5, 2]
realism: true
port: 10300
robots:
  - id: 0
    name: "keeper"
  - id: 1
tags: [x, y]
)";

// The YAML of kValidYaml with one line replaced (or appended when `old_line` is empty).
std::string valid_yaml_with(const std::string& old_line, const std::string& new_line) {
  std::string yaml = kValidYaml;
  if (old_line.empty()) return yaml + new_line + "\n";
  const std::size_t at = yaml.find(old_line);
  EXPECT_NE(at, std::string::npos) << old_line;
  return yaml.replace(at, old_line.size(), new_line);
}

std::string load_error(const std::string& yaml, std::span<const std::string> overrides = {}) {
  Result<SimConfig> loaded = load_string(yaml, sim_fields(), "deploy/config/sim.yaml", overrides);
  EXPECT_FALSE(loaded) << "expected an error for:\n" << yaml;
  return loaded ? std::string() : loaded.error().message;
}

// ---------------------------------------------------------------------------------------------------------
// Valid input

TEST(ConfigLoadTest, LoadsNestedStructsListsEnumsAndDefaults) {
  Result<SimConfig> loaded = load_string(kValidYaml, sim_fields(), "sim.yaml");
  ASSERT_TRUE(loaded) << loaded.error().message;
  const SimConfig& c = *loaded;
  EXPECT_EQ(c.physics.ball_radius_m, 0.0215);
  EXPECT_EQ(c.physics.friction, 0.3);  // default
  EXPECT_EQ(c.robots_per_team, 11);
  EXPECT_EQ(c.division, Division::kB);
  EXPECT_EQ(c.team, "blue");
  EXPECT_EQ(c.gains, (std::vector<double>{1.5, 2.0}));
  EXPECT_TRUE(c.realism);
  EXPECT_EQ(c.port, 10300);
  ASSERT_EQ(c.robots.size(), 2u);
  EXPECT_EQ(c.robots[0], (Robot{0, "keeper"}));
  EXPECT_EQ(c.robots[1], (Robot{1, ""}));  // name defaulted
  EXPECT_EQ(c.tags, (std::vector<std::string>{"x", "y"}));
}

TEST(ConfigLoadTest, OptionalKeysTakeTheirExplicitDefaults) {
  const std::string yaml =
      "physics: {ball_radius: 0.02}\nrobots_per_team: 6\ndivision: a\nteam: yellow\nport: 1\n";
  Result<SimConfig> loaded = load_string(yaml, sim_fields());
  ASSERT_TRUE(loaded) << loaded.error().message;
  EXPECT_EQ(loaded->gains, (std::vector<double>{1.0, 2.0}));
  EXPECT_FALSE(loaded->realism);
  EXPECT_TRUE(loaded->robots.empty());
  EXPECT_TRUE(loaded->tags.empty());
  EXPECT_EQ(loaded->physics.friction, 0.3);
}

TEST(ConfigLoadTest, AcceptsIntegersForDoublesAndPlusSigns) {
  Result<SimConfig> loaded =
      load_string(valid_yaml_with("gains: [1.5, 2]", "gains: [+3, 1e-1]"), sim_fields());
  ASSERT_TRUE(loaded) << loaded.error().message;
  EXPECT_EQ(loaded->gains, (std::vector<double>{3.0, 0.1}));
}

// ---------------------------------------------------------------------------------------------------------
// Each error kind names the file, line and key path

TEST(ConfigErrorTest, UnknownKeySuggestsTheClosestKnownKey) {
  const std::string message =
      load_error(valid_yaml_with("  ball_radius: 0.0215  # [m]", "  bal_radius: 0.02"));
  EXPECT_THAT(message, HasSubstr("deploy/config/sim.yaml:3: unknown key 'physics.bal_radius' "
                                 "(did you mean 'ball_radius'?)"));
}

TEST(ConfigErrorTest, UnknownKeyWithoutACloseMatchListsTheAllowedKeys) {
  const std::string message = load_error(valid_yaml_with("", "completely_different: 1"));
  EXPECT_EQ(message,
            "deploy/config/sim.yaml:15: unknown key 'completely_different' (allowed here: physics, "
            "robots_per_team, division, team, gains, realism, port, robots, tags)");
}

TEST(ConfigErrorTest, UnknownKeyInsideAListElement) {
  const std::string message = load_error(valid_yaml_with("  - id: 1", "  - id: 1\n    nmae: striker"));
  EXPECT_THAT(message,
              HasSubstr("deploy/config/sim.yaml:14: unknown key 'robots[1].nmae' (did you mean 'name'?)"));
}

TEST(ConfigErrorTest, MissingRequiredKeyNamesTheFullPathTypeUnitAndDoc) {
  EXPECT_EQ(load_error(valid_yaml_with("robots_per_team: 11\n", "")),
            "deploy/config/sim.yaml: missing required key 'robots_per_team' (integer)");
  EXPECT_EQ(load_error(valid_yaml_with("  ball_radius: 0.0215  # [m]\n", "")),
            "deploy/config/sim.yaml: missing required key 'physics.ball_radius' (number, m): ball radius");
  // An absent nested block reports its required keys by full path, too.
  EXPECT_EQ(load_error(valid_yaml_with("physics:\n  ball_radius: 0.0215  # [m]\n", "")),
            "deploy/config/sim.yaml: missing required key 'physics.ball_radius' (number, m): ball radius");
  EXPECT_THAT(load_error(valid_yaml_with("  - id: 1", "  - name: x")),
              HasSubstr("missing required key 'robots[1].id' (integer): robot id on its shirt"));
}

TEST(ConfigErrorTest, WrongTypesAreNamed) {
  EXPECT_EQ(load_error(valid_yaml_with("robots_per_team: 11", "robots_per_team: eleven")),
            "deploy/config/sim.yaml:4: key 'robots_per_team': expected an integer, got 'eleven'");
  EXPECT_EQ(
      load_error(valid_yaml_with("  ball_radius: 0.0215  # [m]", "  ball_radius: \"0.02\"")),
      "deploy/config/sim.yaml:3: key 'physics.ball_radius': expected a number, got the string \"0.02\"");
  EXPECT_EQ(load_error(valid_yaml_with("team: \"blue\"", "team: [blue]")),
            "deploy/config/sim.yaml:6: key 'team': expected a string, got a list");
  EXPECT_EQ(load_error(valid_yaml_with("gains: [1.5, 2]", "gains: 1.5")),
            "deploy/config/sim.yaml:7: key 'gains': expected a list, got '1.5'");
  EXPECT_EQ(load_error(valid_yaml_with("gains: [1.5, 2]", "gains: [1.5, fast]")),
            "deploy/config/sim.yaml:7: key 'gains[1]': expected a number, got 'fast'");
  EXPECT_EQ(load_error(valid_yaml_with("physics:\n  ball_radius: 0.0215  # [m]", "physics: 3")),
            "deploy/config/sim.yaml:2: key 'physics': expected a map of keys, got '3'");
  EXPECT_EQ(load_error(valid_yaml_with("realism: true", "realism: yes")),
            "deploy/config/sim.yaml:8: key 'realism': expected true or false, got 'yes'");
}

TEST(ConfigErrorTest, IntegersMustBeWholeAndFitTheMemberType) {
  EXPECT_EQ(load_error(valid_yaml_with("robots_per_team: 11", "robots_per_team: 3.5")),
            "deploy/config/sim.yaml:4: key 'robots_per_team': expected an integer, got '3.5'");
  EXPECT_EQ(load_error(valid_yaml_with("port: 10300", "port: 70000")),
            "deploy/config/sim.yaml:9: key 'port': 70000 does not fit this field's type [0, 65535]");
  EXPECT_EQ(load_error(valid_yaml_with("port: 10300", "port: -1")),
            "deploy/config/sim.yaml:9: key 'port': expected a non-negative integer, got '-1'");
  EXPECT_EQ(load_error(valid_yaml_with("robots_per_team: 11", "robots_per_team: 99999999999999999999")),
            "deploy/config/sim.yaml:4: key 'robots_per_team': 99999999999999999999 is too large for a 64-bit "
            "integer");
}

TEST(ConfigErrorTest, OutOfRangeValueNamesTheRangeAndUnit) {
  EXPECT_EQ(load_error(valid_yaml_with("  ball_radius: 0.0215  # [m]", "  ball_radius: 0.5")),
            "deploy/config/sim.yaml:3: key 'physics.ball_radius': 0.5 is out of range [0.01, 0.05] (m)");
  EXPECT_EQ(load_error(valid_yaml_with("robots_per_team: 11", "robots_per_team: 17")),
            "deploy/config/sim.yaml:4: key 'robots_per_team': 17 is out of range [0, 16]");
  EXPECT_EQ(load_error(valid_yaml_with("gains: [1.5, 2]", "gains: [1.5, 11]")),
            "deploy/config/sim.yaml:7: key 'gains[1]': 11 is out of range [0, 10]");
  EXPECT_EQ(load_error(valid_yaml_with("  - id: 1", "  - id: 99")),
            "deploy/config/sim.yaml:13: key 'robots[1].id': 99 is out of range [0, 15]");
}

TEST(ConfigErrorTest, NonFiniteNumbersAreRejected) {
  for (const char* value : {".nan", ".inf", "-.inf", "nan", "inf"}) {
    EXPECT_EQ(
        load_error(valid_yaml_with("  ball_radius: 0.0215  # [m]", std::string("  ball_radius: ") + value)),
        std::string("deploy/config/sim.yaml:3: key 'physics.ball_radius': ") + value +
            " is not a finite number");
  }
}

TEST(ConfigErrorTest, BadEnumAndOneOfValuesListTheAllowedOnes) {
  EXPECT_EQ(load_error(valid_yaml_with("division: b", "division: c")),
            "deploy/config/sim.yaml:5: key 'division': 'c' is not one of: a, b");
  EXPECT_EQ(load_error(valid_yaml_with("division: b", "division: B")),
            "deploy/config/sim.yaml:5: key 'division': 'B' is not one of: a, b (did you mean 'b'?)");
  EXPECT_EQ(load_error(valid_yaml_with("team: \"blue\"", "team: blu")),
            "deploy/config/sim.yaml:6: key 'team': 'blu' is not one of: blue, yellow (did you mean 'blue'?)");
}

TEST(ConfigErrorTest, ListLengthIsChecked) {
  EXPECT_EQ(load_error(valid_yaml_with("gains: [1.5, 2]", "gains: [1, 2, 3, 4]")),
            "deploy/config/sim.yaml:7: key 'gains': has 4 elements, expected between 1 and 3");
}

TEST(ConfigErrorTest, KeyWithoutAValueIsReported) {
  EXPECT_EQ(load_error(valid_yaml_with("team: \"blue\"", "team:")),
            "deploy/config/sim.yaml:6: key 'team': has no value");
  EXPECT_EQ(load_error(valid_yaml_with("realism: true", "realism: ~")),
            "deploy/config/sim.yaml:8: key 'realism': has no value (write one, or remove the key to use the "
            "default)");
}

TEST(ConfigErrorTest, YamlSyntaxErrorNamesLineAndColumn) {
  const std::string message = load_error(valid_yaml_with("gains: [1.5, 2]", "gains: [1.5, 2"));
  EXPECT_THAT(message, HasSubstr("deploy/config/sim.yaml:"));
  EXPECT_THAT(message, HasSubstr("YAML syntax error: end of sequence flow not found"));
  EXPECT_THAT(load_error("a: 1\n  b: 2\n"),
              HasSubstr("deploy/config/sim.yaml:2:4: YAML syntax error: illegal map value"));
}

TEST(ConfigErrorTest, DuplicateKeysAreRejected) {
  EXPECT_EQ(load_error(valid_yaml_with("", "robots_per_team: 5")),
            "deploy/config/sim.yaml:15: duplicate key 'robots_per_team' (first on line 4)");
}

TEST(ConfigErrorTest, TopLevelMustBeAMap) {
  EXPECT_EQ(load_error("- 1\n- 2\n"),
            "deploy/config/sim.yaml:1: the top level must be a map of keys, got a list");
}

TEST(ConfigErrorTest, EmptyDocumentReportsEveryRequiredKey) {
  const std::string message = load_error("# nothing here\n");
  EXPECT_THAT(message, HasSubstr("missing required key 'physics.ball_radius'"));
  EXPECT_THAT(message, HasSubstr("missing required key 'robots_per_team'"));
  EXPECT_THAT(message, HasSubstr("missing required key 'division' (one of a, b)"));
  EXPECT_THAT(message, HasSubstr("missing required key 'port' (non-negative integer)"));
}

TEST(ConfigErrorTest, AllErrorsOfAFileAreReportedAtOnceOnePerLine) {
  std::string yaml = kValidYaml;
  yaml.replace(yaml.find("robots_per_team: 11"), 19, "robots_per_team: 17");
  yaml.replace(yaml.find("division: b"), 11, "division: z");
  const std::string message = load_error(yaml);
  EXPECT_EQ(message,
            "deploy/config/sim.yaml:4: key 'robots_per_team': 17 is out of range [0, 16]\n"
            "deploy/config/sim.yaml:5: key 'division': 'z' is not one of: a, b");
}

TEST(ConfigErrorTest, WholeStructChecksRunAfterTheFieldsLoaded) {
  EXPECT_EQ(load_error(valid_yaml_with("robots_per_team: 11", "robots_per_team: 1")),
            "deploy/config/sim.yaml: lists 2 robots but robots_per_team is 1");
}

// ---------------------------------------------------------------------------------------------------------
// Files

class ConfigFileTest : public ::testing::Test {
 protected:
  void SetUp() override {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    dir_ = std::filesystem::temp_directory_path() /
           ("ssl_config_test_" + std::string(info->name()) + "_" + std::to_string(::getpid()));
    std::filesystem::create_directories(dir_);
  }
  void TearDown() override { std::filesystem::remove_all(dir_); }

  std::string write(const std::string& name, const std::string& text) {
    const std::filesystem::path path = dir_ / name;
    std::ofstream(path) << text;
    return path.string();
  }

  std::filesystem::path dir_;
};

TEST_F(ConfigFileTest, LoadsAFileAndNamesItInErrors) {
  const std::string good = write("sim.yaml", kValidYaml);
  Result<SimConfig> loaded = load_file(good, sim_fields());
  ASSERT_TRUE(loaded) << loaded.error().message;
  EXPECT_EQ(loaded->robots_per_team, 11);

  const std::string bad =
      write("bad.yaml", valid_yaml_with("  ball_radius: 0.0215  # [m]", "  ball_radius: 0.5"));
  Result<SimConfig> failed = load_file(bad, sim_fields());
  ASSERT_FALSE(failed);
  EXPECT_EQ(failed.error().message,
            bad + ":3: key 'physics.ball_radius': 0.5 is out of range [0.01, 0.05] (m)");
}

TEST_F(ConfigFileTest, UnreadableFileIsReportedWithTheReason) {
  const std::string missing = (dir_ / "missing.yaml").string();
  Result<SimConfig> loaded = load_file(missing, sim_fields());
  ASSERT_FALSE(loaded);
  EXPECT_EQ(loaded.error().message, "cannot read config file '" + missing + "': No such file or directory");

  Result<SimConfig> directory = load_file(dir_.string(), sim_fields());
  ASSERT_FALSE(directory);
  EXPECT_EQ(directory.error().message, "cannot read config file '" + dir_.string() + "': Is a directory");
}

TEST_F(ConfigFileTest, ALayerGivesOnlyTheKeysItChanges) {
  const std::string defaults = write("sim.yaml", kValidYaml);
  const std::string site = write("site.yaml", "physics:\n  friction: 0.5\nport: 10020\n");
  const std::string user = write("user.yaml", "# only one key\nport: 10400\n");
  const std::vector<std::string> layers{defaults, site, user};
  Result<SimConfig> loaded = load_files(layers, sim_fields());
  ASSERT_TRUE(loaded) << loaded.error().message;
  EXPECT_EQ(loaded->port, 10400);                       // the user's file wins over the site
  EXPECT_DOUBLE_EQ(loaded->physics.friction, 0.5);      // the site's key, merged into the map
  EXPECT_DOUBLE_EQ(loaded->physics.ball_radius_m, 0.0215);  // its sibling from the defaults
  EXPECT_EQ(loaded->robots_per_team, 11);

  const std::vector<std::string> overridden{defaults, user};
  const std::vector<std::string> set{"port=10500"};
  EXPECT_EQ(load_files(overridden, sim_fields(), set)->port, 10500);  // --set wins over every file
}

TEST_F(ConfigFileTest, ALayerReplacesListsWhole) {
  const std::string defaults = write("sim.yaml", kValidYaml);
  const std::string layer = write("layer.yaml", "gains: [3, 4]\nrobots:\n  - id: 5\n");
  const std::vector<std::string> layers{defaults, layer};
  Result<SimConfig> loaded = load_files(layers, sim_fields());
  ASSERT_TRUE(loaded) << loaded.error().message;
  EXPECT_EQ(loaded->gains, (std::vector<double>{3, 4}));
  ASSERT_EQ(loaded->robots.size(), 1u);
  EXPECT_EQ(loaded->robots[0].id, 5);
}

TEST_F(ConfigFileTest, ALayersMistakesAreReportedAtItsOwnFileAndLine) {
  const std::string defaults = write("sim.yaml", kValidYaml);
  const std::string layer = write("layer.yaml", "port: 10020\nphysics:\n  bal_radius: 0.03\nrealism: maybe\n");
  const std::vector<std::string> layers{defaults, layer};
  Result<SimConfig> loaded = load_files(layers, sim_fields());
  ASSERT_FALSE(loaded);
  EXPECT_THAT(loaded.error().message,
              HasSubstr(layer + ":3: unknown key 'physics.bal_radius' (did you mean 'ball_radius'?)"));
  EXPECT_THAT(loaded.error().message, HasSubstr(layer + ":4: key 'realism': expected true or false"));

  const std::string broken = write("broken.yaml", "port: [10020\n");
  const std::vector<std::string> with_broken{defaults, broken};
  Result<SimConfig> syntax = load_files(with_broken, sim_fields());
  ASSERT_FALSE(syntax);
  EXPECT_THAT(syntax.error().message, HasSubstr(broken + ":"));
  EXPECT_THAT(syntax.error().message, HasSubstr("YAML syntax error"));

  const std::vector<std::string> with_missing{defaults, (dir_ / "missing.yaml").string()};
  Result<SimConfig> missing = load_files(with_missing, sim_fields());
  ASSERT_FALSE(missing);
  EXPECT_THAT(missing.error().message, HasSubstr("cannot read config file"));
}

TEST_F(ConfigFileTest, OnlyTheLowestLayerMustBeComplete) {
  // A file with one key is a fine layer, and not a complete config by itself.
  const std::string one_key = write("one.yaml", "port: 10400\n");
  Result<SimConfig> alone = load_file(one_key, sim_fields());
  ASSERT_FALSE(alone);
  EXPECT_THAT(alone.error().message, HasSubstr(one_key + ": missing required key 'robots_per_team'"));
}

// ---------------------------------------------------------------------------------------------------------
// to_yaml, describe

TEST(ConfigToYamlTest, RoundTripGivesAnEqualStruct) {
  Result<SimConfig> loaded = load_string(kValidYaml, sim_fields());
  ASSERT_TRUE(loaded) << loaded.error().message;
  const std::string yaml = to_yaml(*loaded, sim_fields());
  Result<SimConfig> reloaded = load_string(yaml, sim_fields(), "<to_yaml>");
  ASSERT_TRUE(reloaded) << reloaded.error().message << "\n" << yaml;
  EXPECT_EQ(*reloaded, *loaded) << yaml;
}

TEST(ConfigToYamlTest, RoundTripKeepsExactDoublesAndAwkwardStrings) {
  SimConfig config;
  config.physics = {0.1 + 0.2 - 0.29, 1.0 / 3.0};  // 0.010000000000000009 and 0.333...
  config.robots_per_team = 2;
  config.division = Division::kA;
  config.team = "yellow";
  config.gains = {1e-9, 9.999999999999998};
  config.port = 65535;
  config.robots = {{3, "true"}, {4, "a: b # not a comment"}};
  config.tags = {"", "null", "5", "'quoted'", "line\nbreak"};
  const std::string yaml = to_yaml(config, sim_fields());
  Result<SimConfig> reloaded = load_string(yaml, sim_fields(), "<to_yaml>");
  ASSERT_TRUE(reloaded) << reloaded.error().message << "\n" << yaml;
  EXPECT_EQ(*reloaded, config) << yaml;
}

TEST(ConfigToYamlTest, PrintsSchemaOrderWithUnitsAndDocsAsComments) {
  Result<SimConfig> loaded = load_string(kValidYaml, sim_fields());
  ASSERT_TRUE(loaded) << loaded.error().message;
  const std::string yaml = to_yaml(*loaded, sim_fields());
  EXPECT_THAT(yaml, HasSubstr("physics:\n  ball_radius: 0.0215  # [m] ball radius\n  friction: 0.3\n"));
  EXPECT_THAT(yaml, HasSubstr("division: b\n"));
  EXPECT_THAT(yaml, HasSubstr("team: \"blue\"\n"));
  EXPECT_THAT(yaml, HasSubstr("gains: [1.5, 2]\n"));
  EXPECT_THAT(yaml, HasSubstr("realism: true  # add vision noise\n"));
  EXPECT_THAT(yaml, HasSubstr("robots:\n  - id: 0  # robot id on its shirt\n    name: \"keeper\"\n"));
  EXPECT_LT(yaml.find("physics:"), yaml.find("robots_per_team:"));
}

TEST(ConfigDescribeTest, ListsEveryKeyWithTypeLimitsAndDefaults) {
  const std::string text = describe(sim_fields());
  EXPECT_THAT(text,
              HasSubstr("physics.ball_radius: number in [0.01, 0.05], unit m, required: ball radius\n"));
  EXPECT_THAT(text, HasSubstr("physics.friction: number in [0, 1], default 0.3\n"));
  EXPECT_THAT(text, HasSubstr("division: one of a, b, required\n"));
  EXPECT_THAT(text, HasSubstr("team: string (one of blue, yellow), required\n"));
  EXPECT_THAT(text, HasSubstr("gains: list of number in [0, 10], 1 to 3 elements, default [1, 2]\n"));
  EXPECT_THAT(text, HasSubstr("robots: list of map, default []\n"));
  EXPECT_THAT(text, HasSubstr("robots[].id: integer in [0, 15], required: robot id on its shirt\n"));
}

// ---------------------------------------------------------------------------------------------------------
// Overrides

TEST(ConfigOverrideTest, OverridesReplaceValuesWithTheSameValidation) {
  const std::vector<std::string> overrides = {"physics.ball_radius=0.03", "robots[1].id=5", "gains=[3, 4]",
                                              "team=yellow", "physics.friction=0.5"};
  Result<SimConfig> loaded = load_string(kValidYaml, sim_fields(), "sim.yaml", overrides);
  ASSERT_TRUE(loaded) << loaded.error().message;
  EXPECT_EQ(loaded->physics.ball_radius_m, 0.03);
  EXPECT_EQ(loaded->physics.friction, 0.5);
  EXPECT_EQ(loaded->robots[1].id, 5);
  EXPECT_EQ(loaded->gains, (std::vector<double>{3.0, 4.0}));
  EXPECT_EQ(loaded->team, "yellow");
}

TEST(ConfigOverrideTest, OverrideCanSupplyAMissingKey) {
  const std::vector<std::string> overrides = {"robots_per_team=3"};
  Result<SimConfig> loaded =
      load_string(valid_yaml_with("robots_per_team: 11\n", ""), sim_fields(), "sim.yaml", overrides);
  ASSERT_TRUE(loaded) << loaded.error().message;
  EXPECT_EQ(loaded->robots_per_team, 3);
}

TEST(ConfigOverrideTest, InvalidOverrideValuesNameTheOverride) {
  const std::vector<std::string> out_of_range = {"physics.ball_radius=0.5"};
  EXPECT_EQ(
      load_error(kValidYaml, out_of_range),
      "deploy/config/sim.yaml (override 'physics.ball_radius=0.5'): key 'physics.ball_radius': 0.5 is out of "
      "range [0.01, 0.05] (m)");
  const std::vector<std::string> typo = {"physics.bal_radius=0.02"};
  EXPECT_EQ(load_error(kValidYaml, typo),
            "deploy/config/sim.yaml (override 'physics.bal_radius=0.02'): unknown key 'physics.bal_radius' "
            "(did you "
            "mean 'ball_radius'?)");
  const std::vector<std::string> new_branch = {"phisics.ball_radius=0.02"};
  EXPECT_THAT(
      load_error(kValidYaml, new_branch),
      HasSubstr("(override 'phisics.ball_radius=0.02'): unknown key 'phisics' (did you mean 'physics'?)"));
  const std::vector<std::string> wrong_type = {"robots_per_team=many"};
  EXPECT_EQ(
      load_error(kValidYaml, wrong_type),
      "deploy/config/sim.yaml (override 'robots_per_team=many'): key 'robots_per_team': expected an integer, "
      "got 'many'");
  const std::vector<std::string> empty = {"team="};
  EXPECT_EQ(load_error(kValidYaml, empty),
            "deploy/config/sim.yaml (override 'team='): key 'team': has no value");
}

TEST(ConfigOverrideTest, MalformedOverridesAreRejected) {
  const std::vector<std::string> no_equals = {"physics.ball_radius"};
  EXPECT_EQ(load_error(kValidYaml, no_equals),
            "deploy/config/sim.yaml (override 'physics.ball_radius'): expected key.path=value");
  for (const char* bad_path : {"=1", "a..b=1", "a.=1", "a[x]=1", "a[1=1", ".a=1"}) {
    const std::vector<std::string> overrides = {bad_path};
    EXPECT_THAT(load_error(kValidYaml, overrides), HasSubstr("bad key path")) << bad_path;
  }
  const std::vector<std::string> index = {"robots[5].id=1"};
  EXPECT_EQ(
      load_error(kValidYaml, index),
      "deploy/config/sim.yaml (override 'robots[5].id=1'): index 5 is out of range: 'robots' has 2 elements");
  const std::vector<std::string> not_a_map = {"team.color=red"};
  EXPECT_EQ(load_error(kValidYaml, not_a_map),
            "deploy/config/sim.yaml (override 'team.color=red'): 'team' is the string \"blue\", not a map");
  const std::vector<std::string> bad_yaml = {"gains=[1, 2"};
  EXPECT_THAT(load_error(kValidYaml, bad_yaml),
              HasSubstr("deploy/config/sim.yaml (override 'gains=[1, 2'): YAML syntax error"));
}

// ---------------------------------------------------------------------------------------------------------
// More member types and schema mistakes

struct Numbers {
  float gain = 0;
  std::int64_t big = 0;
  std::uint8_t small = 0;
  std::vector<int> ids;
  bool operator==(const Numbers&) const = default;
};

Fields<Numbers> number_fields() {
  return {
      field("gain", &Numbers::gain).min(0.0F),
      field("big", &Numbers::big),
      field("small", &Numbers::small).max(200),
      optional_field("ids", &Numbers::ids, {1, 2}).range(0, 15),
  };
}

TEST(ConfigTypesTest, FloatInt64AndUint8Members) {
  Result<Numbers> loaded =
      load_string("gain: 0.5\nbig: -9000000000000\nsmall: 200\nids: []\n", number_fields());
  ASSERT_TRUE(loaded) << loaded.error().message;
  EXPECT_EQ(*loaded, (Numbers{0.5F, -9'000'000'000'000, 200, {}}));
  EXPECT_EQ(*load_string(to_yaml(*loaded, number_fields()), number_fields()), *loaded);

  Result<Numbers> too_small = load_string("gain: -1\nbig: 1\nsmall: 201\n", number_fields(), "n.yaml");
  ASSERT_FALSE(too_small);
  EXPECT_EQ(too_small.error().message,
            "n.yaml:1: key 'gain': -1 is below the minimum 0\n"
            "n.yaml:3: key 'small': 201 is above the maximum 200");
  Result<Numbers> too_big = load_string("gain: 1e300\nbig: 1\nsmall: 256\n", number_fields(), "n.yaml");
  ASSERT_FALSE(too_big);
  EXPECT_EQ(too_big.error().message,
            "n.yaml:1: key 'gain': 1e300 does not fit this field's type\n"
            "n.yaml:3: key 'small': 256 does not fit this field's type [0, 255]");
}

struct Bad {
  int a = 0;
  Division division = Division::kA;
};

TEST(ConfigSchemaTest, SchemaMistakesAreReportedBeforeTheFileIsRead) {
  const Fields<Bad> duplicate = {field("a", &Bad::a), field("a", &Bad::a)};
  Result<Bad> loaded = load_string("a: 1\n", duplicate, "bad.yaml");
  ASSERT_FALSE(loaded);
  EXPECT_EQ(loaded.error().message, "bad.yaml: config schema error: key 'a' is declared twice");

  const Fields<Bad> no_names = {field("division", &Bad::division)};
  Result<Bad> enum_without_values = load_string("division: a\n", no_names, "bad.yaml");
  ASSERT_FALSE(enum_without_values);
  EXPECT_THAT(enum_without_values.error().message,
              HasSubstr("config schema error: key 'division': enum field needs .values("));

  const Fields<Bad> bad_default = {optional_field("a", &Bad::a, 20).range(0, 10)};
  Result<Bad> with_bad_default = load_string("{}", bad_default, "bad.yaml");
  ASSERT_FALSE(with_bad_default);
  EXPECT_EQ(with_bad_default.error().message,
            "bad.yaml: config schema error: key 'a': default: 20 is out of range [0, 10]");

  const Fields<Bad> dotted = {field("a.b", &Bad::a)};
  EXPECT_THAT(load_string("{}", dotted).error().message, HasSubstr("must be non-empty without ."));
}

TEST(ConfigLoadTest, ErrorsAreCappedSoAHugeBadFileStaysReadable) {
  std::string yaml;
  for (int i = 0; i < 30; ++i) yaml += "unknown_" + std::to_string(i) + ": 1\n";
  const Fields<Bad> fields = {optional_field("a", &Bad::a, 0)};
  Result<Bad> loaded = load_string(yaml, fields, "big.yaml");
  ASSERT_FALSE(loaded);
  EXPECT_THAT(loaded.error().message, HasSubstr("\n... and 10 more errors"));
  EXPECT_THAT(loaded.error().message, Not(HasSubstr("unknown_29")));
}

}  // namespace
}  // namespace ssl::config
