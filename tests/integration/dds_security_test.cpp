// DDS Security between teams, with real Fast DDS, real certificates made by deploy/dds-certs.sh (what
// `./ssl certs` runs) and the real robot_link executable. One trust domain holds both teams (an AI-vs-AI
// simulation: the other team authenticates, access control must stop it); a second, foreign CA stands for
// a stranger; an unauthenticated participant has no security at all. Each test first proves the legit
// path works (a reader receives, a command or release moves the robot), then that within a bounded time
// after that nothing came through from the intruders. DDS domains 173-176, UDP ports 27311-27312.
#include <gtest/gtest.h>
#include <unistd.h>

#include <array>
#include <atomic>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <optional>
#include <stdexcept>
#include <thread>

#include "libs/common/deploy_files.h"
#include "libs/dds/participant.h"
#include "libs/league/decode.h"
#include "libs/net/udp.h"
#include "tests/support/process.h"

namespace ssl::testing {
namespace {

namespace fs = std::filesystem;
using std::chrono::milliseconds;
using std::chrono::seconds;
using SteadyClock = std::chrono::steady_clock;

constexpr auto kMatchTimeout = seconds(20);       // secure discovery: handshakes on top of discovery
constexpr auto kIntruderWindow = milliseconds(2000);  // how long intruders get after a legit peer matched

/// Certificates for the whole suite: `trusted` (both teams, one CA) and `foreign` (another CA).
class DdsSecurityTest : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    ::unsetenv("SSL_CERTS_DIR");  // it would beat the directories given below
    root_ = fs::temp_directory_path() / ("ssl_dds_security_test_" + std::to_string(::getpid()));
    fs::remove_all(root_);
    auto script = find_deploy_file("dds-certs.sh");
    ASSERT_TRUE(script) << script.error().message;
    for (const auto& [dir, teams] : {std::pair{"trusted", "blue,yellow"}, std::pair{"foreign", "blue"}}) {
      const ShellRun made = shell("'" + *script + "' --dir '" + (root_ / dir).string() + "' --teams " + teams);
      ASSERT_EQ(made.status, 0) << made.output;
    }
    // A site directory that turns security on with the trusted files (robot_link --site DIR).
    fs::create_directories(root_ / "site");
    std::ofstream(root_ / "site" / "dds.yaml")
        << "security:\n  enabled: true\n  directory: " << (root_ / "trusted").string() << "\n";
  }
  static void TearDownTestSuite() { fs::remove_all(root_); }

  static dds::ParticipantOptions trusted(int domain, const std::string& identity) {
    return {.domain_id = domain, .name = "dds_security_test/" + identity,
            .security = {.enabled = true, .directory = (root_ / "trusted").string()}, .identity = identity};
  }
  static dds::ParticipantOptions foreign(int domain, const std::string& identity) {
    return {.domain_id = domain, .name = "dds_security_test/foreign-" + identity,
            .security = {.enabled = true, .directory = (root_ / "foreign").string()}, .identity = identity};
  }
  static dds::ParticipantOptions unauthenticated(int domain) {
    return {.domain_id = domain, .name = "dds_security_test/unauthenticated"};
  }
  static dds::Participant create(const dds::ParticipantOptions& options) {
    auto participant = dds::Participant::create(options);
    if (!participant) throw std::runtime_error(participant.error().message);
    return std::move(*participant);
  }
  static std::string site() { return (root_ / "site").string(); }

  static inline fs::path root_;
};

template <typename T>
T value_of(Result<T> result) {
  if (!result) throw std::runtime_error(result.error().message);
  return std::move(*result);
}

/// Stands in for the simulator's blue port: robot_link's RobotControl datagrams.
class SimStandIn {
 public:
  explicit SimStandIn(int port) : socket_(value_of(net::UdpSocket::open("127.0.0.1", port))) {}

  /// Robot 0's command in the next datagram that has one; nullopt when none arrives within `timeout`.
  std::optional<::RobotCommand> next_robot0(milliseconds timeout) {
    const auto deadline = SteadyClock::now() + timeout;
    while (SteadyClock::now() < deadline) {
      const auto result = socket_.receive(buffer_, milliseconds(100));
      if (!result.ok()) continue;
      auto control = league::decode_robot_control(std::span(buffer_).first(result.size));
      if (!control) continue;
      for (const ::RobotCommand& command : control->robot_commands()) {
        if (command.id() == 0) return command;
      }
    }
    return std::nullopt;
  }

