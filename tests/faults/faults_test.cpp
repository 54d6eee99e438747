// Faults: a match started as a user starts it (`./ssl up --robots 6`, on a private DDS domain, private ports
// and a private run directory).
//  * Every service killed in turn with SIGKILL. Each time ./ssl up's supervisor starts the service again: a
//    new process reports HEALTH_OK on system.health within 3 s of the kill (the figure printed); both
//    teams' robots move again within 15 s (world.state of each team: its own robots; a restart may fall
//    into a stoppage); the built-in referee resumes its match (its command counter goes on from where it
//    stood, in the first half).
//  * A team's planner, then its robot_link, hangs (SIGSTOP) for about 4 s: its robots stand still (vision:
//    none moves more than 0.1 m over 3 s, from 1 s after the hang on: the link's watchdog, then the
//    simulator's command timeout, braking included), and they move again once it runs on (SIGCONT): the
//    hang outlasted the DDS lease, so the process exits at its next health report and is started again
//    (dds::HealthReporter::exit_when_stalled).
//  * Garbage (random datagrams, 1-1400 bytes, seeded) for 10 s: 10 kHz on each league port of the match
//    (vision, referee, the simulator's control, blue, yellow and grSim ports) and 10 kHz spread over every
//    other UDP port its processes bound (DDS, robot_link's simulator socket). Every service lives on (same
//    process), is HEALTH_OK within 5 s after, the gateways and the simulator count what they dropped, and
//    both teams still move.
#include <arpa/inet.h>
#include <netinet/in.h>
#include <signal.h>
#include <sys/socket.h>
#include <sys/types.h>
#include <unistd.h>

#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <limits>
#include <map>
#include <nlohmann/json.hpp>
#include <optional>
#include <random>
#include <set>
#include <thread>
#include <string>
#include <vector>

#include "tests/support/netns.h"
#include "tests/support/process.h"

namespace ssl {
namespace {

namespace fs = std::filesystem;
using namespace std::chrono_literals;
using Clock = std::chrono::steady_clock;
using testing::ChildProcess;

constexpr int kDomain = 210;
constexpr int kVisionPort = 23220;  // the simulator's control, team and grSim ports are the four above it
constexpr int kRefereePort = 23230;
constexpr int kHttpPort = 23240;
constexpr auto kBackWithin = 3s;
constexpr auto kMovesWithin = 15s;
constexpr auto kStoppedWithin = 1s;     // after a hang: the watchdog's 0.1-0.2 s, then braking
constexpr auto kStandingWindow = 3s;   // with kStoppedWithin longer than the DDS lease (3 s)
constexpr double kStandingDisplacement = 0.10;  // m over kStandingWindow: vision noise, a push

/// A service of the match: its name in the run directory (NAME.service.pid) and on system.health.
struct Service {
  std::string name;
  std::string health;
};

std::vector<Service> services() {
  return {{"world_model-blue", "world_model/blue"}, {"planner-blue", "planner/blue"},
          {"robot_link-blue", "robot_link/blue"},   {"world_model-yellow", "world_model/yellow"},
          {"planner-yellow", "planner/yellow"},     {"robot_link-yellow", "robot_link/yellow"},
          {"vision_gateway", "vision_gateway"},     {"simulator", "simulator"},
          {"console", "console/" + std::to_string(kHttpPort)},
          {"referee_gateway", "referee_gateway"}};
}

/// `./ssl up` on the private domain, ports and run directory; `./ssl down` at the end.
class Match {
 public:
  Match() : run_dir_(fs::temp_directory_path() / ("ssl_faults_" + std::to_string(::getpid()))) {
    fs::create_directories(run_dir_);
    const auto up = testing::shell(ssl("up --no-build --robots 6 --domain " + std::to_string(kDomain) +
                                       " --vision-port " + std::to_string(kVisionPort) + " --referee-port " +
                                       std::to_string(kRefereePort) + " --http-port " + std::to_string(kHttpPort)));
    started_ = up.status == 0;
    if (!started_) std::fprintf(stderr, "./ssl up failed:\n%s\n", up.output.c_str());
  }
  ~Match() {
    testing::shell(ssl("down --domain " + std::to_string(kDomain)));
    std::error_code ignored;
    fs::remove_all(run_dir_, ignored);
  }
  bool started() const { return started_; }

