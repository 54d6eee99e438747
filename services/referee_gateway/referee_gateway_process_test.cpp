// referee_gateway as a process, as it runs at a match: Referee packets multicast on loopback (like the
// Game Controller, about every 25 ms) in; referee.state, referee.event and system.health read back over
// DDS and through `sslctl topic echo`; and the built-in referee. Each test has its own DDS domain (181-187)
// and referee port (24181-24187). Nothing sleeps to wait for discovery: readers wait for matched writers or data, bounded.
#include <gtest/gtest.h>
#include <signal.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <functional>
#include <nlohmann/json.hpp>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "libs/dds/participant.h"
#include "libs/league/decode.h"
#include "libs/net/multicast.h"
#include "services/referee_gateway/testing/referee_packets.h"
#include "tests/support/process.h"

namespace ssl::referee {
namespace {

using namespace std::chrono_literals;
using Clock = std::chrono::steady_clock;
using referee::testing::encode;
using referee::testing::game_event;
using referee::testing::referee_packet;
using ssl::testing::ChildProcess;
namespace idl = ::ssl::idl;

constexpr auto kTimeout = 20s;

ChildProcess start_gateway(int port, int domain, const std::vector<std::string>& extra = {}) {
  std::vector<std::string> args = {
      "--referee-port", std::to_string(port), "--domain",    std::to_string(domain),
      "--interface",    "127.0.0.1",          "--log-level", "warn"};
  args.insert(args.end(), extra.begin(), extra.end());
  auto child = ChildProcess::start(ssl::testing::bin_dir() / "referee_gateway", args);
  EXPECT_TRUE(child) << child.error().message;
  return std::move(child).value();
}

template <typename T>
T value_of(Result<T> result) {
  if (!result) throw std::runtime_error(result.error().message);  // fails the test with the message
  return std::move(result).value();
}

/// The test's side of DDS: a participant with readers on the gateway's topics.
///
/// CAUTION: a referee.state reader reserves about 27 GB of virtual memory (Fast DDS preallocates samples
/// of the type's maximum size, and referee.idl's nested unbounded sequences take the default bound of 100
/// each: 269 MB per sample). Under the kernel's default overcommit heuristic a process holding one can no
/// longer fork(): start child processes before creating it (`referee_readers = false`).
struct Observer {
  explicit Observer(int domain, bool referee_readers = true)
      : participant(
            value_of(dds::Participant::create({.domain_id = domain, .name = "referee_gateway_test"}))) {
    if (referee_readers) {
      state.emplace(value_of(participant->make_reader(dds::topics::kRefereeState)));
      event.emplace(value_of(participant->make_reader(dds::topics::kRefereeEvent)));
    }
    health.emplace(value_of(participant->make_reader(dds::topics::kSystemHealth)));
  }

  /// The gateway's writers exist once it is set up (its receiver is joined before they are created).
  bool wait_for_gateway() { return state->wait_for_match(1, kTimeout) && event->wait_for_match(1, kTimeout); }

