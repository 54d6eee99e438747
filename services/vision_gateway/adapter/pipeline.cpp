#include "services/vision_gateway/adapter/pipeline.h"

#include <utility>

namespace ssl::vision_gateway {

DatagramResult VisionPipeline::on_datagram(std::span<const std::uint8_t> bytes, const net::Endpoint& sender,
                                           const ReceiveTime& received) {
  DatagramResult result;
  Result<VisionPacket> packet = decoder_.decode(bytes);
  if (!packet) {
    ++malformed_;
    result.malformed = packet.error().message;
    return result;
  }
  result.output = gateway_.on_packet(std::move(*packet), sender, received);
  return result;
}

std::uint64_t LogThrottle::on_event(time::Timestamp now_monotonic) {
  ++pending_;
  if (last_logged_ && now_monotonic - *last_logged_ < interval_) return 0;
  last_logged_ = now_monotonic;
  return std::exchange(pending_, 0);
}

}  // namespace ssl::vision_gateway