  /// The pid ./ssl up's supervisor wrote for the service's current process.
  std::optional<pid_t> pid_of(const std::string& name) const {
    std::ifstream in(run_dir_ / "ssl-stack" / ("domain-" + std::to_string(kDomain)) / (name + ".service.pid"));
    pid_t pid = 0;
    if (!(in >> pid)) return std::nullopt;
    return pid;
  }
  std::string log_of(const std::string& name) const {
    std::ifstream in(run_dir_ / "ssl-stack" / ("domain-" + std::to_string(kDomain)) / (name + ".log"));
    return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
  }

 private:
  std::string ssl(const std::string& arguments) const {
    return "XDG_RUNTIME_DIR=" + run_dir_.string() + " SSL_BUILD_DIR=" + testing::bin_dir().parent_path().string() +
           " " + std::string(SSL_SOURCE_DIR) + "/ssl " + arguments + " 2>&1";
  }

  fs::path run_dir_;
  bool started_ = false;
};

/// system.health as `sslctl topic echo` prints it: the last report of every service.
class HealthWatch {
 public:
  HealthWatch()
      : echo_(ChildProcess::start(testing::bin_dir() / "sslctl",
                                  {"topic", "echo", "system.health", "--domain", std::to_string(kDomain)})) {}

  struct Report {
    pid_t pid = 0;
    std::string level;
    std::uint64_t dropped = 0;
    std::int64_t stamp_unix_ns = 0;
  };

  /// Reads reports until `done(reports)` holds or `timeout` passes; whether it held.
  template <typename Done>
  bool until(Done done, std::chrono::milliseconds timeout) {
    const auto deadline = Clock::now() + timeout;
    while (!done(reports_)) {
      const auto left = std::chrono::duration_cast<std::chrono::milliseconds>(deadline - Clock::now());
      if (left <= 0ms || !echo_) return false;
      const std::optional<std::string> line = echo_->read_line(left);
      if (!line) continue;
      const nlohmann::json report = nlohmann::json::parse(*line, nullptr, false);
      if (report.is_discarded() || !report.contains("service")) continue;
      reports_[report["service"].get<std::string>()] = {report.value("pid", 0), report.value("level", ""),
                                                        report.value("dropped", std::uint64_t{0}),
                                                        report.value("stamp_unix_ns", std::int64_t{0})};
    }
    return true;
  }
  bool ok(const std::string& service, pid_t pid) const {
    const auto found = reports_.find(service);
    return found != reports_.end() && found->second.pid == pid && found->second.level == "HEALTH_OK";
  }
  std::optional<Report> last(const std::string& service) const {
    const auto found = reports_.find(service);
    if (found == reports_.end()) return std::nullopt;
    return found->second;
  }