  /// Receives until robot 0's command satisfies `predicate`; false after `timeout`.
  template <typename Predicate>
  bool wait_for(Predicate predicate, milliseconds timeout) {
    const auto deadline = SteadyClock::now() + timeout;
    while (SteadyClock::now() < deadline) {
      auto command = next_robot0(milliseconds(200));
      if (command && predicate(*command)) return true;
    }
    return false;
  }

  /// How many of robot 0's commands within `duration` satisfy `predicate`.
  template <typename Predicate>
  int count_for(Predicate predicate, milliseconds duration) {
    const auto deadline = SteadyClock::now() + duration;
    int count = 0;
    while (SteadyClock::now() < deadline) {
      auto command = next_robot0(milliseconds(100));
      if (command && predicate(*command)) ++count;
    }
    return count;
  }

 private:
  net::UdpSocket socket_;
  std::array<std::uint8_t, 65536> buffer_{};
};

double forward(const ::RobotCommand& c) { return c.move_command().local_velocity().forward(); }
double left(const ::RobotCommand& c) { return c.move_command().local_velocity().left(); }
bool moving(const ::RobotCommand& c) { return std::abs(forward(c)) > 1e-3 || std::abs(left(c)) > 1e-3; }
bool stopped(const ::RobotCommand& c) { return c.move_command().has_local_velocity() && !moving(c); }

/// Robot 0 forward (legit planner) or sideways (intruders: any sideways speed is theirs).
idl::robot::RobotCommands drive(bool sideways) {
  idl::robot::RobotCommands sample;
  sample.team(idl::common::TEAM_COLOR_BLUE);
  idl::robot::RobotCommand command;
  command.id(0);
  (sideways ? command.left(1.0) : command.forward(1.0));
  sample.commands({command});
  return sample;
}

idl::system::Estop estop(bool engaged, const std::string& source) {
  idl::system::Estop sample;
  sample.engaged(engaged);
  sample.source(source);
  sample.reason("dds_security_test");
  return sample;
}

/// Writes `sample` every 20 ms on a thread until destroyed.
template <typename T>
class Repeater {
 public:
  Repeater(dds::Writer<T>& writer, T sample)
      : thread_([this, &writer, sample = std::move(sample)] {
          while (!stop_) {
            (void)writer.write(sample);
            std::this_thread::sleep_for(milliseconds(20));
          }
        }) {}
  ~Repeater() {
    stop_ = true;
    thread_.join();
  }

 private:
  std::atomic<bool> stop_{false};
  std::thread thread_;
};

std::string output_of(ChildProcess& child) {
  std::string text;
  while (auto line = child.read_line(milliseconds(200))) text += *line + "\n";
  return text + child.drain_stderr();
}

/// The real robot_link of the blue team with security on, its simulator stand-in, and our planner's
/// robot.commands writer (as the identity `blue`), matched with robot_link's reader once `matched()`.
struct SecureRobotLink {
  SecureRobotLink(int domain, int sim_port, const dds::ParticipantOptions& planner_options, const std::string& site)
      : sim(sim_port),
        process(value_of(ChildProcess::start(
            bin_dir() / "robot_link",
            {"--team", "blue", "--domain", std::to_string(domain), "--site", site, "--backend", "sim", "--sim-host",
             "127.0.0.1", "--sim-port", std::to_string(sim_port), "--interface", "127.0.0.1"}))),
        planner(value_of(dds::Participant::create(planner_options))),
        commands(value_of(planner.make_writer(dds::topics::kRobotCommands, TeamColor::kBlue))) {}

  bool matched() { return commands.wait_for_match(1, kMatchTimeout); }

  SimStandIn sim;
  ChildProcess process;
  dds::Participant planner;
  dds::Writer<idl::robot::RobotCommands> commands;
};

