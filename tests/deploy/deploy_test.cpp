// Deployment as a team does it on a match PC, with the real parts: the services talk to a service manager
// over a NOTIFY_SOCKET of this test's own, `cmake --install` puts a match PC's tree under a prefix, every
// unit passes `systemd-analyze verify`, each unit's ExecStart runs exactly as written with its environment
// file, the Debian package declares its dependencies and installs, each site makes the same services bind
// what it says, and a discovery server connects participants that multicast would not. Each test uses its
// own DDS domain (211-223, apart from every other suite's); the tests that need root (network namespaces,
// installing) skip without it. The field site has DDS Security on: the suite makes its certificates (deploy/dds-certs.sh) and points every
// process at them ($SSL_CERTS_DIR).
#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <poll.h>
#include <sys/socket.h>
#include <sys/un.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <csignal>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <optional>
#include <regex>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "libs/common/deploy_files.h"
#include "libs/common/team.h"
#include "libs/dds/participant.h"
#include "libs/dds/topics.h"
#include "tests/support/netns.h"
#include "tests/support/process.h"

namespace ssl::testing {
namespace {

namespace fs = std::filesystem;
using namespace std::chrono_literals;
using ::testing::HasSubstr;
using ::testing::Not;


const std::vector<std::string> kExecutables{"simulator",   "vision_gateway", "referee_gateway", "world_model",
                                            "planner",     "robot_link",     "console",        "sslctl"};
/// The field site's DDS Security files, made once for the suite; children inherit $SSL_CERTS_DIR.
class FieldCertificates : public ::testing::Environment {
 public:
  static fs::path directory() { return fs::temp_directory_path() / ("ssl_deploy_certs_" + std::to_string(::getpid())); }

