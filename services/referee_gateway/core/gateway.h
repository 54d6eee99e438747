// RefereeGateway: the pure decision logic between the Game Controller's Referee packets and the two
// referee topics. No DDS, no sockets, no threads, no clock: the caller passes each packet (already
// converted to SI, see types.h) and the current time of a MONOTONIC clock (`now`), and publishes what
// the step returns.
//
// Rules (config in GatewayOptions):
//  * Source selection. Several referees may multicast on one group (two Game Controllers, a stray one in
//    the next room). With a fixed `source_identifier` only that one is accepted. With auto (nullopt) the
//    first one seen is chosen, and another one is accepted only after the chosen one was silent for
//    `source_switch_after`. Packets of other sources are counted (foreign_source) and dropped.
//  * referee.state. A packet is published when it differs in meaning from the last published one
//    (same_meaning in types.h: game events, proposals, match type, status message and running clocks are
//    ignored), and otherwise once `heartbeat_period` has passed since the last publication. Nothing is
//    republished while no packets arrive (silence on referee.state means a silent referee).
//    Because referee.state is transient-local keep-last-1, the latest sample is what a late joiner gets:
//    every published sample is therefore the LATEST accepted packet in full, including its current game
//    events, proposals, match type and status message. A change of only those fields reaches the
//    state topic with the next heartbeat (at most `heartbeat_period` later); game events themselves are
//    never late, they go out on referee.event at once.
//  * referee.event. Every game event of an accepted packet that was not seen before (by id when the
//    referee gives one, otherwise by content, see event_key) is published once, with the command in
//    force. Identities of the last `remembered_events` events are kept. After a start every event the
//    referee still lists is new to us and is published once.
//  * Command counter. The Game Controller repeats its state about 40 times a second with the same
//    counter; that is normal. A counter that skips (not +1 mod 2^32) or goes backwards is a jump: counted
//    and returned so the adapter can report it (commands may have been missed). A source switch restarts
//    the tracking.
//  * Staleness. liveness(now) says how long ago the last accepted packet arrived; stale after
//    `stale_after` (and before the first packet).
//
//   RefereeGateway gateway({.heartbeat_period = 1s});
//   StepOutput out = gateway.on_packet(std::move(state), monotonic.now());
//   for (const auto& event : out.events) event_writer.write(to_idl(event));
//   if (out.state) state_writer.write(to_idl(*out.state));
#pragma once

#include <chrono>
#include <cstddef>
#include <cstdint>
#include <deque>
#include <optional>
#include <string>
#include <unordered_set>
#include <vector>

#include "libs/time/time.h"
#include "services/referee_gateway/core/types.h"

namespace ssl::referee {

struct GatewayOptions {
  std::optional<std::string> source_identifier;  // nullopt: auto (first seen, switch after silence)
  time::Duration source_switch_after = std::chrono::seconds(2);
  time::Duration heartbeat_period = std::chrono::seconds(1);
  time::Duration stale_after = std::chrono::seconds(1);
  std::size_t remembered_events = 1024;  // event identities kept for "publish once"
};

enum class PacketVerdict { kAccepted, kForeignSource };

enum class PublishReason { kNone, kFirst, kChange, kHeartbeat };

/// A command counter that did not stay or advance by one.
struct CounterJump {
  std::uint32_t from = 0;
  std::uint32_t to = 0;

  friend bool operator==(const CounterJump&, const CounterJump&) = default;
};

/// What one packet leads to.
struct StepOutput {
  PacketVerdict verdict = PacketVerdict::kAccepted;
  PublishReason reason = PublishReason::kNone;
  std::optional<RefereeState> state;  // publish on referee.state (set iff reason != kNone)
  std::vector<RefereeEvent> events;   // publish on referee.event, in the packet's order
  std::optional<CounterJump> counter_jump;
  std::optional<std::string> switched_from;  // set when this packet's source replaced a silent one
};

/// Everything the core counted since construction (the adapter adds malformed datagrams).
struct GatewayCounters {
  std::uint64_t packets = 0;          // decoded packets handed to on_packet
  std::uint64_t accepted = 0;         // from the chosen source
  std::uint64_t foreign_source = 0;   // from another source, dropped
  std::uint64_t source_switches = 0;  // the chosen source changed after silence
  std::uint64_t counter_jumps = 0;
  std::uint64_t states_published = 0;
  std::uint64_t heartbeats = 0;  // of states_published, those due to the heartbeat only
  std::uint64_t events_published = 0;
};

struct Liveness {
  bool stale = true;
  std::optional<time::Duration> age;  // since the last accepted packet; nullopt before the first
};

class RefereeGateway {
 public:
  explicit RefereeGateway(GatewayOptions options);

  /// Applies one packet received at monotonic time `now` (non-decreasing between calls).
  StepOutput on_packet(RefereeState packet, time::Timestamp now);

  Liveness liveness(time::Timestamp now) const;

  const GatewayCounters& counters() const noexcept { return counters_; }
  /// The source identifier currently followed; nullopt before the first packet in auto mode.
  const std::optional<std::string>& chosen_source() const noexcept { return chosen_; }
  /// The identifier of the last dropped foreign packet ("" when none).
  const std::string& last_foreign_source() const noexcept { return last_foreign_; }
  /// The last published state (nullopt before the first).
  const std::optional<RefereeState>& last_published() const noexcept { return published_; }
  const GatewayOptions& options() const noexcept { return options_; }

 private:
  bool accept_source(const std::string& source, time::Timestamp now, StepOutput& out);
  void collect_new_events(const RefereeState& packet, StepOutput& out);
  void remember(std::string key);

  GatewayOptions options_;
  GatewayCounters counters_;
  std::optional<std::string> chosen_;
  std::string last_foreign_;
  std::optional<time::Timestamp> last_accepted_;  // monotonic
  std::optional<std::uint32_t> last_counter_;
  std::optional<RefereeState> published_;
  time::Timestamp published_at_;  // monotonic
  std::unordered_set<std::string> seen_events_;
  std::deque<std::string> seen_order_;  // oldest first, for forgetting
};

}  // namespace ssl::referee