TEST_F(DdsSecurityTest, TheOtherTeamsIdentityMayNotEvenCreateEndpointsInOurPartition) {
  constexpr int kDomain = 173;
  for (const std::string identity : {"yellow", "yellow-operator"}) {
    auto yellow = create(trusted(kDomain, identity));
    EXPECT_FALSE(yellow.make_writer(dds::topics::kRobotCommands, TeamColor::kBlue)) << identity;
    EXPECT_FALSE(yellow.make_reader(dds::topics::kWorldState, TeamColor::kBlue)) << identity;
    EXPECT_FALSE(yellow.make_reader(dds::topics::kPlannerDebug, TeamColor::kBlue)) << identity;
    EXPECT_FALSE(yellow.make_writer(dds::topics::kSystemEstop, TeamColor::kBlue)) << identity;
    EXPECT_FALSE(yellow.make_writer(dds::topics::kSystemEstop)) << identity << ": the e-stop of every team";
    // Its own partition is allowed: the denials above are about the partition, not the topic.
    EXPECT_TRUE(yellow.make_writer(dds::topics::kSystemEstop, TeamColor::kYellow)) << identity;
    EXPECT_TRUE(yellow.make_reader(dds::topics::kWorldState, TeamColor::kYellow)) << identity;
  }
}

TEST_F(DdsSecurityTest, OurWorldStateAndPlannerDebugReachOurReaderButNoIntruder) {
  constexpr int kDomain = 174;
  auto ours = create(trusted(kDomain, "blue"));
  auto world_writer = value_of(ours.make_writer(dds::topics::kWorldState, TeamColor::kBlue));
  auto debug_writer = value_of(ours.make_writer(dds::topics::kPlannerDebug, TeamColor::kBlue));
  auto operator_participant = create(trusted(kDomain, "blue-operator"));
  auto legit_world = value_of(operator_participant.make_reader(dds::topics::kWorldState, TeamColor::kBlue));
  auto legit_debug = value_of(operator_participant.make_reader(dds::topics::kPlannerDebug, TeamColor::kBlue));

  // Intruders that can ask for our partition: no security at all, and our team's name under a foreign CA.
  auto stranger = create(unauthenticated(kDomain));
  auto impostor = create(foreign(kDomain, "blue-operator"));
  std::vector<dds::Reader<idl::world::WorldState>> world_intruders;
  std::vector<dds::Reader<idl::planner::PlannerDebug>> debug_intruders;
  for (dds::Participant* intruder : {&stranger, &impostor}) {
    world_intruders.push_back(value_of(intruder->make_reader(dds::topics::kWorldState, TeamColor::kBlue)));
    debug_intruders.push_back(value_of(intruder->make_reader(dds::topics::kPlannerDebug, TeamColor::kBlue)));
  }
  // The other team's identity reads only its own partition (it may not create a reader in ours).
  auto yellow = create(trusted(kDomain, "yellow"));
  world_intruders.push_back(value_of(yellow.make_reader(dds::topics::kWorldState, TeamColor::kYellow)));
  debug_intruders.push_back(value_of(yellow.make_reader(dds::topics::kPlannerDebug, TeamColor::kYellow)));

  ASSERT_TRUE(legit_world.wait_for_match(1, kMatchTimeout));
  ASSERT_TRUE(legit_debug.wait_for_match(1, kMatchTimeout));
  idl::world::WorldState world;
  world.team(idl::common::TEAM_COLOR_BLUE);
  idl::planner::PlannerDebug debug;
  debug.play("secret play");
  Repeater world_repeater(world_writer, world);
  Repeater debug_repeater(debug_writer, debug);
  ASSERT_TRUE(legit_world.wait_for_data(kMatchTimeout));
  ASSERT_TRUE(legit_debug.wait_for_data(kMatchTimeout));
  std::this_thread::sleep_for(kIntruderWindow);  // the bounded time the intruders get, after legit data

  EXPECT_GT(legit_world.take().size(), 0u);
  EXPECT_GT(legit_debug.take().size(), 0u);
  for (auto& reader : world_intruders) {
    EXPECT_EQ(reader.counters().matched_writers, 0u);
    EXPECT_TRUE(reader.take().empty());
  }
  for (auto& reader : debug_intruders) {
    EXPECT_EQ(reader.counters().matched_writers, 0u);
    EXPECT_TRUE(reader.take().empty());
  }
  // Only our own reader matched our writers.
  EXPECT_EQ(world_writer.counters().matched_readers, 1u);
  EXPECT_EQ(debug_writer.counters().matched_readers, 1u);
}

