// A match spread over four hosts, each a network namespace joined to the others by veth pairs over one
// bridge (addresses in 198.18.0.0/15), run from this build installed as on a match PC (cmake --install:
// /opt/ssl-stack/bin and /etc/ssl-stack under a prefix; the namespaces share it as two PCs each with the
// package would):
//   A 198.18.0.1  the field PC: simulator (no vision noise: its vision is the ground truth), vision_gateway,
//                 referee_gateway with the built-in referee, both robot_links (the radio host)
//   B 198.18.0.2  blue world_model + planner, run by B's own systemd from the installed units
//                 (ssl-team@blue.target): a container (systemd-nspawn) booting this machine's /usr with an
//                 empty /etc in B's namespace
//   C 198.18.0.3  yellow world_model + planner
//   D 198.18.0.4  the coach box: sslctl (starts the match, reads health)
// With multicast discovery; and with multicast dropped by the bridge, using a discovery server on A or
// unicast peers (a site of the install like sim with `discovery: server` or `discovery: peers`). Each run:
// both teams move during 20 s of play; cutting B's link stops blue (robot_link's 100 ms watchdog, then
// braking) while yellow's commands keep reaching its robots; restoring it brings blue's commands back to A
// within 3 s; killing B's planner (SIGKILL): B's systemd restarts it (Restart=on-failure, RestartSec=1) and
// its commands come back (the referee state and geometry caught up from transient-local samples), blue
// standing meanwhile.
// Motion is the simulator's noise-free vision read on A; commands are robot.commands samples read on A.
// Needs root and systemd-nspawn (systemd-container); skips without them. Figures are printed.
#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cctype>
#include <cmath>
#include <csignal>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <functional>
#include <iterator>
#include <map>
#include <memory>
#include <mutex>
#include <nlohmann/json.hpp>
#include <optional>
#include <regex>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

#include "tests/support/netns.h"
#include "tests/support/process.h"

namespace ssl::testing {
namespace {

namespace fs = std::filesystem;
using namespace std::chrono_literals;
using Clock = std::chrono::system_clock;

std::int64_t now_ns() {
  return std::chrono::duration_cast<std::chrono::nanoseconds>(Clock::now().time_since_epoch()).count();
}

constexpr double kStoppedSpeed = 0.1;  // m/s: a robot slower than this stands
constexpr double kMoved = 0.3;         // m: a team whose robot went this far in a window moves

// The four hosts and the switch, named after `tag` (runs in parallel each have their own). Deleted with
// the object.
class Network {
 public:
  static Result<Network> create(const std::string& tag) {
    Network net;
    net.switch_name_ = "ssl-mh" + tag + "-sw";
    auto sw = NetNamespace::create(net.switch_name_);
    if (!sw) return sw.error();
    net.switch_.emplace(std::move(*sw));
    for (const std::vector<std::string>& step : std::vector<std::vector<std::string>>{
             {"-n", net.switch_name_, "link", "add", "br0", "type", "bridge"},
             {"-n", net.switch_name_, "link", "set", "br0", "up"}}) {
      if (Status ok = NetNamespace::run_ip(step); !ok) return ok.error();
    }
    const char* names[] = {"a", "b", "c", "d"};
    for (int i = 0; i < 4; ++i) {
      const std::string host = "ssl-mh" + tag + "-" + names[i];
      auto ns = NetNamespace::create(host);
      if (!ns) return ns.error();
      net.hosts_.push_back(std::move(*ns));
      const std::string port = std::string("v") + names[i];
      for (const std::vector<std::string>& step : std::vector<std::vector<std::string>>{
               {"link", "add", "eth0", "netns", host, "type", "veth", "peer", "name", port, "netns", net.switch_name_},
               {"-n", net.switch_name_, "link", "set", port, "master", "br0"},
               {"-n", net.switch_name_, "link", "set", port, "up"},
               {"-n", host, "addr", "add", "198.18.0." + std::to_string(i + 1) + "/15", "dev", "eth0"},
               {"-n", host, "link", "set", "eth0", "up"},
               {"-n", host, "route", "add", "224.0.0.0/4", "dev", "eth0", "metric", "10"}}) {
        if (Status ok = NetNamespace::run_ip(step); !ok) return ok.error();
      }
    }
    return net;
  }