 private:
  Result<ChildProcess> echo_;
  std::map<std::string, Report> reports_;
};

/// The first referee.state sample heard: its command counter and stage.
std::optional<std::pair<std::uint32_t, std::string>> referee_state() {
  auto echo = ChildProcess::start(testing::bin_dir() / "sslctl", {"topic", "echo", "referee.state", "--count", "1",
                                                                  "--domain", std::to_string(kDomain)});
  if (!echo) return std::nullopt;
  const auto line = echo->read_line(10s);
  if (!line) return std::nullopt;
  const nlohmann::json state = nlohmann::json::parse(*line, nullptr, false);
  if (state.is_discarded()) return std::nullopt;
  return std::pair{state.value("command_counter", 0u), state.value("stage", std::string())};
}

/// Whether some robot of `team` moved more than 5 cm over `window`, as its own world.state shows it.
bool team_moves(const std::string& team, std::chrono::milliseconds window) {
  auto echo = ChildProcess::start(testing::bin_dir() / "sslctl",
                                  {"topic", "echo", "world.state", "--team", team, "--domain", std::to_string(kDomain)});
  if (!echo) return false;
  std::map<int, std::pair<double, double>> first;
  const auto deadline = Clock::now() + window;
  while (Clock::now() < deadline) {
    const auto line = echo->read_line(std::chrono::duration_cast<std::chrono::milliseconds>(deadline - Clock::now()));
    if (!line) continue;
    const nlohmann::json world = nlohmann::json::parse(*line, nullptr, false);
    if (world.is_discarded() || !world.contains("friendly")) continue;
    for (const auto& robot : world["friendly"]) {
      const int id = robot.value("id", -1);
      const double x = robot["pose"].value("x", 0.0), y = robot["pose"].value("y", 0.0);
      const auto [at, inserted] = first.try_emplace(id, x, y);
      if (!inserted && std::hypot(x - at->second.first, y - at->second.second) > 0.05) return true;
    }
  }
  return false;
}

/// The largest distance a robot of `team` moved in vision.detection (global frame; per camera, as cameras
/// overlap) over `window`, counted from frames captured at or after `from` (Unix wall clock).
double largest_robot_displacement(const std::string& team, std::chrono::system_clock::time_point from,
                                  std::chrono::milliseconds window) {
  auto echo = ChildProcess::start(testing::bin_dir() / "sslctl",
                                  {"topic", "echo", "vision.detection", "--domain", std::to_string(kDomain)});
  if (!echo) return std::numeric_limits<double>::infinity();
  const std::int64_t from_ns =
      std::chrono::duration_cast<std::chrono::nanoseconds>(from.time_since_epoch()).count();
  const std::int64_t until_ns = from_ns + std::chrono::duration_cast<std::chrono::nanoseconds>(window).count();
  std::map<std::pair<int, int>, std::pair<double, double>> first;  // (camera, id) -> position
  double largest = 0;
  bool window_over = false;
  const auto deadline = Clock::now() + window + 5s;
  while (!window_over && Clock::now() < deadline) {
    const auto line = echo->read_line(std::chrono::duration_cast<std::chrono::milliseconds>(deadline - Clock::now()));
    if (!line) continue;
    const nlohmann::json frame = nlohmann::json::parse(*line, nullptr, false);
    if (frame.is_discarded() || !frame.contains("robots_" + team)) continue;
    const std::int64_t captured = frame.value("capture_unix_ns", std::int64_t{0});
    if (captured < from_ns) continue;
    if (captured > until_ns) {
      window_over = true;
      continue;
    }
    for (const auto& robot : frame["robots_" + team]) {
      const std::pair<int, int> key{frame.value("camera_id", -1), robot.value("robot_id", -1)};
      const double x = robot.value("x", 0.0), y = robot.value("y", 0.0);
      const auto [at, inserted] = first.try_emplace(key, x, y);
      largest = std::max(largest, std::hypot(x - at->second.first, y - at->second.second));
    }
  }
  if (!window_over || first.empty()) return std::numeric_limits<double>::infinity();  // no vision: not shown
  return largest;
}

/// Sends random datagrams (1-1400 bytes, from `seed`) to 127.0.0.1: each of `full_rate_ports` at
/// `rate_hz`, and `rate_hz` spread over `shared_ports`, for `duration`. Returns the datagrams sent.
std::uint64_t flood(const std::set<int>& full_rate_ports, const std::set<int>& shared_ports, double rate_hz,
                    std::chrono::milliseconds duration, std::uint32_t seed) {
  const int fd = ::socket(AF_INET, SOCK_DGRAM, 0);
  if (fd < 0) return 0;
  std::mt19937 random(seed);
  std::uniform_int_distribution<int> size_of(1, 1400);
  std::uniform_int_distribution<int> byte(0, 255);
  std::vector<std::uint8_t> datagram(1400);
  const auto send_to = [&](int port) {
    for (auto& b : datagram) b = static_cast<std::uint8_t>(byte(random));
    sockaddr_in to{};
    to.sin_family = AF_INET;
    to.sin_port = htons(static_cast<std::uint16_t>(port));
    to.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
    // Loss (a full receive buffer, ECONNREFUSED from an earlier datagram) is part of a flood.
    (void)::sendto(fd, datagram.data(), static_cast<std::size_t>(size_of(random)), MSG_DONTWAIT,
                   reinterpret_cast<const sockaddr*>(&to), sizeof to);
  };
  const std::vector<int> shared(shared_ports.begin(), shared_ports.end());
  std::uint64_t sent = 0, shared_next = 0;
  const auto start = Clock::now();
  for (auto tick = start; tick < start + duration; tick += 1ms) {
    std::this_thread::sleep_until(tick);  // pacing: rate_hz / 1000 datagrams per port each millisecond
    const auto batch = static_cast<int>(rate_hz / 1000);
    for (int i = 0; i < batch; ++i) {
      for (const int port : full_rate_ports) send_to(port), ++sent;
      if (!shared.empty()) send_to(shared[shared_next++ % shared.size()]), ++sent;
    }
  }
  ::close(fd);
  return sent;
}

/// Waits until every service of the match reported HEALTH_OK and both teams move.
void expect_match_running(Match& match, HealthWatch& health) {
  const std::vector<Service> all = services();
  ASSERT_TRUE(health.until(
      [&](const auto&) {
        for (const Service& service : all) {
          const std::optional<pid_t> pid = match.pid_of(service.name);
          if (!pid || !health.ok(service.health, *pid)) return false;
        }
        return true;
      },
      30s))
      << "not every service reported HEALTH_OK within 30 s of ./ssl up";
  ASSERT_TRUE(team_moves("blue", kMovesWithin) && team_moves("yellow", kMovesWithin)) << "the match does not run";
}

TEST(Faults, EveryServiceKilledDuringAMatchIsRestartedReportsHealthyAndTheMatchGoesOn) {
  Match match;
  ASSERT_TRUE(match.started());
  HealthWatch health;
  const std::vector<Service> all = services();
  ASSERT_NO_FATAL_FAILURE(expect_match_running(match, health));

  for (const Service& service : all) {
    const bool referee = service.name == "referee_gateway";
    const auto referee_before = referee ? referee_state() : std::nullopt;
    if (referee) ASSERT_TRUE(referee_before) << "no referee.state";
    const std::optional<pid_t> killed = match.pid_of(service.name);
    ASSERT_TRUE(killed) << service.name;
    const auto kill_time = Clock::now();
    ASSERT_EQ(::kill(*killed, SIGKILL), 0) << service.name;
    std::optional<pid_t> back;
    const bool healthy = health.until(
        [&](const auto&) {
          back = match.pid_of(service.name);
          return back && *back != *killed && health.ok(service.health, *back);
        },
        std::chrono::duration_cast<std::chrono::milliseconds>(kBackWithin));
    const double seconds = std::chrono::duration<double>(Clock::now() - kill_time).count();
    EXPECT_TRUE(healthy) << service.name << " not back and healthy " << seconds << " s after its SIGKILL\n"
                         << match.log_of(service.name);
    std::printf("[figures] %-20s back and healthy %.2f s after SIGKILL\n", service.name.c_str(), seconds);
    std::fflush(stdout);
    if (!healthy) continue;
    if (referee) {
      const auto after = referee_state();
      ASSERT_TRUE(after) << "no referee.state after the referee's restart";
      EXPECT_GT(after->first, referee_before->first) << "the restarted referee began a new match";
      EXPECT_EQ(after->second, referee_before->second) << "the restarted referee is in another stage";
    }
    EXPECT_TRUE(team_moves("blue", kMovesWithin)) << "blue stands after " << service.name << " came back";
    EXPECT_TRUE(team_moves("yellow", kMovesWithin)) << "yellow stands after " << service.name << " came back";
  }
}

TEST(Faults, ATeamWhosePlannerOrLinkHangsStandsStillAndMovesAgainOnceItRunsOn) {
  Match match;
  ASSERT_TRUE(match.started());
  HealthWatch health;
  ASSERT_NO_FATAL_FAILURE(expect_match_running(match, health));
  for (const std::string& name : {"planner-blue", "robot_link-blue", "planner-yellow", "robot_link-yellow"}) {
    const std::string team = name.substr(name.find('-') + 1);
    const std::optional<pid_t> pid = match.pid_of(name);
    ASSERT_TRUE(pid) << name;
    const auto hung = std::chrono::system_clock::now();
    ASSERT_EQ(::kill(*pid, SIGSTOP), 0) << name;
    const double displacement = largest_robot_displacement(team, hung + kStoppedWithin, kStandingWindow);
    ASSERT_EQ(::kill(*pid, SIGCONT), 0) << name;
    std::printf("[figures] %-18s hung: %s robots moved at most %.3f m over 3 s from 1 s after\n", name.c_str(),
                team.c_str(), displacement);
    std::fflush(stdout);
    EXPECT_LT(displacement, kStandingDisplacement) << team << "'s robots move while " << name << " hangs";
    EXPECT_TRUE(team_moves(team, kMovesWithin)) << team << " stands after " << name << " runs on";
  }
}

TEST(Faults, AGarbageFloodOnEveryUdpPortLeavesEveryServiceHealthyAndCounting) {
  Match match;
  ASSERT_TRUE(match.started());
  HealthWatch health;
  ASSERT_NO_FATAL_FAILURE(expect_match_running(match, health));
  const std::vector<Service> all = services();
  std::map<std::string, pid_t> pids;
  std::set<int> bound;
  for (const Service& service : all) {
    const std::optional<pid_t> pid = match.pid_of(service.name);
    ASSERT_TRUE(pid) << service.name;
    pids[service.name] = *pid;
    for (const int port : testing::bound_udp_ports(*pid)) bound.insert(port);
  }
  // The league's ports of this match: vision, referee, and the simulator's four above the vision port.
  const std::set<int> league{kVisionPort,     kRefereePort,    kVisionPort + 1,
                             kVisionPort + 2, kVisionPort + 3, kVisionPort + 4};
  std::set<int> others;
  for (const int port : bound) {
    if (!league.contains(port)) others.insert(port);
  }
  for (const int port : league) EXPECT_TRUE(bound.contains(port)) << "nothing listens on league port " << port;
  std::map<std::string, std::uint64_t> dropped_before;
  for (const char* counting : {"vision_gateway", "referee_gateway", "simulator"}) {
    dropped_before[counting] = health.last(counting)->dropped;
  }

  const std::uint64_t sent = flood(league, others, 10'000, 10s, 17);
  const std::int64_t flood_end_ns =
      std::chrono::duration_cast<std::chrono::nanoseconds>(std::chrono::system_clock::now().time_since_epoch()).count();
  std::printf("[figures] garbage: %llu datagrams in 10 s to %zu league ports (10 kHz each) and %zu other UDP ports "
              "(10 kHz together)\n",
              static_cast<unsigned long long>(sent), league.size(), others.size());

  const bool healthy = health.until(
      [&](const auto&) {
        for (const Service& service : all) {
          const auto report = health.last(service.health);
          if (!report || report->stamp_unix_ns < flood_end_ns || !health.ok(service.health, pids[service.name])) {
            return false;
          }
        }
        return true;
      },
      5s);
  for (const Service& service : all) {
    EXPECT_EQ(match.pid_of(service.name), pids[service.name])
        << service.name << " did not live through the flood\n" << match.log_of(service.name);
    const auto report = health.last(service.health);
    EXPECT_TRUE(report && report->level == "HEALTH_OK") << service.name << ": " << (report ? report->level : "no report");
  }
  EXPECT_TRUE(healthy) << "not every service reported HEALTH_OK within 5 s after the flood";
  for (const auto& [service, before] : dropped_before) {
    const std::uint64_t after = health.last(service)->dropped;
    std::printf("[figures] %-16s dropped %llu datagrams of the flood\n", service.c_str(),
                static_cast<unsigned long long>(after - before));
    EXPECT_GT(after, before + 1000) << service << " did not count the garbage it dropped";
  }
  EXPECT_TRUE(team_moves("blue", kMovesWithin)) << "blue stands after the flood";
  EXPECT_TRUE(team_moves("yellow", kMovesWithin)) << "yellow stands after the flood";
}

}  // namespace
}  // namespace ssl