  std::optional<dds::Participant> participant;
  std::optional<dds::Reader<idl::referee::RefereeState>> state;
  std::optional<dds::Reader<idl::referee::RefereeEvent>> event;
  std::optional<dds::Reader<idl::system::Health>> health;
};

net::MulticastSender open_sender(int port) {
  auto sender = net::MulticastSender::open("224.5.23.1", port, "127.0.0.1");
  EXPECT_TRUE(sender) << sender.error().message;
  return std::move(*sender);
}

/// Sends `bytes` every 25 ms, as the Game Controller does, until a referee.state sample satisfies
/// `accept` (returned) or the timeout passes (nullopt).
std::optional<idl::referee::RefereeState> send_until_state(
    net::MulticastSender& sender, const std::string& bytes, Observer& observer,
    const std::function<bool(const idl::referee::RefereeState&)>& accept) {
  const auto deadline = Clock::now() + kTimeout;
  while (Clock::now() < deadline) {
    EXPECT_TRUE(sender.send(league::byte_span(bytes)).ok());
    if (!observer.state->wait_for_data(25ms)) continue;
    for (auto& sample : observer.state->take()) {
      if (accept(sample.data)) return sample.data;
    }
  }
  return std::nullopt;
}

/// Reads system.health until a "referee_gateway" sample satisfies `accept`, optionally sending `bytes`
/// every 25 ms meanwhile (keeps the referee fresh).
std::optional<idl::system::Health> wait_for_health(
    Observer& observer, const std::function<bool(const idl::system::Health&)>& accept,
    net::MulticastSender* sender = nullptr, const std::string& bytes = {}) {
  const auto deadline = Clock::now() + kTimeout;
  while (Clock::now() < deadline) {
    if (sender != nullptr) {
      EXPECT_TRUE(sender->send(league::byte_span(bytes)).ok());
    }
    if (!observer.health->wait_for_data(25ms)) continue;
    for (auto& sample : observer.health->take()) {
      if (sample.data.service() == "referee_gateway" && accept(sample.data)) return sample.data;
    }
  }
  return std::nullopt;
}

std::uint64_t counter(const idl::system::Health& health, const std::string& name) {
  for (const auto& c : health.counters()) {
    if (c.name() == name) return c.value();
  }
  ADD_FAILURE() << "no health counter '" << name << "'";
  return 0;
}

void stop(ChildProcess& gateway) {
  gateway.signal(SIGTERM);
  EXPECT_EQ(gateway.wait(kTimeout), 0) << gateway.drain_stderr();
}

TEST(RefereeGatewayProcess, StateAndEachGameEventOnceFlowFromMulticastToDds) {
  constexpr int kDomain = 181;
  constexpr int kPort = 24181;
  auto gateway = start_gateway(kPort, kDomain);
  Observer observer(kDomain);
  ASSERT_TRUE(observer.wait_for_gateway()) << gateway.drain_stderr();
  // referee.event is volatile: an event written before the gateway's writer matched our reader would be
  // lost by design. The gateway's health says when its writers see our readers.
  ASSERT_TRUE(wait_for_health(observer, [](const auto& h) {
    return counter(h, "event_readers") >= 1 && counter(h, "state_readers") >= 1;
  })) << gateway.drain_stderr();
  auto sender = open_sender(kPort);

  ::Referee placement = referee_packet(::Referee::BALL_PLACEMENT_BLUE, 3);
  placement.mutable_designated_position()->set_x(1500.0f);  // mm
  placement.mutable_designated_position()->set_y(-250.0f);
  placement.set_next_command(::Referee::DIRECT_FREE_BLUE);
  placement.set_stage_time_left(-7'000'000'000ll);  // µs, 64-bit, negative
  placement.set_status_message("placement");
  *placement.add_game_events() = game_event(
      R"(id: "ev-1" ball_left_field_goal_line { by_team: YELLOW by_bot: 2 location { x: -6 y: 1.5 } })");
  const auto state = send_until_state(sender, encode(placement), observer, [](const auto& s) {
    return s.command() == idl::referee::COMMAND_BALL_PLACEMENT_BLUE;
  });
  ASSERT_TRUE(state) << gateway.drain_stderr();
  EXPECT_EQ(state->command_counter(), 3u);
  EXPECT_EQ(state->source_identifier(), "gc-1");
  EXPECT_TRUE(state->has_designated_position());
  EXPECT_DOUBLE_EQ(state->designated_position().x(), 1.5);  // m
  EXPECT_DOUBLE_EQ(state->designated_position().y(), -0.25);
  EXPECT_TRUE(state->has_next_command());
  EXPECT_EQ(state->next_command(), idl::referee::COMMAND_DIRECT_FREE_BLUE);
  EXPECT_DOUBLE_EQ(state->stage_time_left(), -7000.0);
  EXPECT_EQ(state->status_message(), "placement");
  ASSERT_EQ(state->game_events().size(), 1u);
  EXPECT_EQ(state->game_events()[0].type(), idl::referee::GAME_EVENT_BALL_LEFT_FIELD_GOAL_LINE);
  EXPECT_GT(state->receive_unix_ns(), 0);

  // The Game Controller repeats the state; then the command changes (a deprecated GOAL_* packet, too).
  const std::string repeated = encode(placement);
  for (int i = 0; i < 20; ++i) ASSERT_TRUE(sender.send(league::byte_span(repeated)).ok());
  const auto goal =
      send_until_state(sender, encode(referee_packet(::Referee::GOAL_BLUE, 4)), observer,
                       [](const auto& s) { return s.command() == idl::referee::COMMAND_GOAL_BLUE; });
  ASSERT_TRUE(goal) << gateway.drain_stderr();
  const auto start =
      send_until_state(sender, encode(referee_packet(::Referee::FORCE_START, 5)), observer,
                       [](const auto& s) { return s.command() == idl::referee::COMMAND_FORCE_START; });
  ASSERT_TRUE(start) << gateway.drain_stderr();
  EXPECT_FALSE(start->has_designated_position());
  EXPECT_TRUE(start->game_events().empty());

  // Exactly one event, although its packet was sent many times.
  std::vector<idl::referee::RefereeEvent> events;
  while (observer.event->wait_for_data(500ms)) {
    for (auto& sample : observer.event->take()) events.push_back(sample.data);
  }
  ASSERT_EQ(events.size(), 1u);
  EXPECT_EQ(events[0].event().id(), "ev-1");
  EXPECT_EQ(events[0].event().type(), idl::referee::GAME_EVENT_BALL_LEFT_FIELD_GOAL_LINE);
  EXPECT_EQ(events[0].event().by_team(), idl::common::TEAM_COLOR_YELLOW);
  EXPECT_EQ(events[0].event().by_bot(), 2u);
  EXPECT_DOUBLE_EQ(events[0].event().location().x(), -6.0);
  EXPECT_EQ(events[0].command(), idl::referee::COMMAND_BALL_PLACEMENT_BLUE);
  EXPECT_EQ(events[0].command_counter(), 3u);
  stop(gateway);
}

TEST(RefereeGatewayProcess, LateJoiningReadersGetTheLastState) {
  constexpr int kDomain = 182;
  constexpr int kPort = 24182;
  auto gateway = start_gateway(kPort, kDomain);
  Observer observer(kDomain, /*referee_readers=*/false);  // sslctl is forked below (see Observer)
  auto sender = open_sender(kPort);
  ::Referee kickoff = referee_packet(::Referee::PREPARE_KICKOFF_YELLOW, 9);
  kickoff.set_status_message("kickoff yellow");
  const std::string bytes = encode(kickoff);
  ASSERT_TRUE(wait_for_health(
      observer, [](const auto& h) { return counter(h, "states_published") >= 1; }, &sender, bytes))
      << gateway.drain_stderr();

  // The referee goes quiet; readers that join now still get the last state (transient local).
  auto echo = ChildProcess::start(
      ssl::testing::bin_dir() / "sslctl",
      {"topic", "echo", "referee.state", "--count", "1", "--domain", std::to_string(kDomain), "--timeout",
       "20"});
  ASSERT_TRUE(echo) << echo.error().message;
  const auto line = echo->read_line(kTimeout);
  ASSERT_TRUE(line) << echo->drain_stderr();
  const auto json = nlohmann::json::parse(*line);
  EXPECT_EQ(json["command"], "COMMAND_PREPARE_KICKOFF_YELLOW");
  EXPECT_EQ(json["command_counter"], 9);
  EXPECT_EQ(json["status_message"], "kickoff yellow");
  EXPECT_EQ(json["yellow"]["name"], "yellow");
  EXPECT_EQ(echo->wait(kTimeout), 0);

  auto late = observer.participant->make_reader(dds::topics::kRefereeState);
  ASSERT_TRUE(late);
  ASSERT_TRUE(late->wait_for_data(kTimeout));
  const auto latest = late->take_latest();
  ASSERT_TRUE(latest);
  EXPECT_EQ(latest->data.command(), idl::referee::COMMAND_PREPARE_KICKOFF_YELLOW);
  EXPECT_EQ(latest->data.command_counter(), 9u);
  EXPECT_EQ(latest->data.status_message(), "kickoff yellow");
  stop(gateway);
}

TEST(RefereeGatewayProcess, GarbageIsCountedAndTheGatewayKeepsWorking) {
  constexpr int kDomain = 183;
  constexpr int kPort = 24183;
  auto gateway = start_gateway(kPort, kDomain);
  Observer observer(kDomain);
  ASSERT_TRUE(observer.wait_for_gateway()) << gateway.drain_stderr();
  auto sender = open_sender(kPort);

  constexpr int kGarbage = 40;
  const std::string whole = encode(referee_packet(::Referee::STOP, 1));
  for (int i = 0; i < kGarbage; ++i) {
    const std::string garbage = i % 2 == 0
                                    ? std::string(static_cast<std::size_t>(i + 1), static_cast<char>(0xff))
                                    : whole.substr(0, static_cast<std::size_t>(i) % whole.size());
    ASSERT_TRUE(sender.send(league::byte_span(garbage)).ok());
  }
  const auto state =
      send_until_state(sender, encode(referee_packet(::Referee::STOP, 2)), observer,
                       [](const auto& s) { return s.command() == idl::referee::COMMAND_STOP; });
  ASSERT_TRUE(state) << gateway.drain_stderr();
  EXPECT_EQ(state->command_counter(), 2u);

  const std::string valid = encode(referee_packet(::Referee::STOP, 2));
  const auto health = wait_for_health(
      observer, [](const auto& h) { return h.level() == idl::system::HEALTH_OK; }, &sender, valid);
  ASSERT_TRUE(health) << gateway.drain_stderr();
  EXPECT_EQ(counter(*health, "malformed"), static_cast<std::uint64_t>(kGarbage));
  EXPECT_GE(counter(*health, "packets"), static_cast<std::uint64_t>(kGarbage) + 1);
  EXPECT_GE(health->dropped(), static_cast<std::uint64_t>(kGarbage));
  EXPECT_GE(counter(*health, "states_published"), 1u);
  EXPECT_EQ(counter(*health, "foreign_source"), 0u);
  stop(gateway);
}

TEST(RefereeGatewayProcess, AStrayGameControllerIsCountedAndIgnored) {
  constexpr int kDomain = 184;
  constexpr int kPort = 24184;
  auto gateway = start_gateway(kPort, kDomain);
  Observer observer(kDomain);
  ASSERT_TRUE(observer.wait_for_gateway()) << gateway.drain_stderr();
  auto sender = open_sender(kPort);
  const std::string main_gc = encode(referee_packet(::Referee::HALT, 1, "gc-main"));
  ASSERT_TRUE(send_until_state(sender, main_gc, observer, [](const auto& s) {
    return s.source_identifier() == "gc-main";
  })) << gateway.drain_stderr();

  const std::string stray = encode(referee_packet(::Referee::FORCE_START, 77, "gc-stray"));
  const auto health = wait_for_health(
      observer,
      [](const auto& h) {
        for (const auto& c : h.counters()) {
          if (c.name() == "foreign_source" && c.value() >= 10) return true;
        }
        return false;
      },
      &sender, stray);
  ASSERT_TRUE(health) << gateway.drain_stderr();
  // Keep the main one alive a little; the stray one never reaches referee.state.
  for (int i = 0; i < 10; ++i) ASSERT_TRUE(sender.send(league::byte_span(main_gc)).ok());
  while (observer.state->wait_for_data(300ms)) {
    for (auto& sample : observer.state->take()) EXPECT_EQ(sample.data.source_identifier(), "gc-main");
  }
  stop(gateway);
}

TEST(RefereeGatewayProcess, AStaleRefereeTurnsHealthToWarnWithItsAge) {
  constexpr int kDomain = 185;
  constexpr int kPort = 24185;
  auto gateway = start_gateway(kPort, kDomain, {"--set", "stale_after=0.3"});
  Observer observer(kDomain);
  ASSERT_TRUE(observer.wait_for_gateway()) << gateway.drain_stderr();
  auto sender = open_sender(kPort);

  const auto before =
      wait_for_health(observer, [](const auto& h) { return h.level() == idl::system::HEALTH_WARN; });
  ASSERT_TRUE(before) << gateway.drain_stderr();
  EXPECT_NE(before->status().find("no referee packet yet"), std::string::npos) << before->status();

  const std::string stop_packet = encode(referee_packet(::Referee::STOP, 1));
  const auto alive = wait_for_health(
      observer, [](const auto& h) { return h.level() == idl::system::HEALTH_OK; }, &sender, stop_packet);
  ASSERT_TRUE(alive) << gateway.drain_stderr();
  EXPECT_GT(alive->rate_hz(), 0.0);

  // The referee goes quiet.
  const auto stale =
      wait_for_health(observer, [](const auto& h) { return h.level() == idl::system::HEALTH_WARN; });
  ASSERT_TRUE(stale) << gateway.drain_stderr();
  EXPECT_NE(stale->status().find("stale: no referee packet for"), std::string::npos) << stale->status();
  EXPECT_GE(counter(*stale, "referee_age_ms"), 300u);
  stop(gateway);
}

// The built-in referee as it runs in `./ssl up`: arcade profile, vision.detection and referee.command in
// (this test writes them over DDS), league Referee packets out on the referee group, which the same
// process's gateway turns into referee.state. A ball rolled into the positive-x goal (yellow's: blue
// defends negative x) scores for blue; arcade restarts with FORCE_START after its 2 s STOP by itself.
TEST(RefereeGatewayProcess, TheBuiltinRefereeScoresAGoalSeenInVisionAndSendsLeaguePackets) {
  constexpr int kDomain = 187;
  constexpr int kPort = 24187;
  auto gateway = start_gateway(kPort, kDomain, {"--source", "builtin", "--profile", "arcade"});
  auto packets = net::MulticastReceiver::open("224.5.23.1", kPort, "127.0.0.1");
  ASSERT_TRUE(packets) << packets.error().message;
  Observer observer(kDomain);
  auto vision = value_of(observer.participant->make_writer(dds::topics::kVisionDetection));
  auto operator_commands = value_of(observer.participant->make_writer(dds::topics::kRefereeCommand));
  ASSERT_TRUE(observer.wait_for_gateway());
  ASSERT_TRUE(vision.wait_for_match(1, kTimeout));
  ASSERT_TRUE(operator_commands.wait_for_match(1, kTimeout));

  // The newest referee.state satisfying `accept` while vision frames with the ball at ball(t) go out
  // every 10 ms (t: seconds since the call).
  auto state_while_seeing = [&](const std::function<Vec2(double)>& ball,
                                const std::function<bool(const idl::referee::RefereeState&)>& accept)
      -> std::optional<idl::referee::RefereeState> {
    const auto start = Clock::now();
    std::uint32_t frame_number = 0;
    while (Clock::now() < start + kTimeout) {
      const double t = std::chrono::duration<double>(Clock::now() - start).count();
      idl::vision::DetectionFrame frame;
      frame.camera_id(0);
      frame.frame_number(++frame_number);
      const std::int64_t now_ns = std::chrono::duration_cast<std::chrono::nanoseconds>(
                                      std::chrono::system_clock::now().time_since_epoch())
                                      .count();
      frame.capture_unix_ns(now_ns);
      frame.receive_unix_ns(now_ns);
      idl::vision::BallDetection detection;
      detection.x(ball(t).x());
      detection.y(ball(t).y());
      detection.confidence(0.9F);
      frame.balls().push_back(detection);
      EXPECT_TRUE(vision.write(frame));
      if (!observer.state->wait_for_data(10ms)) continue;
      for (auto& sample : observer.state->take()) {
        if (accept(sample.data)) return sample.data;
      }
    }
    return std::nullopt;
  };
  auto at_centre = [](double) { return Vec2(0, 0); };

  idl::referee::RefereeOperatorCommand force_start;
  force_start.command(idl::referee::COMMAND_FORCE_START);
  force_start.author("test");
  ASSERT_TRUE(operator_commands.write(force_start));
  const auto running = state_while_seeing(at_centre, [](const auto& s) {
    return s.command() == idl::referee::COMMAND_FORCE_START;
  });
  ASSERT_TRUE(running) << "the operator's FORCE_START never arrived";
  EXPECT_EQ(running->source(), idl::referee::REFEREE_SOURCE_BUILTIN);
  EXPECT_EQ(running->stage(), idl::referee::STAGE_NORMAL_FIRST_HALF);

  // Rolled from the centre into the positive-x goal at 3 m/s (division B: goal line at x = 4.5 m).
  auto into_the_goal = [](double t) { return Vec2(std::min(3.0 * t, 4.6), 0.1); };
  const auto goal = state_while_seeing(into_the_goal, [](const auto& s) { return s.blue().score() == 1; });
  ASSERT_TRUE(goal) << "no goal";
  // arcade: the conceding team places the ball on the centre mark, then the game goes on.
  EXPECT_EQ(goal->command(), idl::referee::COMMAND_BALL_PLACEMENT_YELLOW);
  ASSERT_TRUE(goal->has_designated_position());
  EXPECT_EQ(goal->designated_position().x(), 0.0);
  EXPECT_EQ(goal->designated_position().y(), 0.0);
  EXPECT_EQ(goal->yellow().score(), 0u);
  ASSERT_TRUE(goal->has_next_command());
  EXPECT_EQ(goal->next_command(), idl::referee::COMMAND_FORCE_START);
  const auto restarted = state_while_seeing(at_centre, [&](const auto& s) {
    return s.command() == idl::referee::COMMAND_FORCE_START && s.command_counter() > goal->command_counter();
  });
  ASSERT_TRUE(restarted) << "arcade did not restart after the goal";
  EXPECT_EQ(restarted->blue().score(), 1u);

  // What went over the wire are league Referee packets other teams can read: every one decodes, and (the
  // socket has queued them since the start) one carries the restart after the goal.
  std::array<std::uint8_t, 65536> buffer{};
  std::optional<::Referee> restart_packet;
  std::size_t decoded_packets = 0;
  const auto deadline = Clock::now() + kTimeout;
  while (!restart_packet && Clock::now() < deadline) {
    const net::ReceiveResult received = packets->receive(buffer, 100ms);
    if (!received.ok()) continue;
    auto decoded = league::decode_referee({buffer.data(), received.size});
    ASSERT_TRUE(decoded) << decoded.error().message;
    ++decoded_packets;
    EXPECT_EQ(decoded->source_identifier(), "builtin:arcade");
    if (decoded->blue().score() == 1 && decoded->command() == ::Referee::FORCE_START) restart_packet = *decoded;
  }
  ASSERT_TRUE(restart_packet) << "no restart packet among " << decoded_packets << " on 224.5.23.1:" << kPort;
  EXPECT_EQ(restart_packet->yellow().score(), 0u);
  EXPECT_EQ(restart_packet->stage(), ::Referee::NORMAL_FIRST_HALF);
  stop(gateway);
}

TEST(RefereeGatewayProcess, BadBuiltinRefereeUsageIsRefusedWithAClearMessage) {
  auto unknown = ChildProcess::start(ssl::testing::bin_dir() / "referee_gateway",
                                     {"--source", "builtin", "--profile", "no_such_profile", "--domain", "186"});
  ASSERT_TRUE(unknown);
  const auto line = unknown->read_line(kTimeout);
  EXPECT_EQ(unknown->wait(kTimeout), 1);
  ASSERT_TRUE(line) << unknown->drain_stderr();
  EXPECT_NE(line->find("no_such_profile"), std::string::npos) << *line;

  auto profile_only = ChildProcess::start(ssl::testing::bin_dir() / "referee_gateway",
                                          {"--profile", "strict_ai", "--domain", "186"});
  ASSERT_TRUE(profile_only);
  const auto profile_line = profile_only->read_line(kTimeout);
  EXPECT_EQ(profile_only->wait(kTimeout), 2);
  ASSERT_TRUE(profile_line);
  EXPECT_NE(profile_line->find("--source builtin"), std::string::npos) << *profile_line;

  auto help = ChildProcess::start(ssl::testing::bin_dir() / "referee_gateway", {"--help"});
  ASSERT_TRUE(help);
  std::string text;
  while (auto help_line = help->read_line(kTimeout)) text += *help_line + "\n";
  EXPECT_EQ(help->wait(kTimeout), 0);
  for (const char* flag :
       {"--config", "--domain", "--interface", "--log-level", "--source", "--referee-port", "--profile"}) {
    EXPECT_NE(text.find(flag), std::string::npos) << flag << " missing from --help:\n" << text;
  }
}

}  // namespace
}  // namespace ssl::referee