  const NetNamespace& host(char name) const { return hosts_.at(static_cast<std::size_t>(name - 'a')); }

  /// Multicast dropped between the hosts (the bridge forwards no multicast frame).
  Status block_multicast() const {
    for (const std::string& rule : {std::string("add table bridge ssl"),
                                    std::string("add chain bridge ssl forward { type filter hook forward priority 0; }"),
                                    std::string("add rule bridge ssl forward meta pkttype multicast drop")}) {
      const ShellRun run = shell(NetNamespace::ip().string() + " netns exec " + switch_name_ + " nft '" + rule + "'");
      if (run.status != 0) return Error{"nft " + rule + " failed (is nftables installed?): " + run.output};
    }
    return Status::success();
  }
  /// A host's cable: the switch's port of `host` down or up.
  Status set_link(char host, bool up) const {
    return NetNamespace::run_ip({"-n", switch_name_, "link", "set", std::string("v") + host, up ? "up" : "down"});
  }

 private:
  Network() = default;
  std::string switch_name_;
  std::optional<NetNamespace> switch_;
  std::vector<NetNamespace> hosts_;
};

// `sslctl topic echo` read on its own thread until destroyed: each JSON object goes to `on_sample` with the
// time it was read (wall clock, ns).
class EchoReader {
 public:
  EchoReader(ChildProcess echo, std::function<void(const nlohmann::json&, std::int64_t)> on_sample)
      : echo_(std::move(echo)), on_sample_(std::move(on_sample)), reader_([this] { read(); }) {}
  ~EchoReader() {
    stop_ = true;
    echo_.signal(SIGTERM);
    reader_.join();
  }

 private:
  void read() {
    while (!stop_) {
      auto line = echo_.read_line(500ms);
      if (!line) continue;
      const std::int64_t read_at = now_ns();
      auto sample = nlohmann::json::parse(*line, nullptr, false);
      if (sample.is_object()) on_sample_(sample, read_at);
    }
  }
  ChildProcess echo_;
  std::function<void(const nlohmann::json&, std::int64_t)> on_sample_;
  std::atomic<bool> stop_{false};
  std::thread reader_;
};

// The simulator's noise-free vision, read on A (where the link cuts do not reach): every robot's position
// at each camera frame's capture time (wall clock, ns).
class Truth {
 public:
  explicit Truth(ChildProcess echo)
      : reader_(std::move(echo), [this](const nlohmann::json& frame, std::int64_t) { add(frame); }) {}

  /// The largest distance any robot of `team` ("blue", "yellow") went between `from` and `to` (ns).
  double moved(const std::string& team, std::int64_t from, std::int64_t to) const {
    std::vector<std::uint32_t> ids;
    {
      std::lock_guard lock(mutex_);
      for (const auto& [key, track] : tracks_) {
        if (key.first == team) ids.push_back(key.second);
      }
    }
    double best = 0;
    for (std::uint32_t id : ids) best = std::max(best, robot_moved(team, id, from, to));
    return best;
  }

  /// The largest distance robot `id` of `team` went from where it was first seen after `from`, until `to`.
  double robot_moved(const std::string& team, std::uint32_t id, std::int64_t from, std::int64_t to) const {
    std::lock_guard lock(mutex_);
    const auto found = tracks_.find({team, id});
    if (found == tracks_.end()) return 0;
    std::optional<std::pair<double, double>> first;
    double best = 0;
    for (const Sample& s : found->second) {
      if (s.t < from || s.t > to) continue;
      if (!first) first = std::make_pair(s.x, s.y);
      best = std::max(best, std::hypot(s.x - first->first, s.y - first->second));
    }
    return best;
  }