TEST_F(DdsSecurityTest, RobotLinkTakesRobotCommandsFromOurPlannerButNotFromIntruders) {
  constexpr int kDomain = 175;
  SecureRobotLink link(kDomain, 27311, trusted(kDomain, "blue"), site());
  ASSERT_TRUE(link.matched()) << output_of(link.process);
  SimStandIn& sim = link.sim;

  auto stranger = create(unauthenticated(kDomain));
  auto impostor = create(foreign(kDomain, "blue"));
  auto stranger_writer = value_of(stranger.make_writer(dds::topics::kRobotCommands, TeamColor::kBlue));
  auto impostor_writer = value_of(impostor.make_writer(dds::topics::kRobotCommands, TeamColor::kBlue));
  {
    Repeater from_stranger(stranger_writer, drive(/*sideways=*/true));
    Repeater from_impostor(impostor_writer, drive(/*sideways=*/true));
    // Robot 0 never moves sideways (robot_link sends stops at start and nothing after for unknown robots).
    EXPECT_EQ(sim.count_for([](const ::RobotCommand& c) { return std::abs(left(c)) > 1e-3; }, kIntruderWindow), 0);
  }
  EXPECT_EQ(stranger_writer.counters().matched_readers, 0u);
  EXPECT_EQ(impostor_writer.counters().matched_readers, 0u);

  // Our planner's commands do move it.
  Repeater from_planner(link.commands, drive(/*sideways=*/false));
  EXPECT_TRUE(sim.wait_for([](const ::RobotCommand& c) { return forward(c) > 0.5; }, milliseconds(10000)))
      << output_of(link.process);
}

TEST_F(DdsSecurityTest, OurOperatorReleasesOurEstopButNoIntruderDoes) {
  constexpr int kDomain = 176;
  SecureRobotLink link(kDomain, 27312, trusted(kDomain, "blue"), site());
  ASSERT_TRUE(link.matched()) << output_of(link.process);
  SimStandIn& sim = link.sim;
  Repeater from_planner(link.commands, drive(/*sideways=*/false));
  ASSERT_TRUE(sim.wait_for(moving, milliseconds(10000))) << output_of(link.process);

  // Our operator engages our e-stop: robot 0 stops although the planner keeps driving.
  auto our_operator = create(trusted(kDomain, "blue-operator"));
  auto our_estop = value_of(our_operator.make_writer(dds::topics::kSystemEstop, TeamColor::kBlue));
  ASSERT_TRUE(our_estop.wait_for_match(1, kMatchTimeout));
  ASSERT_TRUE(our_estop.write(estop(true, "our operator")));
  ASSERT_TRUE(sim.wait_for(stopped, milliseconds(5000)));

  // Intruders release it: addressed to every team, to our team under a foreign CA, to the other team.
  auto stranger = create(unauthenticated(kDomain));
  auto impostor = create(foreign(kDomain, "operator"));
  auto yellow_operator = create(trusted(kDomain, "yellow-operator"));
  auto stranger_release = value_of(stranger.make_writer(dds::topics::kSystemEstop));
  auto impostor_release = value_of(impostor.make_writer(dds::topics::kSystemEstop, TeamColor::kBlue));
  auto yellow_release = value_of(yellow_operator.make_writer(dds::topics::kSystemEstop, TeamColor::kYellow));
  {
    Repeater from_stranger(stranger_release, estop(false, "stranger"));
    Repeater from_impostor(impostor_release, estop(false, "impostor"));
    Repeater from_yellow(yellow_release, estop(false, "yellow operator"));
    EXPECT_EQ(sim.count_for(moving, kIntruderWindow), 0) << "an intruder released our e-stop";
  }
  EXPECT_EQ(stranger_release.counters().matched_readers, 0u);
  EXPECT_EQ(impostor_release.counters().matched_readers, 0u);
  EXPECT_EQ(yellow_release.counters().matched_readers, 0u);

  // Our operator's release does restore the planner's commands.
  ASSERT_TRUE(our_estop.write(estop(false, "our operator")));
  EXPECT_TRUE(sim.wait_for(moving, milliseconds(5000))) << output_of(link.process);
}

}  // namespace
}  // namespace ssl::testing