  void SetUp() override {
    auto script = find_deploy_file("dds-certs.sh");
    ASSERT_TRUE(script) << script.error().message;
    const ShellRun made = shell("'" + *script + "' --dir '" + directory().string() + "' --teams blue,yellow");
    ASSERT_EQ(made.status, 0) << made.output;
    ::setenv("SSL_CERTS_DIR", directory().c_str(), 1);
  }
  void TearDown() override { fs::remove_all(directory()); }
};
[[maybe_unused]] const auto* const kFieldCertificates = ::testing::AddGlobalTestEnvironment(new FieldCertificates);

const std::vector<std::string> kUnits{"ssl-latency.slice", "ssl-bulk.slice", "ssl-discovery.service", "ssl-simulator.service",
                                      "ssl-vision-gateway.service", "ssl-referee-gateway.service",
                                      "ssl-robot-link@.service",   "ssl-world-model@.service",
                                      "ssl-planner@.service",      "ssl-console.service",
                                      "ssl-field.target",          "ssl-team@.target",
                                      "ssl-coach.target"};

struct TempDir {
  TempDir() {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    path = fs::temp_directory_path() / ("ssl_deploy_" + std::string(info->name()) + "_" + std::to_string(::getpid()));
    fs::remove_all(path);
    fs::create_directories(path);
  }
  ~TempDir() { fs::remove_all(path); }
  fs::path path;
};

std::string read_text(const fs::path& path) {
  std::ifstream in(path);
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

void write_text(const fs::path& path, const std::string& text) {
  fs::create_directories(path.parent_path());
  std::ofstream(path) << text;
}

void install_to(const fs::path& prefix) {
  const Status installed = install_build(prefix);
  ASSERT_TRUE(installed) << installed.error().message;
}

// One unit file: the values of each "Key=" of its [Service] section (and the others), in order.
std::multimap<std::string, std::string> unit_keys(const fs::path& unit) {
  std::multimap<std::string, std::string> keys;
  std::ifstream in(unit);
  std::string line;
  while (std::getline(in, line)) {
    if (line.empty() || line[0] == '#' || line[0] == '[') continue;
    const std::size_t equals = line.find('=');
    if (equals != std::string::npos) keys.emplace(line.substr(0, equals), line.substr(equals + 1));
  }
  return keys;
}

std::string unit_value(const fs::path& unit, const std::string& key) {
  const auto keys = unit_keys(unit);
  const auto found = keys.find(key);
  return found == keys.end() ? std::string() : found->second;
}

// KEY=value lines of an environment file.
std::map<std::string, std::string> read_environment_file(const fs::path& path) {
  std::map<std::string, std::string> env;
  std::ifstream in(path);
  std::string line;
  while (std::getline(in, line)) {
    if (line.empty() || line[0] == '#') continue;
    const std::size_t equals = line.find('=');
    if (equals != std::string::npos) env[line.substr(0, equals)] = line.substr(equals + 1);
  }
  return env;
}

// An ExecStart= line as systemd runs it: %i is the instance, ${VAR} one argument, $VAR split on whitespace
// (nothing when empty).
std::vector<std::string> expand_exec_start(const std::string& line, const std::map<std::string, std::string>& env,
                                           const std::string& instance) {
  std::vector<std::string> argv;
  std::istringstream words(line);
  std::string word;
  while (words >> word) {
    word = std::regex_replace(word, std::regex("%i"), instance);
    std::smatch match;
    if (std::regex_match(word, match, std::regex(R"(\$([A-Za-z_][A-Za-z0-9_]*))"))) {
      const auto found = env.find(match[1]);
      std::istringstream split(found == env.end() ? "" : found->second);
      for (std::string part; split >> part;) argv.push_back(part);
      continue;
    }
    std::string expanded;
    std::size_t from = 0;
    const std::regex braced(R"(\$\{([A-Za-z_][A-Za-z0-9_]*)\})");
    for (std::sregex_iterator it(word.begin(), word.end(), braced), end; it != end; ++it) {
      expanded += word.substr(from, static_cast<std::size_t>(it->position()) - from);
      const auto found = env.find((*it)[1]);
      expanded += found == env.end() ? "" : found->second;
      from = static_cast<std::size_t>(it->position() + it->length());
    }
    expanded += word.substr(from);
    argv.push_back(expanded);
  }
  return argv;
}

// The service manager's end of NOTIFY_SOCKET: a datagram socket of this test. A socket's path has at most
// 107 bytes (sun_path): a longer one is refused, never cut short.
class NotifySocket {
 public:
  explicit NotifySocket(const fs::path& path) : path_(path) {
    fd_ = ::socket(AF_UNIX, SOCK_DGRAM | SOCK_CLOEXEC, 0);
    sockaddr_un address{};
    address.sun_family = AF_UNIX;
    if (path.string().size() >= sizeof address.sun_path) return;
    std::snprintf(address.sun_path, sizeof address.sun_path, "%s", path.c_str());
    bound_ = ::bind(fd_, reinterpret_cast<const sockaddr*>(&address), sizeof address) == 0;
  }
  ~NotifySocket() {
    ::close(fd_);
    fs::remove(path_);
  }
  bool bound() const { return bound_; }
  std::optional<std::string> receive(std::chrono::milliseconds timeout) {
    pollfd poll_fd{.fd = fd_, .events = POLLIN, .revents = 0};
    if (::poll(&poll_fd, 1, static_cast<int>(timeout.count())) <= 0) return std::nullopt;
    std::array<char, 4096> buffer{};
    const ssize_t n = ::recv(fd_, buffer.data(), buffer.size(), 0);
    if (n <= 0) return std::nullopt;
    return std::string(buffer.data(), static_cast<std::size_t>(n));
  }

 private:
  fs::path path_;
  int fd_ = -1;
  bool bound_ = false;
};

// `sslctl health --json` over `listen_s` seconds: the latest report of each service, by name.
std::map<std::string, nlohmann::json> health_reports(const std::vector<std::string>& prefix, int domain,
                                                     double listen_s, const std::string& site_dir = "") {
  std::vector<std::string> args = prefix;
  for (const std::string& arg : std::vector<std::string>{"health", "--json", "--listen", std::to_string(listen_s),
                                                          "--domain", std::to_string(domain)}) {
    args.push_back(arg);
  }
  if (!site_dir.empty()) {
    args.push_back("--site");
    args.push_back(site_dir);
  }
  std::map<std::string, nlohmann::json> reports;
  const fs::path program = prefix.empty() ? bin_dir() / "sslctl" : NetNamespace::ip();
  auto child = ChildProcess::start(program, args);
  if (!child) return reports;
  while (auto line = child->read_line(std::chrono::milliseconds(static_cast<int>(listen_s * 1000) + 10000))) {
    auto json = nlohmann::json::parse(*line, nullptr, false);
    if (json.is_object() && json.contains("service")) reports[json["service"].get<std::string>()] = json;
  }
  (void)child->wait(10s);
  return reports;
}

bool healthy(const nlohmann::json& report) {
  return report.contains("level") && report["level"].get<std::string>() != "ERROR";
}

// ---------------------------------------------------------------------------------------------------------
// The notification protocol, from each real service.

struct NotifyCase {
  std::string program;
  std::vector<std::string> args;  // private ports: the league's may be in use on this machine
  std::string input;              // the topic it waits to hear before READY ("" none); the test writes it

  /// The case's own DDS domain (its --domain): no other case's service may feed it.
  int domain() const {
    const auto flag = std::find(args.begin(), args.end(), "--domain");
    return flag != args.end() && std::next(flag) != args.end() ? std::stoi(*std::next(flag)) : 0;
  }
};

void PrintTo(const NotifyCase& c, std::ostream* os) { *os << c.program; }

class ServiceManagerTest : public ::testing::TestWithParam<NotifyCase> {};

TEST_P(ServiceManagerTest, AServiceSaysReadyOnceItHearsItsInputsThenFeedsTheWatchdogFromItsLoop) {
  const fs::path socket_path = fs::temp_directory_path() / ("ssl_notify_" + std::to_string(::getpid()));
  NotifySocket socket(socket_path);
  ASSERT_TRUE(socket.bound()) << socket_path;
  ::setenv("NOTIFY_SOCKET", socket_path.c_str(), 1);
  auto child = ChildProcess::start(bin_dir() / GetParam().program, GetParam().args);
  ::unsetenv("NOTIFY_SOCKET");
  ASSERT_TRUE(child) << child.error().message;

  auto first = socket.receive(20s);
  ASSERT_TRUE(first) << "no notification within 20 s; stderr:\n" << child->drain_stderr();
  EXPECT_THAT(*first, HasSubstr("STATUS="));
  std::shared_ptr<void> input_writer;  // the service's input, written from here once it waits for it
  std::optional<dds::Participant> participant;
  if (!GetParam().input.empty()) {
    EXPECT_THAT(*first, Not(HasSubstr("READY=1"))) << "READY before its input " << GetParam().input << " was heard";
    EXPECT_THAT(*first, HasSubstr("waiting for its inputs"));
    auto created = dds::Participant::create({.domain_id = GetParam().domain(), .name = "deploy_test/input"});
    ASSERT_TRUE(created) << created.error().message;
    participant.emplace(std::move(*created));
    ASSERT_TRUE(dds::visit_topic(GetParam().input, [&](const auto& spec) {
      auto writer = participant->make_writer(spec, spec.scope == dds::TopicScope::kTeam
                                                       ? std::optional<TeamColor>(TeamColor::kBlue)
                                                       : std::nullopt);
      ASSERT_TRUE(writer) << writer.error().message;
      input_writer = std::make_shared<std::decay_t<decltype(*writer)>>(std::move(*writer));
    }));
    std::optional<std::string> ready;
    while (!ready) {
      auto next = socket.receive(15s);
      ASSERT_TRUE(next) << "no READY after its input appeared";
      if (next->find("READY=1") != std::string::npos) ready = next;
    }
    EXPECT_THAT(*ready, Not(HasSubstr("without its inputs"))) << "READY by the grace period, not the match";
  } else {
    EXPECT_THAT(*first, HasSubstr("READY=1"));
  }
  int watchdogs = 0;
  while (watchdogs < 3) {
    auto next = socket.receive(5s);
    ASSERT_TRUE(next) << "the watchdog went silent after " << watchdogs << " pings";
    EXPECT_THAT(*next, Not(HasSubstr("READY=1"))) << "READY is said once";
    watchdogs += next->find("WATCHDOG=1") != std::string::npos ? 1 : 0;
  }
  child->signal(SIGTERM);
  EXPECT_EQ(child->wait(15s), 0) << child->drain_stderr();
}

INSTANTIATE_TEST_SUITE_P(
    EveryService, ServiceManagerTest,
    ::testing::Values(
        NotifyCase{"simulator", {"--domain", "211", "--robots", "2", "--vision-port", "22160", "--control-port",
                                 "22161", "--blue-port", "22162", "--yellow-port", "22163", "--grsim-port", "22164"}},
        NotifyCase{"vision_gateway", {"--domain", "212", "--vision-port", "22165"}},
        NotifyCase{"referee_gateway", {"--domain", "213", "--referee-port", "22166"}},
        NotifyCase{"world_model", {"--domain", "214", "--team", "blue"}, "vision.detection"},
        NotifyCase{"planner", {"--domain", "215", "--team", "blue"}, "world.state"},
        NotifyCase{"robot_link", {"--domain", "216", "--team", "blue", "--sim-port", "22167"}, "robot.commands"},
        NotifyCase{"console", {"--domain", "217", "--http-port", "22172"}}),
    [](const ::testing::TestParamInfo<NotifyCase>& param) { return param.param.program; });

TEST(ServiceManager, AServiceWhoseInputsNeverAppearIsUpAfterItsGraceAndSaysSo) {
  const fs::path socket_path = fs::temp_directory_path() / ("ssl_notify_" + std::to_string(::getpid()));
  NotifySocket socket(socket_path);
  ASSERT_TRUE(socket.bound()) << socket_path;
  ::setenv("NOTIFY_SOCKET", socket_path.c_str(), 1);
  // A planner alone on its domain: no world model will ever be heard.
  auto child = ChildProcess::start(bin_dir() / "planner", {"--domain", "218", "--team", "blue"});
  ::unsetenv("NOTIFY_SOCKET");
  ASSERT_TRUE(child) << child.error().message;
  const auto started = std::chrono::steady_clock::now();
  std::optional<std::string> ready;
  int waiting = 0;
  while (!ready) {
    auto next = socket.receive(15s);
    ASSERT_TRUE(next) << "no READY within the grace; stderr:\n" << child->drain_stderr();
    if (next->find("READY=1") != std::string::npos) {
      ready = next;
    } else {
      EXPECT_THAT(*next, HasSubstr("waiting for its inputs"));
      ++waiting;
    }
  }
  const double after_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
  EXPECT_THAT(*ready, HasSubstr("up without its inputs"));
  EXPECT_GE(waiting, 5) << "READY came before the 10 s grace, after " << after_s << " s";
  child->signal(SIGTERM);
  EXPECT_EQ(child->wait(15s), 0) << child->drain_stderr();
}

TEST(ServiceManager, WithoutANotifySocketTheServicesRunAsBefore) {
  // Every other process test of the project starts services without NOTIFY_SOCKET; this one says so and
  // checks a service starts and stops cleanly with it unset.
  ::unsetenv("NOTIFY_SOCKET");
  auto child = ChildProcess::start(bin_dir() / "vision_gateway", {"--domain", "219", "--vision-port", "22168"});
  ASSERT_TRUE(child) << child.error().message;
  const auto reports = health_reports({}, 219, 3);
  child->signal(SIGTERM);
  EXPECT_EQ(child->wait(15s), 0) << child->drain_stderr();
  EXPECT_TRUE(reports.contains("vision_gateway"));
}

TEST(ServiceManager, AnOperatorsSslctlReachesServicesRunningAsTheUnitsUser) {
  // The units run the services as their own user; an operator runs sslctl as another. Fast DDS's shared-
  // memory segments would be writable by their owner only; every participant talks UDP
  // (libs/dds/participant.cpp). Two ids of no account, via setpriv: neither may write the other's files.
  if (::geteuid() != 0) GTEST_SKIP() << "running processes as other users needs root";
  if (shell("command -v setpriv").status != 0) GTEST_SKIP() << "setpriv (util-linux) is not installed";
  const auto as_user = [](int uid, const fs::path& program, std::vector<std::string> args) {
    std::vector<std::string> argv{"--reuid=" + std::to_string(uid), "--regid=" + std::to_string(uid), "--clear-groups",
                                  program.string()};
    argv.insert(argv.end(), args.begin(), args.end());
    return ChildProcess::start("/usr/bin/setpriv", argv);
  };
  auto service = as_user(4242, bin_dir() / "vision_gateway", {"--domain", "220", "--vision-port", "22171"});
  ASSERT_TRUE(service) << service.error().message;
  auto health = as_user(4243, bin_dir() / "sslctl", {"health", "--json", "--listen", "4", "--domain", "220"});
  ASSERT_TRUE(health) << health.error().message;
  std::string reports;
  while (auto line = health->read_line(15s)) reports += *line + "\n";
  service->signal(SIGTERM);
  EXPECT_EQ(service->wait(15s), 0) << service->drain_stderr();
  EXPECT_THAT(reports, HasSubstr("\"service\":\"vision_gateway\"")) << health->drain_stderr();
}

// ---------------------------------------------------------------------------------------------------------
// cmake --install

TEST(Install, PutsAMatchPcsTreeUnderThePrefixWithUnitsNamingIt) {
  TempDir prefix;
  install_to(prefix.path);
  for (const std::string& program : kExecutables) {
    EXPECT_TRUE(fs::exists(prefix.path / "opt/ssl-stack/bin" / program)) << program;
  }
  for (const char* file : {"config/planner.yaml", "config/dds.yaml", "qos/profiles.xml", "sites/sim/dds.yaml",
                           "sites/field/robot_link.yaml", "config/referee_profiles/simulation.yaml", "ssl-stack.env"}) {
    EXPECT_TRUE(fs::exists(prefix.path / "etc/ssl-stack" / file)) << file;
  }
  for (const std::string& unit : kUnits) {
    const fs::path path = prefix.path / "lib/systemd/system" / unit;
    ASSERT_TRUE(fs::exists(path)) << unit;
    const std::string text = read_text(path);
    EXPECT_THAT(text, Not(HasSubstr("@"  "SSL_"))) << unit << " has an unexpanded placeholder";
  }
  const fs::path planner = prefix.path / "lib/systemd/system/ssl-planner@.service";
  EXPECT_EQ(unit_value(planner, "ExecStart"),
            (prefix.path / "opt/ssl-stack/bin/planner").string() +
                " --team %i --site ${SSL_SITE} --domain ${SSL_DOMAIN} $SSL_FLAGS");
  EXPECT_EQ(unit_value(planner, "EnvironmentFile"), (prefix.path / "etc/ssl-stack/ssl-stack.env").string());
  EXPECT_EQ(unit_value(planner, "Type"), "notify");
  EXPECT_EQ(read_environment_file(prefix.path / "etc/ssl-stack/ssl-stack.env").at("SSL_SITE"), "sim");
}

TEST(Install, TheInstalledServicesReadTheInstalledConfigsAndSites) {
  TempDir prefix;
  install_to(prefix.path);
  // A team's edit of the installed file, which the source tree does not have.
  const fs::path config = prefix.path / "etc/ssl-stack/config/vision_gateway.yaml";
  std::string text = read_text(config);
  const std::string tracker = "  port: 10010";
  ASSERT_NE(text.find(tracker), std::string::npos);
  text.replace(text.find(tracker), tracker.size(), "  port: 10099");
  write_text(config, text);

  const fs::path gateway = prefix.path / "opt/ssl-stack/bin/vision_gateway";
  for (const auto& [site, port] : std::vector<std::pair<std::string, std::string>>{{"sim", "10020"}, {"grsim", "10020"}, {"field", "10006"}}) {
    auto child = ChildProcess::start(gateway, {"--print-config", "--site", site});
    ASSERT_TRUE(child) << child.error().message;
    std::string printed;
    while (auto line = child->read_line(10s)) printed += *line + "\n";
    EXPECT_EQ(child->wait(10s), 0) << child->drain_stderr();
    EXPECT_THAT(printed, HasSubstr("port: 10099")) << "not the installed file:\n" << printed;
    EXPECT_THAT(printed, HasSubstr("vision_port: " + port)) << site;
  }
  // The grsim site's planner layer: grSim's robots' acceleration and the turn limit their wheels need.
  const fs::path planner = prefix.path / "opt/ssl-stack/bin/planner";
  for (const auto& [site, limits] : std::vector<std::pair<std::string, std::vector<std::string>>>{
           {"sim", {"max_acceleration: 3", "max_turning_acceleration: 0"}},
           {"grsim", {"max_acceleration: 2.3", "max_turning_acceleration: 1.5"}}}) {
    auto child = ChildProcess::start(planner, {"--print-config", "--site", site});
    ASSERT_TRUE(child) << child.error().message;
    std::string printed;
    while (auto line = child->read_line(10s)) printed += *line + "\n";
    EXPECT_EQ(child->wait(10s), 0) << child->drain_stderr();
    for (const std::string& limit : limits) EXPECT_THAT(printed, HasSubstr(limit)) << site;
  }
  // An unknown site is a clear error naming the installed ones.
  auto wrong = ChildProcess::start(gateway, {"--print-config", "--site", "feild"});
  ASSERT_TRUE(wrong);
  EXPECT_EQ(wrong->wait(10s), 1);
  EXPECT_THAT(wrong->drain_stderr() + [&] {
    std::string out;
    while (auto line = wrong->read_line(1s)) out += *line;
    return out;
  }(), HasSubstr("unknown site 'feild' (known: field, grsim, sim"));
}

// ---------------------------------------------------------------------------------------------------------
// The units

TEST(Units, EveryUnitPassesSystemdAnalyzeVerify) {
  if (shell("command -v systemd-analyze").status != 0) GTEST_SKIP() << "systemd-analyze is not installed";
  TempDir prefix;
  install_to(prefix.path);
  const fs::path units = prefix.path / "lib/systemd/system";
  // Templates are verified as an instance, beside the units they name.
  for (const std::string& unit : kUnits) {
    const std::string name = unit.find("@.") != std::string::npos
                                 ? std::regex_replace(unit, std::regex("@\\."), "@blue.")
                                 : unit;
    if (name != unit) fs::copy_file(units / unit, units / name, fs::copy_options::overwrite_existing);
    const ShellRun run = shell("cd '" + units.string() + "' && SYSTEMD_LOG_LEVEL=notice systemd-analyze verify --man=no './" +
                          name + "'");
    // Users and the target's siblings in the real /lib/systemd/system are not ours to judge here; any
    // other complaint is a failure.
    std::string complaints;
    std::istringstream lines(run.output);
    for (std::string line; std::getline(lines, line);) {
      if (line.find("ssl-stack") != std::string::npos && line.find("user") != std::string::npos) continue;
      complaints += line + "\n";
    }
    EXPECT_EQ(run.status, 0) << name << ":\n" << run.output;
    EXPECT_EQ(complaints, "") << name;
  }
}

TEST(Units, TheVisionToRadioPathRunsInAHeavierSliceThanTheRest) {
  TempDir prefix;
  install_to(prefix.path);
  const fs::path units = prefix.path / "lib/systemd/system";
  for (const std::string& unit : kUnits) {
    if (!unit.ends_with(".service")) continue;
    const bool on_path = unit == "ssl-vision-gateway.service" || unit == "ssl-world-model@.service" ||
                         unit == "ssl-planner@.service" || unit == "ssl-robot-link@.service";
    EXPECT_EQ(unit_value(units / unit, "Slice"), on_path ? "ssl-latency.slice" : "ssl-bulk.slice") << unit;
  }
  const int latency = std::stoi(unit_value(units / "ssl-latency.slice", "CPUWeight"));
  const int bulk = std::stoi(unit_value(units / "ssl-bulk.slice", "CPUWeight"));
  EXPECT_GE(latency, 10 * bulk);
}

TEST(Units, AServiceThatKeepsFailingIsRestartedWithAGrowingWait) {
  TempDir prefix;
  install_to(prefix.path);
  const fs::path backoff = prefix.path / "opt/ssl-stack/bin/ssl-restart-backoff";
  ASSERT_TRUE(fs::exists(backoff));
  for (const std::string& unit : kUnits) {
    if (!unit.ends_with(".service")) continue;
    EXPECT_EQ(unit_value(prefix.path / "lib/systemd/system" / unit, "ExecStartPre"), backoff.string() + " %n") << unit;
  }
  // Starts within a minute: the first two at once, then 1, 2, 4, 8 s, never more.
  const fs::path runtime = prefix.path / "run";  // a second TempDir would be the same directory
  std::string waits;
  for (int start = 0; start < 7; ++start) {
    const ShellRun run = shell("RUNTIME_DIRECTORY='" + runtime.string() + "' '" + backoff.string() +
                               "' --print ssl-planner@blue.service");
    ASSERT_EQ(run.status, 0) << run.output;
    waits += run.output.substr(0, run.output.find('\n')) + " ";
  }
  EXPECT_EQ(waits, "0 0 1 2 4 8 8 ");
  // Another unit keeps its own count.
  EXPECT_EQ(shell("RUNTIME_DIRECTORY='" + runtime.string() + "' '" + backoff.string() +
                  "' --print ssl-world-model@blue.service").output,
            "0\n");
}

// Runs `ExecStart` of `unit` (instance `instance`) exactly as written, with `env`, in namespace `ns`.
Result<ChildProcess> start_unit(const NetNamespace& ns, const fs::path& unit, const std::map<std::string, std::string>& env,
                                const std::string& instance) {
  const std::vector<std::string> argv = expand_exec_start(unit_value(unit, "ExecStart"), env, instance);
  if (argv.empty()) return Error{"no ExecStart in " + unit.string()};
  return ChildProcess::start(NetNamespace::ip(),
                             ns.exec_args(argv.front(), std::vector<std::string>(argv.begin() + 1, argv.end())));
}

TEST(Units, EachExecStartAsWrittenWithItsEnvironmentFileGivesAHealthyService) {
  auto ns = NetNamespace::create("ssl-test-units");
  if (!ns) GTEST_SKIP() << ns.error().message;
  TempDir prefix;
  install_to(prefix.path);
  // The team's environment file: this test's domain; the rest as installed (site sim).
  const fs::path env_file = prefix.path / "etc/ssl-stack/ssl-stack.env";
  std::string text = read_text(env_file);
  text = std::regex_replace(text, std::regex("SSL_DOMAIN=0"), "SSL_DOMAIN=221");
  write_text(env_file, text);
  const fs::path units = prefix.path / "lib/systemd/system";
  const std::map<std::string, std::string> env = read_environment_file(
      fs::path(unit_value(units / "ssl-planner@.service", "EnvironmentFile")));
  ASSERT_EQ(env.at("SSL_DOMAIN"), "221");

  std::vector<ChildProcess> running;
  const std::vector<std::pair<std::string, std::string>> started{
      {"ssl-simulator.service", ""},         {"ssl-vision-gateway.service", ""},
      {"ssl-referee-gateway.service", ""},   {"ssl-robot-link@.service", "blue"},
      {"ssl-world-model@.service", "blue"},  {"ssl-planner@.service", "blue"},
      {"ssl-console.service", ""}};
  for (const auto& [unit, instance] : started) {
    auto child = start_unit(*ns, units / unit, env, instance);
    ASSERT_TRUE(child) << unit << ": " << child.error().message;
    running.push_back(std::move(*child));
  }
  const std::vector<std::string> expected{"simulator",       "vision_gateway",   "referee_gateway", "robot_link/blue",
                                          "world_model/blue", "planner/blue",    "console/8080"};
  std::map<std::string, nlohmann::json> reports;
  for (int attempt = 0; attempt < 4; ++attempt) {
    reports = health_reports(ns->exec_args(bin_dir() / "sslctl", {}), 221, 3);
    bool all = true;
    for (const std::string& service : expected) all = all && reports.contains(service);
    if (all) break;
  }
  for (const std::string& service : expected) {
    ASSERT_TRUE(reports.contains(service)) << service << " is not reporting";
    EXPECT_TRUE(healthy(reports[service])) << service << ": " << reports[service].dump();
  }
  for (ChildProcess& child : running) child.signal(SIGTERM);
  for (ChildProcess& child : running) EXPECT_EQ(child.wait(15s), 0) << child.drain_stderr();
}

// ---------------------------------------------------------------------------------------------------------
// Sites

// Starts `program args` in `ns` and returns the UDP ports it has bound once `port` is among them (or
// after 10 s).
std::vector<int> ports_once_bound(const NetNamespace& ns, const std::string& program, const std::vector<std::string>& args,
                                  int port) {
  auto child = ChildProcess::start(NetNamespace::ip(), ns.exec_args(bin_dir() / program, args));
  if (!child) return {};
  std::vector<int> ports;
  for (int i = 0; i < 100; ++i) {
    ports = bound_udp_ports(child->pid());
    if (std::find(ports.begin(), ports.end(), port) != ports.end()) break;
    std::this_thread::sleep_for(100ms);  // polls the process's socket table, not a wait for discovery
  }
  child->signal(SIGTERM);
  (void)child->wait(15s);
  return ports;
}

TEST(Sites, TheSameServicesBindWhatEachSiteSays) {
  auto ns = NetNamespace::create("ssl-test-sites");
  if (!ns) GTEST_SKIP() << ns.error().message;
  // vision_gateway: the simulators' port in sim, SSL-Vision's on the field.
  EXPECT_THAT(ports_once_bound(*ns, "vision_gateway", {"--site", "sim", "--domain", "222"}, 10020),
              ::testing::Contains(10020));
  EXPECT_THAT(ports_once_bound(*ns, "vision_gateway", {"--site", "field", "--domain", "222"}, 10006),
              ::testing::Contains(10006));
  // referee_gateway: on the field it listens for the Game Controller on 10003; in sim the built-in referee
  // runs (profile simulation) and sends there, and the gateway reads it as it would read a Game Controller.
  EXPECT_THAT(ports_once_bound(*ns, "referee_gateway", {"--site", "field", "--domain", "222"}, 10003),
              ::testing::Contains(10003));
  // The field site's peers, where the site says they are (the field PC, 198.18.0.1), with its DDS Security.
  ASSERT_TRUE(NetNamespace::run_ip({"-n", ns->name(), "addr", "add", "198.18.0.1/15", "dev", "lo"}));
  for (const auto& [site, builtin] : std::vector<std::pair<std::string, bool>>{{"sim", true}, {"field", false}}) {
    auto gateway = ChildProcess::start(NetNamespace::ip(), ns->exec_args(bin_dir() / "referee_gateway",
                                                                          {"--site", site, "--domain", "222"}));
    ASSERT_TRUE(gateway) << gateway.error().message;
    auto reports = health_reports(ns->exec_args(bin_dir() / "sslctl", {}), 222, 3, site);
    gateway->signal(SIGTERM);
    EXPECT_EQ(gateway->wait(15s), 0) << gateway->drain_stderr();
    ASSERT_TRUE(reports.contains("referee_gateway")) << site;
    EXPECT_EQ(reports.contains("referee_gateway/builtin"), builtin) << site;
    if (builtin) {
      EXPECT_THAT(reports["referee_gateway/builtin"]["status"].get<std::string>(), HasSubstr("profile simulation"));
    } else {
      EXPECT_THAT(reports["referee_gateway"]["status"].get<std::string>(), HasSubstr("no referee packet"));
    }
  }
}

TEST(Sites, RobotLinkDrivesTheSimulatorInSimGrSimOnGrSimAndTheRadioOnTheField) {
  TempDir dir;
  for (const auto& [site, backend] :
       std::vector<std::pair<std::string, std::string>>{{"sim", "sim"}, {"grsim", "grsim"}, {"field", "radio"}}) {
    auto child = ChildProcess::start(bin_dir() / "robot_link", {"--print-config", "--team", "blue", "--site", site});
    ASSERT_TRUE(child) << child.error().message;
    std::string printed;
    while (auto line = child->read_line(10s)) printed += *line + "\n";
    EXPECT_EQ(child->wait(10s), 0) << child->drain_stderr();
    EXPECT_THAT(printed, HasSubstr("backend: " + backend)) << site;
  }
  // The field's radio is the USB base station; without one here robot_link says which device it wanted.
  auto field = ChildProcess::start(bin_dir() / "robot_link",
                                   {"--team", "blue", "--site", "field", "--domain", "222", "--set",
                                    "radio.device=" + (dir.path / "no-base-station").string(), "estop_device=\"\""});
  ASSERT_TRUE(field);
  EXPECT_EQ(field->wait(15s), 1);
  EXPECT_THAT(field->drain_stderr() + [&] {
    std::string out;
    while (auto line = field->read_line(1s)) out += *line + "\n";
    return out;
  }(), HasSubstr("no-base-station"));
}

// ---------------------------------------------------------------------------------------------------------
// Discovery without multicast

TEST(Discovery, ClientsOfADiscoveryServerFindEachOtherThroughItAndOnlyThroughIt) {
  if (shell("command -v fastdds").status != 0) GTEST_SKIP() << "fastdds (fastdds-tools) is not installed";
  TempDir dir;
  const std::string port = "22169";
  write_text(dir.path / "served/dds.yaml", "discovery: server\nservers: [127.0.0.1:" + port + "]\n");
  write_text(dir.path / "unserved/dds.yaml", "discovery: server\nservers: [127.0.0.1:22170]\n");
  auto server = ChildProcess::start("/usr/bin/fastdds", {"discovery", "-i", "0", "-l", "127.0.0.1", "-p", port});
  ASSERT_TRUE(server) << server.error().message;

  const auto exchange = [&](const std::string& site, double timeout_s) {
    auto echo = ChildProcess::start(bin_dir() / "sslctl", {"topic", "echo", "system.estop", "--count", "1", "--timeout",
                                                           std::to_string(timeout_s), "--domain", "223", "--site",
                                                           (dir.path / site).string()});
    auto pub = ChildProcess::start(bin_dir() / "sslctl",
                                   {"topic", "pub", "system.estop", R"({"engaged": true, "source": "deploy_test"})",
                                    "--wait-readers", "1", "--wait-timeout", std::to_string(timeout_s), "--linger", "1",
                                    "--domain", "223", "--site", (dir.path / site).string()});
    std::optional<std::string> line = echo ? echo->read_line(std::chrono::seconds(static_cast<int>(timeout_s) + 10))
                                           : std::nullopt;
    if (pub) (void)pub->wait(std::chrono::seconds(static_cast<int>(timeout_s) + 10));
    return line;
  };
  const auto served = exchange("served", 20);
  ASSERT_TRUE(served) << "no sample through the discovery server";
  EXPECT_THAT(*served, HasSubstr("deploy_test"));
  // Pointed at a server that does not run, the same two never meet: no multicast fallback.
  EXPECT_FALSE(exchange("unserved", 5)) << "discovery went around the server";
}

// ---------------------------------------------------------------------------------------------------------
// The Debian package

TEST(Package, TheDebDeclaresItsDependenciesAndInstallsWithApt) {
  if (shell("command -v cpack && command -v dpkg-deb").status != 0) GTEST_SKIP() << "cpack or dpkg-deb is missing";
  TempDir out;
  const ShellRun packed = shell("cd '" + bin_dir().parent_path().string() + "' && cpack -G DEB -B '" + out.path.string() + "'");
  ASSERT_EQ(packed.status, 0) << packed.output;
  std::optional<fs::path> deb;
  for (const auto& entry : fs::directory_iterator(out.path)) {
    if (entry.path().extension() == ".deb") deb = entry.path();
  }
  ASSERT_TRUE(deb) << packed.output;
  const ShellRun depends = shell("dpkg-deb -f '" + deb->string() + "' Depends");
  for (const char* package : {"libfastrtps", "libbullet", "libyaml-cpp", "libsystemd0", "fastdds-tools"}) {
    EXPECT_THAT(depends.output, HasSubstr(package));
  }
  const ShellRun contents = shell("dpkg-deb -c '" + deb->string() + "'");
  for (const char* file : {"./opt/ssl-stack/bin/planner", "./etc/ssl-stack/config/planner.yaml",
                           "./etc/ssl-stack/sites/field/dds.yaml", "./lib/systemd/system/ssl-planner@.service",
                           "./lib/systemd/system/ssl-field.target"}) {
    EXPECT_THAT(contents.output, HasSubstr(file));
  }
  const ShellRun conffiles = shell("dpkg-deb -I '" + deb->string() + "' conffiles");
  EXPECT_THAT(conffiles.output, HasSubstr("/etc/ssl-stack/ssl-stack.env"));

  if (::geteuid() != 0) GTEST_SKIP() << "installing the package needs root";
  if (shell("dpkg-query -W -f='${Status}' ssl-stack | grep -q 'install ok installed'").status == 0) {
    GTEST_SKIP() << "ssl-stack is installed on this machine; this test installs and purges its own";
  }
  const ShellRun installed = shell("DEBIAN_FRONTEND=noninteractive apt-get install -y -q '" + deb->string() + "'");
  ASSERT_EQ(installed.status, 0) << installed.output;
  // From the installed paths alone: the config in /etc/ssl-stack, the site switch, the units' check.
  const ShellRun printed = shell("cd / && SSL_SITE=field /opt/ssl-stack/bin/vision_gateway --print-config");
  const ShellRun verified = shell("cd /lib/systemd/system && systemd-analyze verify --man=no ssl-field.target");
  const ShellRun user = shell("getent passwd ssl-stack");
  const ShellRun purged = shell("DEBIAN_FRONTEND=noninteractive apt-get purge -y -q ssl-stack");
  EXPECT_EQ(printed.status, 0) << printed.output;
  EXPECT_THAT(printed.output, HasSubstr("vision_port: 10006"));
  EXPECT_EQ(verified.status, 0) << verified.output;
  EXPECT_EQ(user.status, 0) << "the package creates the units' user";
  EXPECT_EQ(purged.status, 0) << purged.output;
  EXPECT_FALSE(fs::exists("/opt/ssl-stack/bin/planner"));
}

}  // namespace
}  // namespace ssl::testing