  /// The time after `from` by which every robot of `team` had come to a stand (below kStoppedSpeed over a
  /// 0.1 s step) at least once before `to`: the latest of their first standing steps. A robot pushed after
  /// it stood still counts as stopped. nullopt when one of them never stood.
  std::optional<std::int64_t> all_stood_by(const std::string& team, std::int64_t from, std::int64_t to) const {
    constexpr std::int64_t kStep = 100'000'000;
    std::vector<std::uint32_t> ids;
    {
      std::lock_guard lock(mutex_);
      for (const auto& [key, track] : tracks_) {
        if (key.first == team) ids.push_back(key.second);
      }
    }
    std::int64_t latest = from;
    for (std::uint32_t id : ids) {
      std::optional<std::int64_t> stood;
      for (std::int64_t t = from; t + kStep <= to && !stood; t += kStep) {
        if (robot_moved(team, id, t, t + kStep) < kStoppedSpeed * 0.1) stood = t;
      }
      if (!stood) return std::nullopt;
      latest = std::max(latest, *stood);
    }
    return latest;
  }

  /// The largest distance per 0.1 s step from `from` to `to`, for failure messages.
  std::string windows(const std::string& team, std::int64_t from, std::int64_t to) const {
    std::string text;
    for (std::int64_t t = from; t + 100'000'000 <= to; t += 100'000'000) {
      text += std::to_string(static_cast<int>(moved(team, t, t + 100'000'000) * 1000)) + " ";
    }
    return text + "(mm per 0.1 s)";
  }

  std::size_t frames() const {
    std::lock_guard lock(mutex_);
    return frames_;
  }

  /// Observations of `team`'s robots between `from` and `to`, for failure messages.
  std::size_t samples(const std::string& team, std::int64_t from, std::int64_t to) const {
    std::lock_guard lock(mutex_);
    std::size_t count = 0;
    for (const auto& [key, track] : tracks_) {
      if (key.first != team) continue;
      count += static_cast<std::size_t>(std::count_if(track.begin(), track.end(),
                                                      [&](const Sample& s) { return s.t >= from && s.t <= to; }));
    }
    return count;
  }

 private:
  struct Sample {
    std::int64_t t;
    double x;
    double y;
  };
  void add(const nlohmann::json& frame) {
    std::lock_guard lock(mutex_);
    ++frames_;
    const std::int64_t t = frame.value("capture_unix_ns", std::int64_t{0});
    for (const char* team : {"blue", "yellow"}) {
      for (const auto& robot : frame[std::string("robots_") + team]) {
        tracks_[{team, robot.value("robot_id", 0u)}].push_back({t, robot.value("x", 0.0), robot.value("y", 0.0)});
      }
    }
  }

  mutable std::mutex mutex_;
  std::map<std::pair<std::string, std::uint32_t>, std::vector<Sample>> tracks_;
  std::size_t frames_ = 0;
  EchoReader reader_;  // last: it starts after the state above exists and stops before it goes
};

// When one team's robot.commands samples reach A (robot_link's host): the planner across the network, as
// the field PC sees it. Each arrival is kept with the time it was read here and the receive time of the
// camera frame its world state came from (its VisionStamp, stamped by vision_gateway on A): a command
// computed from vision received after an event can only have been planned after it, however late this
// test reads it.
class Arrivals {
 public:
  explicit Arrivals(ChildProcess echo)
      : reader_(std::move(echo), [this](const nlohmann::json& sample, std::int64_t read_at) { add(sample, read_at); }) {}
  /// When the first command planned from vision received after `t` was read, if any.
  std::optional<std::int64_t> first_planned_after(std::int64_t t) const {
    std::lock_guard lock(mutex_);
    for (const Arrival& a : arrivals_) {
      if (a.vision > t) return a.read;
    }
    return std::nullopt;
  }
  /// The longest time without an arrival between `from` and `to` (ns, read times).
  std::int64_t longest_gap(std::int64_t from, std::int64_t to) const {
    std::lock_guard lock(mutex_);
    std::int64_t last = from;
    std::int64_t gap = 0;
    for (const Arrival& a : arrivals_) {
      if (a.read <= from || a.read > to) continue;
      gap = std::max(gap, a.read - last);
      last = a.read;
    }
    return std::max(gap, to - last);
  }

