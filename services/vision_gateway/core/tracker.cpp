#include "services/vision_gateway/core/tracker.h"

namespace ssl::vision_gateway {

namespace {
/// A misbehaving sender that changes its uuid every packet must not grow memory without bound.
constexpr std::size_t kMaxRememberedSources = 64;
}  // namespace

void TrackerMonitor::on_packet(const TrackerPacket& packet, const ReceiveTime& received) {
  ++counters_.packets;
  if (packet.frame_number) ++counters_.frames;
  if (!uuids_.contains(packet.uuid)) {
    ++counters_.sources;
    if (uuids_.size() < kMaxRememberedSources) uuids_.insert(packet.uuid);
  }
  last_source_ = packet.source_name && !packet.source_name->empty() ? *packet.source_name : packet.uuid;
  last_monotonic_ = received.monotonic;
}

std::optional<time::Duration> TrackerMonitor::age(time::Timestamp now_monotonic) const {
  if (!last_monotonic_) return std::nullopt;
  return now_monotonic - *last_monotonic_;
}

}  // namespace ssl::vision_gateway
