#include "services/referee_gateway/core/gateway.h"

#include <utility>

namespace ssl::referee {

RefereeGateway::RefereeGateway(GatewayOptions options) : options_(std::move(options)) {
  if (options_.source_identifier) chosen_ = options_.source_identifier;
}

bool RefereeGateway::accept_source(const std::string& source, time::Timestamp now, StepOutput& out) {
  if (options_.source_identifier) return source == *options_.source_identifier;
  if (!chosen_) {
    chosen_ = source;
    return true;
  }
  if (source == *chosen_) return true;
  const bool chosen_silent = !last_accepted_ || now - *last_accepted_ >= options_.source_switch_after;
  if (!chosen_silent) return false;
  out.switched_from = *chosen_;
  chosen_ = source;
  last_counter_.reset();
  ++counters_.source_switches;
  return true;
}

void RefereeGateway::remember(std::string key) {
  if (options_.remembered_events == 0) return;
  while (seen_order_.size() >= options_.remembered_events) {
    seen_events_.erase(seen_order_.front());
    seen_order_.pop_front();
  }
  seen_order_.push_back(key);
  seen_events_.insert(std::move(key));
}

void RefereeGateway::collect_new_events(const RefereeState& packet, StepOutput& out) {
  for (const GameEvent& event : packet.game_events) {
    std::string key = event_key(event);
    if (seen_events_.contains(key)) continue;
    remember(std::move(key));
    out.events.push_back({.event = event,
                          .command = packet.command,
                          .command_counter = packet.command_counter,
                          .receive_wall = packet.receive_wall});
  }
  counters_.events_published += out.events.size();
}

StepOutput RefereeGateway::on_packet(RefereeState packet, time::Timestamp now) {
  StepOutput out;
  ++counters_.packets;
  if (!accept_source(packet.source_identifier, now, out)) {
    ++counters_.foreign_source;
    last_foreign_ = packet.source_identifier;
    out.verdict = PacketVerdict::kForeignSource;
    return out;
  }
  ++counters_.accepted;
  last_accepted_ = now;

  if (last_counter_ && packet.command_counter != *last_counter_ &&
      packet.command_counter != static_cast<std::uint32_t>(*last_counter_ + 1u)) {
    out.counter_jump = CounterJump{.from = *last_counter_, .to = packet.command_counter};
    ++counters_.counter_jumps;
  }
  last_counter_ = packet.command_counter;

  collect_new_events(packet, out);

  if (!published_) {
    out.reason = PublishReason::kFirst;
  } else if (!same_meaning(*published_, packet)) {
    out.reason = PublishReason::kChange;
  } else if (now - published_at_ >= options_.heartbeat_period) {
    out.reason = PublishReason::kHeartbeat;
    ++counters_.heartbeats;
  }
  if (out.reason != PublishReason::kNone) {
    ++counters_.states_published;
    published_at_ = now;
    published_ = packet;
    out.state = std::move(packet);
  }
  return out;
}

Liveness RefereeGateway::liveness(time::Timestamp now) const {
  if (!last_accepted_) return {.stale = true, .age = std::nullopt};
  const time::Duration age = now - *last_accepted_;
  return {.stale = age > options_.stale_after, .age = age};
}

}  // namespace ssl::referee
