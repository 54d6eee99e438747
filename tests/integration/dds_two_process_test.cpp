// DDS between separate processes, through the real sslctl tool: a writer process (`sslctl topic pub`) and
// a reader process (`sslctl topic echo`) on a private domain id. Shows delivery, keep-last per key for a
// late joiner, transient-local referee state for a late joiner, and that a writer stopped with SIGTERM
// removes every shared-memory segment it had mapped.
#include <gtest/gtest.h>
#include <signal.h>

#include <filesystem>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <set>

#include "tests/support/process.h"

namespace ssl::testing {
namespace {

using std::chrono::seconds;
constexpr auto kTimeout = seconds(20);

ChildProcess sslctl(const std::vector<std::string>& args) {
  auto child = ChildProcess::start(bin_dir() / "sslctl", args);
  EXPECT_TRUE(child) << child.error().message;
  return std::move(child).value();
}

/// Reads `count` JSON lines from a child, failing the test with its stderr when they do not come.
std::vector<nlohmann::json> read_json_lines(ChildProcess& child, std::size_t count) {
  std::vector<nlohmann::json> lines;
  while (lines.size() < count) {
    auto line = child.read_line(kTimeout);
    if (!line) {
      ADD_FAILURE() << "expected " << count << " lines, got " << lines.size() << "; stderr: " << child.drain_stderr();
      break;
    }
    lines.push_back(nlohmann::json::parse(*line));
  }
  return lines;
}

/// Shared-memory files a process has mapped (Fast DDS segments), from /proc/<pid>/maps.
std::set<std::string> mapped_shm_files(pid_t pid) {
  std::ifstream maps("/proc/" + std::to_string(pid) + "/maps");
  std::set<std::string> files;
  std::string line;
  while (std::getline(maps, line)) {
    if (auto at = line.find("/dev/shm/"); at != std::string::npos) files.insert(line.substr(at));
  }
  return files;
}

TEST(DdsTwoProcessTest, ReaderProcessReceivesEverySampleOfAWriterProcess) {
  auto reader = sslctl({"topic", "echo", "referee.event", "--domain", "150", "--count", "3", "--timeout", "30"});
  auto writer = sslctl({"topic", "pub", "referee.event", "--domain", "150", "--wait-readers", "1", "--wait-timeout",
                        "30", R"({"command_counter": 1, "event": {"type": "GAME_EVENT_GOAL", "by_team": "TEAM_COLOR_BLUE"}})",
                        R"({"command_counter": 2, "event": {"type": "GAME_EVENT_BOT_TOO_FAST_IN_STOP", "value": 2.25}})",
                        R"({"command_counter": 3, "event": {"type": "GAME_EVENT_PLACEMENT_SUCCEEDED"}})"});
  const auto lines = read_json_lines(reader, 3);
  ASSERT_EQ(lines.size(), 3u);
  EXPECT_EQ(lines[0]["command_counter"], 1);
  EXPECT_EQ(lines[0]["event"]["type"], "GAME_EVENT_GOAL");
  EXPECT_EQ(lines[0]["event"]["by_team"], "TEAM_COLOR_BLUE");
  EXPECT_EQ(lines[1]["event"]["type"], "GAME_EVENT_BOT_TOO_FAST_IN_STOP");
  EXPECT_DOUBLE_EQ(lines[1]["event"]["value"].get<double>(), 2.25);
  EXPECT_EQ(lines[2]["command_counter"], 3);
  EXPECT_EQ(reader.wait(kTimeout), 0);
  EXPECT_EQ(writer.wait(kTimeout), 0) << writer.drain_stderr();
}

TEST(DdsTwoProcessTest, LateJoinerGetsOnlyTheNewestSamplePerKey) {
  auto writer = sslctl({"topic", "pub", "system.params", "--domain", "151", "--linger", "-1",
                        R"({"target": "planner/blue", "revision": 1})", R"({"target": "planner/blue", "revision": 2})",
                        R"({"target": "world_model/blue", "revision": 1})", R"({"target": "planner/blue", "revision": 3})",
                        R"({"target": "world_model/blue", "revision": 2})"});
  ASSERT_EQ(writer.read_line(kTimeout), "published 5") << writer.drain_stderr();

  // Asks for three samples but only two instances exist: the reader times out after printing two.
  auto reader = sslctl({"topic", "echo", "system.params", "--domain", "151", "--count", "3", "--timeout", "8"});
  const auto lines = read_json_lines(reader, 2);
  ASSERT_EQ(lines.size(), 2u);
  std::map<std::string, int> revisions;
  for (const auto& line : lines) revisions[line["target"]] = line["revision"];
  EXPECT_EQ(revisions["planner/blue"], 3);
  EXPECT_EQ(revisions["world_model/blue"], 2);
  EXPECT_EQ(reader.wait(kTimeout), 1);  // the timeout: no third sample exists
  EXPECT_EQ(reader.read_line(std::chrono::milliseconds(10)), std::nullopt);

  writer.signal(SIGTERM);
  EXPECT_EQ(writer.wait(kTimeout), 0);
}

TEST(DdsTwoProcessTest, LateJoinerReceivesTheLastRefereeState) {
  auto writer = sslctl({"topic", "pub", "referee.state", "--domain", "152", "--linger", "-1",
                        R"({"command": "COMMAND_HALT", "command_counter": 1})",
                        R"({"command": "COMMAND_STOP", "command_counter": 2})",
                        R"({"command": "COMMAND_FORCE_START", "command_counter": 3, "status_message": "go"})"});
  ASSERT_EQ(writer.read_line(kTimeout), "published 3") << writer.drain_stderr();

  auto reader = sslctl({"topic", "echo", "referee.state", "--domain", "152", "--count", "1", "--timeout", "30"});
  const auto lines = read_json_lines(reader, 1);
  ASSERT_EQ(lines.size(), 1u);
  EXPECT_EQ(lines[0]["command"], "COMMAND_FORCE_START");
  EXPECT_EQ(lines[0]["command_counter"], 3);
  EXPECT_EQ(lines[0]["status_message"], "go");
  EXPECT_EQ(reader.wait(kTimeout), 0);
  writer.signal(SIGTERM);
  EXPECT_EQ(writer.wait(kTimeout), 0);
}

TEST(DdsTwoProcessTest, AServiceMapsNoSharedMemorySegments) {
  // Services talk UDP only (libs/dds/participant.cpp: Fast DDS's shared memory leaves a process restarted
  // after SIGKILL deaf), so a killed one leaves nothing in /dev/shm either.
  auto started = ChildProcess::start(bin_dir() / "vision_gateway", {"--domain", "153", "--vision-port", "22153"});
  ASSERT_TRUE(started) << started.error().message;
  ChildProcess& service = *started;
  std::optional<std::string> line;
  while ((line = service.read_line(kTimeout)) && line->find("listening for vision") == std::string::npos) {}
  ASSERT_TRUE(line) << service.drain_stderr();
  const auto segments = mapped_shm_files(service.pid());
  EXPECT_TRUE(segments.empty()) << "the service maps " << *segments.begin();
  service.signal(SIGTERM);
  EXPECT_EQ(service.wait(kTimeout), 0) << service.drain_stderr();
}

TEST(DdsTwoProcessTest, HzReportsTheRateOfAWriterProcess) {
  auto hz = sslctl({"topic", "hz", "robot.feedback", "--team", "yellow", "--domain", "155", "--window", "1",
                    "--duration", "30"});
  auto writer = sslctl({"topic", "pub", "robot.feedback", "--team", "yellow", "--domain", "155", "--wait-readers",
                        "1", "--wait-timeout", "30", "--repeat", "400", "--rate", "100", R"({"robot_id": 4})"});
  // Reports start with "no rate" until samples flow; wait for a measured one.
  std::optional<std::string> report;
  while ((report = hz.read_line(kTimeout)) && report->find(" Hz") == std::string::npos) {}
  ASSERT_TRUE(report) << hz.drain_stderr();
  ASSERT_EQ(report->rfind("robot.feedback: ", 0), 0u) << *report;
  const double rate = std::stod(report->substr(std::string("robot.feedback: ").size()));
  // A rate is reported, in the right range; this is not a performance check (wide bounds on purpose).
  EXPECT_GT(rate, 20.0) << *report;
  EXPECT_LT(rate, 500.0) << *report;
  hz.signal(SIGINT);
  EXPECT_EQ(hz.wait(kTimeout), 0);
  writer.signal(SIGTERM);
  EXPECT_EQ(writer.wait(kTimeout), 0);
}

TEST(DdsTwoProcessTest, UnknownTopicAndMalformedSampleGiveClearErrors) {
  auto unknown = sslctl({"topic", "echo", "no.such.topic", "--domain", "154"});
  EXPECT_EQ(unknown.wait(kTimeout), 2);
  EXPECT_NE(unknown.drain_stderr().find("unknown topic 'no.such.topic'"), std::string::npos);

  auto malformed = sslctl({"topic", "pub", "referee.state", "--domain", "154", R"({"command": "COMMAND_DANCE"})"});
  EXPECT_EQ(malformed.wait(kTimeout), 2);
  EXPECT_NE(malformed.drain_stderr().find("COMMAND_DANCE"), std::string::npos);

  auto wrong_field = sslctl({"topic", "pub", "system.estop", "--domain", "154", R"({"engagd": true})"});
  EXPECT_EQ(wrong_field.wait(kTimeout), 2);
  EXPECT_NE(wrong_field.drain_stderr().find("unknown field 'engagd'"), std::string::npos);
}

}  // namespace
}  // namespace ssl::testing