 private:
  struct Arrival {
    std::int64_t read;    // when this test read it
    std::int64_t vision;  // receive time of the camera frame it was planned from
  };
  void add(const nlohmann::json& sample, std::int64_t read_at) {
    if (!sample.contains("stamp")) return;
    std::lock_guard lock(mutex_);
    arrivals_.push_back({read_at, sample["stamp"].value("receive_unix_ns", std::int64_t{0})});
  }
  mutable std::mutex mutex_;
  std::vector<Arrival> arrivals_;
  EchoReader reader_;  // last: it starts after the state above exists and stops before it goes
};

// A host's own systemd: a container (systemd-nspawn) in the host's network namespace that boots this
// machine's /usr with an empty /etc, the install under `prefix` bound at its own path, its units as the
// system units and a passwd with the units' user; it starts `target`. Powered off (SIGTERM to nspawn: an
// orderly shutdown of every unit) with the object. Its console is kept for failure messages.
class HostSystemd {
 public:
  static Result<std::unique_ptr<HostSystemd>> boot(const NetNamespace& ns, const fs::path& prefix,
                                                   const std::string& target) {
    const fs::path etc = prefix / ("container-etc-" + ns.name());
    fs::create_directories(etc);
    std::ofstream(etc / "passwd") << "root:x:0:0:root:/root:/bin/sh\n"
                                  << "ssl-stack:x:4240:4240:ssl-stack:/nonexistent:/usr/sbin/nologin\n";
    std::ofstream(etc / "group") << "root:x:0:\nssl-stack:x:4240:\n";
    auto nspawn = ChildProcess::start(
        "/usr/bin/systemd-nspawn",
        {"--quiet", "--register=no", "--keep-unit", "--volatile=yes", "--directory=/", "--machine=" + ns.name(),
         "--network-namespace-path=/run/netns/" + ns.name(), "--console=pipe", "--bind-ro=" + prefix.string(),
         "--bind-ro=" + (prefix / "lib/systemd/system").string() + ":/etc/systemd/system",
         "--bind-ro=" + (etc / "passwd").string() + ":/etc/passwd",
         "--bind-ro=" + (etc / "group").string() + ":/etc/group", "--boot", "--", "--unit=" + target,
         "systemd.firstboot=off"});
    if (!nspawn) return nspawn.error();
    return std::unique_ptr<HostSystemd>(new HostSystemd(std::move(*nspawn)));
  }
  ~HostSystemd() {
    nspawn_.signal(SIGTERM);
    if (!nspawn_.wait(30s)) nspawn_.signal(SIGKILL);
    stop_ = true;
    console_reader_.join();
  }
  /// The container's console so far (its boot and unit messages), for failure messages.
  std::string console() const {
    std::lock_guard lock(mutex_);
    return console_;
  }

 private:
  explicit HostSystemd(ChildProcess nspawn) : nspawn_(std::move(nspawn)), console_reader_([this] { read(); }) {}
  void read() {
    while (!stop_) {
      auto line = nspawn_.read_line(200ms);
      if (!line) continue;
      std::lock_guard lock(mutex_);
      console_ += *line + "\n";
    }
  }
  ChildProcess nspawn_;
  mutable std::mutex mutex_;
  std::string console_;
  std::atomic<bool> stop_{false};
  std::thread console_reader_;  // last: it starts after the state above exists
};

/// The processes running `program` with `args` among their arguments, seen from this (the machine's) PID
/// namespace, containers' included.
std::vector<pid_t> processes_of(const fs::path& program, const std::vector<std::string>& args) {
  std::vector<pid_t> pids;
  for (const auto& entry : fs::directory_iterator("/proc")) {
    const std::string name = entry.path().filename();
    if (name.empty() || !std::all_of(name.begin(), name.end(), ::isdigit)) continue;
    std::ifstream in(entry.path() / "cmdline");
    std::vector<std::string> argv;
    for (std::string arg; std::getline(in, arg, '\0');) argv.push_back(arg);
    if (argv.empty() || argv.front() != program.string()) continue;
    bool all = true;
    for (const std::string& arg : args) all = all && std::find(argv.begin(), argv.end(), arg) != argv.end();
    if (all) pids.push_back(static_cast<pid_t>(std::stoi(name)));
  }
  return pids;
}

// How the hosts find each other: the site's dds.yaml (libs/dds/discovery.h).
enum class Discovery { kMulticast, kServer, kPeers };

struct Layout {
  std::string name;
  Discovery discovery = Discovery::kMulticast;
  int domain = 0;
};

class MultiHost : public ::testing::TestWithParam<Layout> {};

void PrintTo(const Layout& layout, std::ostream* os) { *os << layout.name; }

TEST_P(MultiHost, AMatchAcrossFourHostsSurvivesACutLinkAndAKilledPlanner) {
  if (::geteuid() != 0) GTEST_SKIP() << "network namespaces need root";
  const Layout& run = GetParam();
  auto net = Network::create(std::to_string(run.domain));
  if (!net) GTEST_SKIP() << "cannot make the network namespaces: " << net.error().message;
  if (!fs::exists("/usr/bin/systemd-nspawn")) GTEST_SKIP() << "systemd-nspawn (Debian's systemd-container) is not installed";
  const std::string domain = std::to_string(run.domain);
  const fs::path prefix = fs::temp_directory_path() / ("ssl_multihost_" + std::to_string(::getpid()));
  const std::unique_ptr<const fs::path, void (*)(const fs::path*)> remove_prefix(
      &prefix, [](const fs::path* path) { fs::remove_all(*path); });
  const Status installed = install_build(prefix);
  ASSERT_TRUE(installed) << installed.error().message;
  const fs::path installed_bin = prefix / "opt/ssl-stack/bin";

  // The site: sim; or, where the bridge drops multicast, a site of the install like sim whose discovery is
  // a server on A, or unicast to the four hosts' addresses.
  std::string site = "sim";
  const fs::path site_dir = prefix / "etc/ssl-stack/sites/sim-without-multicast";
  std::optional<ChildProcess> discovery_server;
  if (run.discovery != Discovery::kMulticast) {
    ASSERT_TRUE(net->block_multicast());
    fs::create_directories(site_dir);
    for (const char* file : {"vision_gateway.yaml", "referee_gateway.yaml", "robot_link.yaml"}) {
      fs::copy_file(prefix / "etc/ssl-stack/sites/sim" / file, site_dir / file, fs::copy_options::overwrite_existing);
    }
    std::ofstream(site_dir / "dds.yaml")
        << (run.discovery == Discovery::kServer
                ? "discovery: server\nservers: [198.18.0.1:11811]\n"
                : "discovery: peers\npeers: [198.18.0.1, 198.18.0.2, 198.18.0.3, 198.18.0.4]\n");
    site = "sim-without-multicast";  // a site of the install, by name
  }
  if (run.discovery == Discovery::kServer) {
    auto server = ChildProcess::start(NetNamespace::ip(), net->host('a').exec_args("/usr/bin/fastdds",
                                                                                   {"discovery", "-i", "0", "-l",
                                                                                    "198.18.0.1", "-p", "11811"}));
    ASSERT_TRUE(server) << server.error().message;
    discovery_server.emplace(std::move(*server));
  }
  const auto start = [&](char host, const std::string& program, std::vector<std::string> args) {
    args.insert(args.end(), {"--site", site, "--domain", domain});
    auto child = ChildProcess::start(NetNamespace::ip(), net->host(host).exec_args(installed_bin / program, args));
    if (!child) throw std::runtime_error(child.error().message);
    return std::move(*child);
  };
  std::vector<ChildProcess> services;
  services.push_back(start('a', "simulator", {"--division", "b", "--robots", "6", "--realism", "none"}));
  services.push_back(start('a', "vision_gateway", {}));
  services.push_back(start('a', "referee_gateway", {"--set", "builtin.division=b"}));
  services.push_back(start('a', "robot_link", {"--team", "blue"}));
  services.push_back(start('a', "robot_link", {"--team", "yellow"}));
  // B: its systemd starts the team's target from the installed units, with the installed environment file
  // naming this run's site and domain.
  const fs::path env_file = prefix / "etc/ssl-stack/ssl-stack.env";
  std::ifstream env_in(env_file);
  std::string env_text((std::istreambuf_iterator<char>(env_in)), std::istreambuf_iterator<char>());
  env_text = std::regex_replace(env_text, std::regex("\nSSL_SITE=sim\n"), "\nSSL_SITE=" + site + "\n");
  env_text = std::regex_replace(env_text, std::regex("\nSSL_DOMAIN=0\n"), "\nSSL_DOMAIN=" + domain + "\n");
  std::ofstream(env_file) << env_text;
  auto host_b = HostSystemd::boot(net->host('b'), prefix, "ssl-team@blue.target");
  ASSERT_TRUE(host_b) << host_b.error().message;
  services.push_back(start('c', "world_model", {"--team", "yellow"}));
  services.push_back(start('c', "planner", {"--team", "yellow"}));

  Truth truth(start('a', "sslctl", {"topic", "echo", "vision.detection"}));
  Arrivals blue_commands(start('a', "sslctl", {"topic", "echo", "robot.commands", "--team", "blue"}));
  Arrivals yellow_commands(start('a', "sslctl", {"topic", "echo", "robot.commands", "--team", "yellow"}));
  // The coach box starts the match: the operator's first STOP to the built-in referee.
  auto stop = start('d', "sslctl", {"topic", "pub", "referee.command", R"({"command": "COMMAND_STOP", "author": "multihost"})",
                                    "--wait-readers", "1", "--wait-timeout", "30", "--linger", "1"});
  ASSERT_EQ(stop.wait(40s), 0) << "the coach box could not reach the referee: " << stop.drain_stderr();
  // B's units up (READY once they hear their inputs) and planning: its commands reach A.
  std::optional<std::int64_t> blue_up;
  for (int i = 0; i < 300 && !blue_up; ++i) {
    std::this_thread::sleep_for(100ms);  // polls the observer
    blue_up = blue_commands.first_planned_after(0);
  }
  ASSERT_TRUE(blue_up) << "B's systemd did not bring blue's team up within 30 s; its console:\n" << (*host_b)->console();

  // 20 s of play: both teams move.
  const std::int64_t play_start = now_ns();
  std::this_thread::sleep_for(20s);  // the match plays; this is the observation window, not a wait for discovery
  const std::int64_t play_end = now_ns();
  ASSERT_GT(truth.frames(), 100u) << "no vision reached the observer";
  EXPECT_GT(truth.moved("blue", play_start, play_end), kMoved) << "blue did not play";
  EXPECT_GT(truth.moved("yellow", play_start, play_end), kMoved) << "yellow did not play";

  // B's cable out for 4 s: blue stands (watchdog 100 ms + braking); yellow's commands keep reaching A.
  const std::int64_t cut = now_ns();
  ASSERT_TRUE(net->set_link('b', false));
  std::this_thread::sleep_for(4s);
  const std::int64_t restored = now_ns();
  ASSERT_TRUE(net->set_link('b', true));
  const auto stopped = truth.all_stood_by("blue", cut, restored);
  ASSERT_TRUE(stopped) << "blue robots kept moving with their planner cut off: " << truth.windows("blue", cut, restored);
  const double stop_s = static_cast<double>(*stopped - cut) * 1e-9;
  // The watchdog's 0.1 s, braking from the limit's 3 m/s at 4 m/s^2 (0.75 s), and 0.75 s for the vision
  // frames, robot_link's 100 Hz tick and the 0.1 s steps of the observation.
  EXPECT_LE(stop_s, 1.6) << "stop later than the watchdog plus braking from full speed: "
                         << truth.windows("blue", cut, restored);
  const double yellow_gap_s = static_cast<double>(yellow_commands.longest_gap(cut, restored)) * 1e-9;
  EXPECT_LT(yellow_gap_s, 0.5) << "yellow's commands stopped reaching its robots";

  // Back within 3 s: blue's commands reach A again.
  std::optional<std::int64_t> resumed;
  for (int i = 0; i < 60 && !resumed; ++i) {
    std::this_thread::sleep_for(100ms);  // polls the observer
    resumed = blue_commands.first_planned_after(restored);
  }
  ASSERT_TRUE(resumed) << "blue's commands did not reach A within 6 s of the link coming back";
  const double resume_s = static_cast<double>(*resumed - restored) * 1e-9;
  EXPECT_LE(resume_s, 3.0);

  // B's planner killed: B's systemd restarts it (Restart=on-failure, RestartSec=1); meanwhile blue stands
  // (robot_link's watchdog); it catches up (referee state, geometry: transient local) and its commands reach
  // A again.
  const fs::path planner = installed_bin / "planner";
  const std::vector<pid_t> before = processes_of(planner, {"--team", "blue"});
  ASSERT_EQ(before.size(), 1u) << "B's systemd is not running one blue planner; its console:\n" << (*host_b)->console();
  ASSERT_EQ(::kill(before.front(), SIGKILL), 0);
  const std::int64_t killed = now_ns();
  std::optional<std::int64_t> restarted;
  for (int i = 0; i < 100 && !restarted; ++i) {
    std::this_thread::sleep_for(50ms);  // polls the process table
    const std::vector<pid_t> now = processes_of(planner, {"--team", "blue"});
    if (!now.empty() && now.front() != before.front()) restarted = now_ns();
  }
  ASSERT_TRUE(restarted) << "B's systemd did not restart the killed planner within 5 s; its console:\n"
                         << (*host_b)->console();
  const double restart_s = static_cast<double>(*restarted - killed) * 1e-9;
  {
    const std::vector<pid_t> now = processes_of(planner, {"--team", "blue"});
    ASSERT_FALSE(now.empty());
    std::ifstream cgroup("/proc/" + std::to_string(now.front()) + "/cgroup");
    const std::string groups((std::istreambuf_iterator<char>(cgroup)), std::istreambuf_iterator<char>());
    EXPECT_NE(groups.find("ssl-latency.slice/ssl-planner@blue.service"), std::string::npos)
        << "the restarted planner is not its unit's process in the latency slice:\n" << groups;
  }
  std::optional<std::int64_t> back;
  for (int i = 0; i < 80 && !back; ++i) {
    std::this_thread::sleep_for(100ms);  // polls the observer
    back = blue_commands.first_planned_after(*restarted);
  }
  ASSERT_TRUE(back) << "blue's planner did not command again after its restart";
  const double back_s = static_cast<double>(*back - killed) * 1e-9;
  EXPECT_LE(restart_s, 2.0) << "RestartSec is 1 s and a first restart has no backoff";
  EXPECT_LE(back_s, 6.0) << "from the kill";
  EXPECT_TRUE(truth.all_stood_by("blue", killed, *back)) << "blue robots kept moving without their planner: "
                                                         << truth.windows("blue", killed, *back);

  std::printf("[figures] multihost %s: blue stood %.2f s after the cut (yellow's commands: longest gap %.3f s, its "
              "robots moved up to %.2f m); blue's commands back %.2f s after the link; the killed planner "
              "restarted by B's systemd after %.2f s, its commands back %.2f s after the kill\n",
              run.name.c_str(), stop_s, yellow_gap_s, truth.moved("yellow", cut, restored), resume_s, restart_s, back_s);
  std::fflush(stdout);

  host_b->reset();  // B powers off: systemd stops its units
  for (ChildProcess& child : services) child.signal(SIGTERM);
  for (ChildProcess& child : services) (void)child.wait(15s);
  if (discovery_server) discovery_server->signal(SIGTERM);
}

INSTANTIATE_TEST_SUITE_P(Discovery, MultiHost,
                         ::testing::Values(Layout{"multicast", Discovery::kMulticast, 170},
                                           Layout{"server_without_multicast", Discovery::kServer, 171},
                                           Layout{"peers_without_multicast", Discovery::kPeers, 172}),
                         [](const ::testing::TestParamInfo<Layout>& param) { return param.param.name; });

}  // namespace
}  // namespace ssl::testing
